// The comparison of an OpenJAUS vector's payload with the values that
// implementation was given, written once per message type. Declared here for
// vectors_test.cpp; defined in vector_compare_impl.hpp and instantiated per
// subgroup next to the subgroup's round trip (message_checks_*.cpp).
#pragma once

#include <cstdint>
#include <span>
#include <string>

#include <nlohmann/json.hpp>

#include "message_types.hpp"

namespace jaus::test {

template <class Group>
struct VectorComparison {
  // Decodes `payload` (openjaus dialect) as the message of Group with
  // command code `code` and expects the values of `expected` (our JSON form)
  // within one scale step; encoding those values gives the payload's bytes.
  // False when Group has no message of that code.
  static bool compare(std::uint16_t code, const nlohmann::ordered_json& expected,
                      std::span<const std::uint8_t> payload, const std::string& where);
};

// The same over every subgroup: false when no message has that code.
inline bool compare_with_vector(std::uint16_t code, const nlohmann::ordered_json& expected,
                                std::span<const std::uint8_t> payload, const std::string& where) {
  return [&]<class... Groups>(msg::TypeList<Groups...>) {
    return (VectorComparison<Groups>::compare(code, expected, payload, where) || ...);
  }(MessageGroups{});
}

}  // namespace jaus::test
