// Bad bytes never crash and never pass: truncations, flips, size
// disagreements, reserved presence bits and counts that overrun the payload
// all give an error naming where and why. Run under ASan to catch over-reads.
#include <gtest/gtest.h>

#include <random>

#include "jaus/base/hex.hpp"
#include "jaus/messages/all.hpp"
#include "jaus/messages/catalogue.hpp"
#include "vector_file.hpp"

namespace jaus {
namespace {

using msg::Bytes;

Bytes hex(std::string_view text) {
  auto out = parse_hex(text);
  EXPECT_TRUE(out) << out.error().message();
  return out ? *out : Bytes{};
}

// Decodes as the tools do; must never crash, may succeed or fail.
bool decodes(std::span<const std::uint8_t> bytes) {
  return msg::message_to_json(bytes, wire::Dialect::openjaus).has_value() &&
         msg::message_to_json(bytes, wire::Dialect::ra).has_value();
}

TEST(Malformed, EveryTruncationOfEveryVectorIsAnError) {
  for (const auto& v : test::all_vectors()) {
    const Bytes full = hex(v.hex);
    ASSERT_TRUE(msg::message_to_json(full, wire::Dialect::openjaus)) << v.code;
    for (std::size_t n = 0; n < full.size(); ++n) {
      auto result = msg::message_to_json(std::span(full).first(n), wire::Dialect::openjaus);
      EXPECT_FALSE(result) << v.code << " cut to " << n << " bytes";
    }
  }
}

TEST(Malformed, TruncatedPayloadWithMatchingDataSizeIsAnError) {
  // Header says 4 bytes and carries 4, but Report Global Pose with pv 0x01FF needs 30.
  auto result = msg::message_to_json(hex("06020244012101010128010204000B0AFF0156EC"));
  ASSERT_FALSE(result);
  EXPECT_EQ(result.error().code, ErrorCode::truncated);
  EXPECT_EQ(result.error().field, "latitude_deg");
  EXPECT_EQ(result.error().offset, 18u);
}

TEST(Malformed, DataSizeThatDisagreesWithTheDatagramIsAnError) {
  auto result = msg::message_to_json(hex("06020D00012101010128010202000B0A7B"));
  ASSERT_FALSE(result);
  EXPECT_EQ(result.error().code, ErrorCode::data_size_mismatch);
}

TEST(Malformed, ReservedPresenceBitsAreAnError) {
  // Set Wrench Effort defines bits 0-11; bit 12 is reserved.
  auto result = msg::message_to_json(hex("06020504012101010128010202000B0A0010"));
  ASSERT_FALSE(result);
  EXPECT_EQ(result.error().code, ErrorCode::reserved_presence_bits);
  EXPECT_EQ(result.error().offset, 16u);
  // Report Global Pose: bit 9 maps to no field.
  auto pose = msg::message_to_json(hex("06020244012101010128010202000B0A0002"));
  ASSERT_FALSE(pose);
  EXPECT_EQ(pose.error().code, ErrorCode::reserved_presence_bits);
}

TEST(Malformed, QueryPresenceMasksIgnoreUndefinedBits) {
  // A query's vector is a request mask: extra bits are not an error.
  EXPECT_TRUE(msg::message_to_json(hex("06020224012101010128010202000B0AFFFF")));
}

TEST(Malformed, CountsThatOverrunThePayloadAreAnError) {
  // Set Joint Positions claiming 200 joints with room for one.
  auto result = msg::message_to_json(hex("06020206012101010128010205000B0AC806A04986"));
  ASSERT_FALSE(result);
  EXPECT_EQ(result.error().code, ErrorCode::count_out_of_range);
  EXPECT_EQ(result.error().field, "positions_rad");
  // Report Configuration: one node claiming 100 components.
  auto config = msg::message_to_json(hex("0602014B012101010128010203000B0A010164"));
  ASSERT_FALSE(config);
  EXPECT_EQ(config.error().code, ErrorCode::count_out_of_range);
  // Event whose report size is larger than what follows.
  auto event = msg::message_to_json(hex("0602F14101210101012801020A000B0A04014B11FFFFFFFF0101"));
  ASSERT_FALSE(event);
  EXPECT_EQ(event.error().code, ErrorCode::count_out_of_range);
}

TEST(Malformed, ReservedZeroCountsAreAnError) {
  auto result = msg::message_to_json(hex("06020106012101010128010201000B0A00"));
  ASSERT_FALSE(result);
  EXPECT_EQ(result.error().code, ErrorCode::count_out_of_range);
}

TEST(Malformed, TrailingBytesAreAnError) {
  auto result = msg::message_to_json(hex("06020D00012101010128010202000B0A7B00"));
  ASSERT_FALSE(result);
  EXPECT_EQ(result.error().code, ErrorCode::trailing_bytes);
}

TEST(Malformed, UnknownCommandCodeIsAnError) {
  auto result = msg::message_to_json(hex("06020944012101010128010200000B0A"));
  ASSERT_FALSE(result);
  EXPECT_EQ(result.error().code, ErrorCode::unknown_message);
}

TEST(Malformed, OddDatesSurviveJsonInTheirDialect) {
  // Found by the fuzzer: raw month 15 reads as 16 in the openjaus dialect
  // (0-based months); its JSON must encode again in that dialect.
  const Bytes set_time = hex("06021100012101010128010207000B0A0315AB65ABE0D1");
  for (const auto dialect : {wire::Dialect::ra, wire::Dialect::openjaus}) {
    auto json = msg::message_to_json(set_time, dialect);
    ASSERT_TRUE(json) << json.error().message();
    auto again = msg::message_from_json(*json, dialect);
    ASSERT_TRUE(again) << again.error().message();
    EXPECT_EQ(*again, set_time);
  }
}

TEST(Malformed, RandomByteFlipsNeverCrash) {
  std::mt19937 rng(20261121);
  std::size_t rejected = 0, total = 0;
  for (const auto& v : test::all_vectors()) {
    const Bytes original = hex(v.hex);
    for (int i = 0; i < 300; ++i) {
      Bytes mutated = original;
      const int flips = 1 + static_cast<int>(rng() % 4);
      for (int f = 0; f < flips; ++f) mutated[rng() % mutated.size()] ^= static_cast<std::uint8_t>(1u << (rng() % 8));
      ++total;
      if (!decodes(mutated)) ++rejected;
    }
  }
  // Most flips land in fields where any value is valid; some must be caught.
  EXPECT_GT(rejected, 0u);
  EXPECT_LT(rejected, total);
}

TEST(Malformed, RandomGarbageNeverCrashes) {
  std::mt19937 rng(7);
  for (int i = 0; i < 20000; ++i) {
    Bytes garbage(rng() % 64);
    for (auto& b : garbage) b = static_cast<std::uint8_t>(rng());
    if (garbage.size() >= 16) {
      // Make the header plausible so the payload decoders are exercised too.
      garbage[1] = 2;
      const auto& all = msg::catalogue(wire::Dialect::ra);
      const auto code = all[rng() % all.size()].code;
      garbage[2] = static_cast<std::uint8_t>(code);
      garbage[3] = static_cast<std::uint8_t>(code >> 8);
      const auto size = garbage.size() - 16;
      garbage[12] = static_cast<std::uint8_t>(size);
      garbage[13] = static_cast<std::uint8_t>(size >> 8);
    }
    (void)decodes(garbage);
  }
  SUCCEED();
}

}  // namespace
}  // namespace jaus
