// The definition of VectorComparison (vector_compare.hpp), for the files
// that instantiate it: message_checks_*.cpp.
#pragma once

#include <gtest/gtest.h>

#include <string>
#include <vector>

// The codec of every body comes compiled from jaus_core: the comparison calls it.
#include "jaus/messages/compiled_json_codecs.hpp"
#include "described_values.hpp"
#include "jaus/base/hex.hpp"
#include "vector_compare.hpp"

namespace jaus::test {

// Written for the message's body, like the round trip: messages sharing a
// body share its instantiation.
template <class Body>
void compare_with_vector_as(const nlohmann::ordered_json& expected, std::span<const std::uint8_t> payload,
                            const std::string& where) {
  Body decoded{};
  auto decoded_ok = wire::decode_payload_into(payload, decoded, wire::Dialect::openjaus);
  ASSERT_TRUE(decoded_ok) << where << ": " << decoded_ok.error().message();
  Body wanted{};
  auto filled = wire::fields_from_json(expected, wanted);
  ASSERT_TRUE(filled) << where << ": " << filled.error().message() << "\n" << expected.dump();
  StepTolerance tolerance(1.5);  // their rounding is up to one step high for negative values
  expect_close_body(wanted, decoded, where);

  // Encoding the values they were given, in their dialect, gives their bytes.
  std::vector<std::uint8_t> ours(8192);
  auto size = wire::encode_payload(wanted, ours, wire::Dialect::openjaus);
  ASSERT_TRUE(size) << where << ": " << size.error().message();
  EXPECT_EQ(to_hex(std::span(ours).first(*size)), to_hex(payload)) << where;
}

template <class Group>
bool VectorComparison<Group>::compare(std::uint16_t code, const nlohmann::ordered_json& expected,
                                      std::span<const std::uint8_t> payload, const std::string& where) {
  return [&]<class... Ms>(msg::TypeList<Ms...>) {
    const auto compare_as = [&]<class M>() {
      if (M::code != code) return false;
      compare_with_vector_as<typename M::body_type>(expected, payload, where + " " + std::string(M::name));
      return true;
    };
    return (compare_as.template operator()<Ms>() || ...);
  }(Group{});
}

}  // namespace jaus::test
