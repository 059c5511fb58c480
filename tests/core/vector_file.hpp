// Reads the byte-exact vectors of another implementation (tests/data):
// "CODE  FIELD=VALUE;...  HEX", two spaces apart.
#pragma once

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace jaus::test {

struct Vector {
  std::string code;    // "4402"
  std::string fields;  // "_hdr=...;latitudeDegrees=41.6;..."
  std::string hex;     // header + payload
};

inline std::vector<Vector> read_vectors(const std::string& file) {
  // A path, not string concatenation: GCC 12 at -O2 reads the latter as
  // out of bounds (a false -Warray-bounds that -Werror makes fatal).
  std::ifstream in(std::filesystem::path(JAUS_TEST_DATA_DIR) / file);
  if (!in) throw std::runtime_error("cannot open test data " + file);
  std::vector<Vector> out;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    const auto first = line.find("  ");
    const auto last = line.rfind("  ");
    if (first == std::string::npos || last == first) throw std::runtime_error("bad vector line: " + line);
    out.push_back({line.substr(0, first), line.substr(first + 2, last - first - 2), line.substr(last + 2)});
  }
  return out;
}

inline const std::vector<Vector>& all_vectors() {
  static const std::vector<Vector> all = [] {
    auto v = read_vectors("jaus-openjaus-vectors.txt");
    auto d = read_vectors("jaus-openjaus-discovery-vectors.txt");
    v.insert(v.end(), d.begin(), d.end());
    return v;
  }();
  return all;
}

}  // namespace jaus::test
