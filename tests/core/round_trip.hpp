// Round trip of every described message: random in-range values and random
// presence vectors (fixed seed) survive encode -> decode within one scale
// step, in both dialects; re-encoding and the JSON form are byte-exact; every
// truncation of a payload is rejected. Instantiated per subgroup
// (message_checks_*.cpp).
#pragma once

#include <nlohmann/json.hpp>

// The codec of every body comes compiled from jaus_core: the checks call it.
#include "jaus/messages/compiled_json_codecs.hpp"
#include "described_values.hpp"
#include "message_types.hpp"

namespace jaus::test {

template <class M>
class RoundTrip : public ::testing::Test {};
TYPED_TEST_SUITE_P(RoundTrip);

// A body whose last field takes whatever bytes are left (Report Image's data,
// Report Identification's text) accepts a truncated payload by design.
template <class Body>
constexpr bool ends_open() {
  constexpr auto fields = Body::describe();
  constexpr std::size_t n = std::tuple_size_v<decltype(fields)>;
  if constexpr (n == 0) {
    return false;
  } else {
    using Codec = typename std::decay_t<decltype(std::get<n - 1>(fields))>::codec_type;
    return std::is_same_v<Codec, wire::Bytes<>> || std::is_same_v<Codec, wire::Text<80, true>>;
  }
}

// The check of one message, written for its body: Message<Code, Name, Body>
// adds only the code and the name, so messages sharing a body (Set X and
// Report X, the many empty queries) share one instantiation of the check, and
// the codec it calls is the library's, compiled per body.
template <class Body>
void check_round_trip(std::uint16_t code, std::string_view name) {
  Rng rng(0x1A05'0000u + code);
  std::vector<std::uint8_t> first(1 << 16), second(1 << 16);
  for (const auto dialect : {wire::Dialect::ra, wire::Dialect::openjaus}) {
    for (int i = 0; i < 100; ++i) {
      Body original{};
      wire::CodecContext ctx{dialect, {}};
      randomize(original, rng, ctx, /*all_present=*/i == 0);
      const std::string where = std::string(name) + " #" + std::to_string(i);

      auto size = wire::encode_payload(original, first, dialect);
      ASSERT_TRUE(size) << where << ": " << size.error().message();
      const std::span<const std::uint8_t> payload(first.data(), *size);

      Body decoded{};
      auto decoded_ok = wire::decode_payload_into(payload, decoded, dialect);
      ASSERT_TRUE(decoded_ok) << where << ": " << decoded_ok.error().message();
      {
        StepTolerance tolerance(dialect == wire::Dialect::ra ? 1.0 : 1.5);
        expect_close_body(original, decoded, where);
      }

      // Once quantised, a value re-encodes to the same bytes (the peer's
      // rounding in the openjaus dialect moves negative values up a step).
      if (dialect == wire::Dialect::ra) {
      auto size2 = wire::encode_payload(decoded, second, dialect);
      ASSERT_TRUE(size2);
      ASSERT_EQ(*size, *size2) << where;
      EXPECT_TRUE(std::equal(payload.begin(), payload.end(), second.begin())) << where;

      // The JSON form carries the same message.
      const auto json = wire::fields_to_json<nlohmann::ordered_json>(decoded);
      Body from_json{};
      auto filled = wire::fields_from_json(json, from_json);
      ASSERT_TRUE(filled) << where << ": " << filled.error().message() << "\n" << json.dump();
      auto size3 = wire::encode_payload(from_json, second, dialect);
      ASSERT_TRUE(size3);
      ASSERT_EQ(*size, *size3) << where << "\n" << json.dump();
      EXPECT_TRUE(std::equal(payload.begin(), payload.end(), second.begin())) << where << "\n" << json.dump();
      }

      // Every truncation is an error naming the field cut short, never a
      // crash or an over-read (fixed-layout messages find it on a second,
      // checked walk: describe.hpp).
      if constexpr (!ends_open<Body>()) {
        for (std::size_t cut = 0; cut < payload.size(); ++cut) {
          Body partial{};
          const auto cut_error = wire::decode_payload_into(payload.first(cut), partial, dialect);
          ASSERT_FALSE(cut_error.has_value()) << where << " truncated to " << cut << " bytes";
          EXPECT_FALSE(cut_error.error().field.empty())
              << where << " truncated to " << cut << ": " << cut_error.error().message();
          EXPECT_LE(cut_error.error().offset, cut) << where << " truncated to " << cut << ": " << cut_error.error().message();
        }
      }
      // Likewise every output buffer too small for the payload.
      for (std::size_t room = 0; room < *size; ++room) {
        const auto small = wire::encode_payload(original, std::span(second).first(room), dialect);
        ASSERT_FALSE(small) << where << " into " << room << " bytes";
        EXPECT_EQ(small.error().code, ErrorCode::output_too_small) << where << ": " << small.error().message();
        EXPECT_FALSE(small.error().field.empty()) << where << " into " << room << ": " << small.error().message();
        EXPECT_LE(small.error().offset, room) << where << " into " << room << ": " << small.error().message();
      }
      // One byte too many is an error too.
      if (*size < first.size()) {
        first[*size] = 0xA5;
        Body longer{};
        const auto extra = wire::decode_payload_into(std::span<const std::uint8_t>(first.data(), *size + 1), longer,
                                                     dialect);
        if (!ends_open<Body>()) {
          ASSERT_FALSE(extra.has_value()) << where;
        }
      }
    }
  }
}

TYPED_TEST_P(RoundTrip, RandomValuesSurviveEncodeDecode) {
  check_round_trip<typename TypeParam::body_type>(TypeParam::code, TypeParam::name);
}

REGISTER_TYPED_TEST_SUITE_P(RoundTrip, RandomValuesSurviveEncodeDecode);

}  // namespace jaus::test
