// Field values of one message, from both sides, as key -> values in order:
// tshark's JSON (-T json --no-duplicate-keys: abbreviation keys, subtrees as
// <key>_tree) and the codec's JSON (`jausctl msg decode`, `jausctl clearpath
// decode`: nested objects and arrays, flattened to prefix.path.to.field).
// Depth-first order on both sides gives each key's values in the same order.
#pragma once

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace jaus::test {

using Json = nlohmann::ordered_json;
using FieldValues = std::map<std::string, std::vector<Json>>;

inline void flatten_tshark(const Json& j, const std::string& key, FieldValues& out) {
  if (j.is_object()) {
    for (const auto& [k, v] : j.items()) flatten_tshark(v, k, out);
  } else if (j.is_array()) {
    for (const auto& e : j) flatten_tshark(e, key, out);
  } else {
    out[key].push_back(j);
  }
}

inline void flatten_decoded(const Json& j, const std::string& path, FieldValues& out) {
  if (j.is_object()) {
    for (const auto& [k, v] : j.items()) flatten_decoded(v, path + "." + k, out);
  } else if (j.is_array()) {
    for (const auto& e : j) flatten_decoded(e, path, out);
  } else {
    out[path].push_back(j);
  }
}

// The dissector's field prefix of a message name: "Report Global Pose" -> "report_global_pose".
inline std::string slug(const std::string& name) {
  std::string out;
  bool gap = false;
  for (const char c : name) {
    if (std::isalnum(static_cast<unsigned char>(c))) {
      if (gap) out += '_';
      out += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
      gap = false;
    } else {
      gap = true;
    }
  }
  if (gap) out += '_';
  return out;
}

inline std::string upper_hex(std::string s) {
  std::string out;
  for (const char c : s)
    if (c != ':') out += static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return out;
}

// Does tshark's text show the decoded value? Numbers within 1e-6 relative
// (the dissector computes scaled values as the codec does; floats print shorter).
inline bool same_value(const Json& decoded, const Json& shown_json) {
  const std::string shown = shown_json.is_string() ? shown_json.get<std::string>() : shown_json.dump();
  if (decoded.is_boolean()) {
    const bool on = shown == "1" || shown == "True" || shown == "true";
    const bool off = shown == "0" || shown == "False" || shown == "false";
    return decoded.get<bool>() ? on : off;
  }
  if (decoded.is_number()) {
    char* end = nullptr;
    const bool hex = shown.size() > 2 && shown[0] == '0' && (shown[1] == 'x' || shown[1] == 'X');
    const double v =
        hex ? static_cast<double>(std::strtoull(shown.c_str(), &end, 16)) : std::strtod(shown.c_str(), &end);
    if (end == shown.c_str() || *end != '\0') return false;
    const double want = decoded.get<double>();
    return std::fabs(v - want) <= 1e-6 * std::max(1.0, std::fabs(want));
  }
  if (decoded.is_string()) {
    const auto text = decoded.get<std::string>();
    return text == shown || upper_hex(text) == upper_hex(shown);
  }
  return false;
}

inline bool same_values(const std::vector<Json>& decoded, const std::vector<Json>* shown) {
  if (shown == nullptr || shown->size() != decoded.size()) return false;
  for (std::size_t i = 0; i < decoded.size(); ++i)
    if (!same_value(decoded[i], (*shown)[i])) return false;
  return true;
}

inline std::string joined(const std::vector<Json>* values) {
  if (values == nullptr) return "(absent)";
  std::string out;
  for (const auto& v : *values) out += (out.empty() ? "" : ", ") + v.dump();
  return "[" + out + "]";
}

// Items that organise the tree rather than carry a decoded value.
inline bool structural(const std::string& key) {
  const auto last = key.substr(key.rfind('.') + 1);
  return last == "pv" || last == "count" || last == "index" || last == "length" || last == "name" || last == "tag" ||
         key.find(".pv.") != std::string::npos;
}

// Every decoded key shown with the same values (an enumeration's or a packed
// value's name in <key>.name); and nothing shown under `prefix` that the
// codec did not decode (an absent optional field, a field of another dialect).
inline std::vector<std::string> compare_fields(const FieldValues& decoded, const FieldValues& shown,
                                               const std::string& prefix) {
  std::vector<std::string> problems;
  for (const auto& [key, values] : decoded) {
    const auto it = shown.find(key);
    const std::vector<Json>* got = it == shown.end() ? nullptr : &it->second;
    if (same_values(values, got)) continue;
    const auto named = shown.find(key + ".name");
    if (named != shown.end() && same_values(values, &named->second)) continue;
    problems.push_back(key + ": decoded " + joined(&values) + ", tshark " + joined(got));
  }
  for (const auto& [key, values] : shown) {
    if (key.rfind(prefix + ".", 0) != 0 || structural(key) || decoded.count(key) != 0) continue;
    // A part of a value the codec shows whole (a packed date-time's parts, a time stamp's raw number).
    bool part_of_decoded = false;
    const auto parent = key.substr(0, key.rfind('.'));
    if (decoded.count(parent) != 0) part_of_decoded = true;
    for (const auto& [k, v] : decoded)
      if (k.rfind(key + ".", 0) == 0) part_of_decoded = true;
    if (!part_of_decoded) problems.push_back(key + ": shown by tshark " + joined(&values) + ", not decoded");
  }
  return problems;
}

}  // namespace jaus::test
