// Prometheus's text exposition format (version 0.0.4), checked as a scraper
// reads it: every line a HELP, a TYPE or a sample; each family declared
// once, its HELP and TYPE before its samples, all its samples together;
// names and label names well formed, label values quoted with their
// escapes; a counter's name ending in _total. Shared by the tests of
// jaus/host/metrics.hpp and of jausd's metrics port.
#pragma once

#include <gtest/gtest.h>

#include <map>
#include <optional>
#include <regex>
#include <set>
#include <sstream>
#include <string>

namespace jaus::test {

// Checks the text exposition format line by line; returns each sample
// ("name{labels}" as written) with its value, and fails the test on any
// line out of place.
inline std::map<std::string, double> parse_exposition(const std::string& text) {
  static const std::regex help(R"(# HELP ([a-zA-Z_:][a-zA-Z0-9_:]*) .+)");
  static const std::regex type(R"(# TYPE ([a-zA-Z_:][a-zA-Z0-9_:]*) (counter|gauge))");
  static const std::regex sample(
      R"(([a-zA-Z_:][a-zA-Z0-9_:]*)(\{([a-zA-Z_][a-zA-Z0-9_]*="([^"\\\n]|\\[\\"n])*")(,[a-zA-Z_][a-zA-Z0-9_]*="([^"\\\n]|\\[\\"n])*")*\})? (-?[0-9.e+-]+|NaN|\+Inf|-Inf))");
  std::map<std::string, double> samples;
  std::set<std::string> families;
  std::string family;
  std::string family_type;
  std::istringstream lines(text);
  int number = 0;
  for (std::string line; std::getline(lines, line);) {
    ++number;
    std::smatch m;
    if (std::regex_match(line, m, help)) {
      family = m[1];
      EXPECT_TRUE(families.insert(family).second) << "line " << number << ": family " << family << " declared twice";
      family_type.clear();
    } else if (std::regex_match(line, m, type)) {
      EXPECT_EQ(m[1], family) << "line " << number << ": TYPE of another family";
      family_type = m[2];
      if (family_type == "counter") {
        EXPECT_TRUE(family.ends_with("_total")) << family;
      }
    } else if (std::regex_match(line, m, sample)) {
      EXPECT_EQ(m[1], family) << "line " << number << ": a sample outside its family: " << line;
      EXPECT_FALSE(family_type.empty()) << "line " << number << ": a sample before its TYPE";
      const auto space = line.rfind(' ');
      EXPECT_TRUE(samples.emplace(line.substr(0, space), std::stod(line.substr(space + 1))).second)
          << "line " << number << ": sample repeated: " << line;
    } else {
      ADD_FAILURE() << "line " << number << " is not exposition format: '" << line << "'";
    }
  }
  return samples;
}


// The value of the first sample whose text starts with `prefix` (a name and
// some of its labels); none when there is none.
inline std::optional<double> first_sample(const std::map<std::string, double>& samples, const std::string& prefix) {
  for (const auto& [sample, value] : samples)
    if (sample.rfind(prefix, 0) == 0) return value;
  return std::nullopt;
}

}  // namespace jaus::test
