// The pieces of jausd's configuration reader that every section uses: a
// YAML map read key by key in file order (unknown and duplicate keys are
// errors), numbers and integers checked against their range, and the first
// problem thrown as a Failure with its line, caught once in
// load_config_string. config_file.cpp reads the node's sections with them,
// hardware_config.cpp the vehicle, cameras and manipulator.
#pragma once

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <functional>
#include <initializer_list>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include "jaus/base/quoted.hpp"

namespace jausd::yaml_reader {

// A closed or half-open interval of doubles with its wording for errors.
struct NumberRange {
  double min;
  bool min_inclusive;
  double max;
  std::string_view text;  // "a number > 0 and <= 100"
  bool contains(double v) const {
    return std::isfinite(v) && (min_inclusive ? v >= min : v > min) && v <= max;
  }
};

inline std::string join(auto const& names) {
  std::string out;
  for (const auto& name : names) {
    if (!out.empty()) out += ", ";
    out += name;
  }
  return out.empty() ? "none" : out;
}


inline std::string number_text(double v) {
  std::array<char, 32> buf{};
  const auto r = std::to_chars(buf.data(), buf.data() + buf.size(), v);
  return std::string(buf.data(), r.ptr);
}

// A leading '+' is allowed (YAML's own integers allow it), one sign only.
inline std::string_view without_plus(std::string_view text) {
  if (text.size() > 1 && text.front() == '+' && text[1] != '-') text.remove_prefix(1);
  return text;
}

inline std::optional<long long> to_integer(std::string_view text, int base = 10) {
  text = without_plus(text);
  long long v = 0;
  const auto r = std::from_chars(text.data(), text.data() + text.size(), v, base);
  if (text.empty() || r.ec != std::errc{} || r.ptr != text.data() + text.size()) return std::nullopt;
  return v;
}

inline std::optional<double> to_number(std::string_view text) {
  text = without_plus(text);
  double v = 0;
  const auto r = std::from_chars(text.data(), text.data() + text.size(), v, std::chars_format::general);
  if (text.empty() || r.ec != std::errc{} || r.ptr != text.data() + text.size() || !std::isfinite(v))
    return std::nullopt;
  return v;
}

inline bool one_of(std::string_view value, auto const& choices) {
  return std::find(choices.begin(), choices.end(), value) != choices.end();
}

inline std::string first_at(int line) { return line > 0 ? " (first at line " + std::to_string(line) + ")" : ""; }

// The first error found; thrown inside the reader only, caught in load_config_string.
struct Failure {
  int line;
  std::string what;
};

[[noreturn]] inline void fail(int line, std::string what) { throw Failure{line, std::move(what)}; }

inline int line_of(const YAML::Node& node) {
  const YAML::Mark mark = node.Mark();
  return mark.is_null() ? 0 : mark.line + 1;
}

inline std::string describe(const YAML::Node& node) {
  switch (node.Type()) {
    case YAML::NodeType::Scalar: return jaus::quoted(node.Scalar());
    case YAML::NodeType::Sequence:
      return node.size() == 0 ? "an empty list" : "a list";
    case YAML::NodeType::Map: return "a map";
    default: return "nothing";
  }
}

// One key of a map and its value.
struct Entry {
  std::string key;
  int key_line;
  YAML::Node value;
  bool is_null() const { return !value.IsDefined() || value.IsNull(); }
  // Errors about the value point at it; a missing value has no line of its own.
  int value_line() const { return is_null() ? key_line : line_of(value); }
  [[noreturn]] void must_be(std::string_view what) const {
    fail(value_line(), "'" + key + "' must be " + std::string(what) + ", got " + describe(value));
  }
  const std::string& scalar(std::string_view what) const {
    if (!value.IsScalar()) must_be(what);
    return value.Scalar();
  }
};

struct Key {
  std::string_view name;
  std::function<void(const Entry&)> read;
};

inline std::string in(std::string_view where) { return where.empty() ? "" : " in " + std::string(where); }

// Reads a map in file order: every key must be one of `keys` and appear once.
// A missing or empty (null) map reads as all defaults. The keys are a list
// known when the reader is written, or one made at run time (a vector: the
// platform kinds' options).
inline void read_map(const YAML::Node& node, std::string_view where, int where_line, const std::vector<Key>& keys);
inline void read_map(const YAML::Node& node, std::string_view where, int where_line, std::initializer_list<Key> keys) {
  read_map(node, where, where_line, std::vector<Key>(keys));
}
inline void read_map(const YAML::Node& node, std::string_view where, int where_line, const std::vector<Key>& keys) {
  if (!node.IsDefined() || node.IsNull()) return;
  if (!node.IsMap()) {
    if (where.empty()) fail(line_of(node), "the configuration must be a map of keys, got " + describe(node));
    fail(where_line, "'" + std::string(where) + "' must be a map of keys, got " + describe(node));
  }
  std::map<std::string, int> seen;
  for (auto it = node.begin(); it != node.end(); ++it) {
    // Copies: the iterator's pair is a temporary proxy.
    const YAML::Node key = it->first;
    const YAML::Node value = it->second;
    if (!key.IsScalar()) fail(line_of(key), "keys must be plain names, got " + describe(key) + in(where));
    const std::string& name = key.Scalar();
    const int line = line_of(key);
    if (const auto [first, inserted] = seen.emplace(name, line); !inserted)
      fail(line, "duplicate key " + jaus::quoted(name) + in(where) + first_at(first->second));
    const auto handler = std::find_if(keys.begin(), keys.end(), [&](const Key& k) { return k.name == name; });
    if (handler == keys.end()) {
      std::vector<std::string_view> names;
      for (const auto& k : keys) names.push_back(k.name);
      fail(line, "unknown key " + jaus::quoted(name) + in(where) + " (known: " + join(names) + ")");
    }
    handler->read(Entry{name, line, value});
  }
}

// A list; null reads as empty.
inline std::vector<YAML::Node> read_list(const Entry& e) {
  if (e.is_null()) return {};
  if (!e.value.IsSequence()) e.must_be("a list");
  return {e.value.begin(), e.value.end()};
}

template <class T>
T integer(const Entry& e, long long min, long long max) {
  const std::string what = "an integer " + std::to_string(min) + ".." + std::to_string(max);
  const auto v = to_integer(e.scalar(what));
  if (!v || *v < min || *v > max) e.must_be(what);
  return static_cast<T>(*v);
}

// Bits (flags, pins): decimal or hexadecimal with 0x, 0..max.
inline std::uint32_t bits(const Entry& e, std::uint32_t min, std::uint32_t max) {
  const std::string what = "bits " + std::to_string(min) + ".." + std::to_string(max) + " (decimal or 0x hexadecimal)";
  std::string_view text = e.scalar(what);
  const bool hex = text.size() > 2 && text[0] == '0' && (text[1] == 'x' || text[1] == 'X');
  if (hex) text.remove_prefix(2);
  const auto v = hex && !text.empty() && text.front() != '-' && text.front() != '+' ? to_integer(text, 16)
                 : hex                                                             ? std::nullopt
                                                                                   : to_integer(text);
  if (!v || *v < min || *v > max) e.must_be(what);
  return static_cast<std::uint32_t>(*v);
}

inline double number(const Entry& e, const NumberRange& range) {
  const auto v = to_number(e.scalar(range.text));
  if (!v || !range.contains(*v)) e.must_be(range.text);
  return *v;
}

inline bool boolean(const Entry& e) {
  bool v = false;
  if (!YAML::convert<bool>::decode(e.value, v)) e.must_be("true or false");
  return v;
}

inline std::string choice(const Entry& e, auto const& choices) {
  const std::string what = "one of " + join(choices);
  const std::string& text = e.scalar(what);
  if (!one_of(text, choices)) e.must_be(what);
  return text;
}

}  // namespace jausd::yaml_reader
