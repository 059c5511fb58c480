// Malformed JSS contents: each is an error value naming where (offset in the
// contents, field) and why, never a crash or an over-read.
#include <gtest/gtest.h>

#include "jaus/jss/all.hpp"
#include "jss_bytes.hpp"

namespace jaus::test::jss_malformed {

using namespace jaus::jss;
namespace msg = jaus::jss::msg;

template <class M>
Error error_of(const std::vector<std::uint8_t>& contents) {
  const auto decoded = decode_contents<M>(contents);
  EXPECT_FALSE(decoded) << M::name << " " << to_hex(contents);
  return decoded ? Error{} : decoded.error();
}

TEST(JssMalformed, ContentsShorterThanTheId) {
  const auto e = error_of<msg::QueryStatus>({0x02});
  EXPECT_EQ(e.code, ErrorCode::truncated);
  EXPECT_EQ(e.offset, 0u);
}

TEST(JssMalformed, ReservedPresenceBits) {
  // Wrench effort defines bits 0-11; bit 12 is reserved.
  const auto e = error_of<msg::SetWrenchEffort>(hex_bytes("05 04 00 10"));
  EXPECT_EQ(e.code, ErrorCode::reserved_presence_bits);
  EXPECT_EQ(e.offset, 2u);
  // Set Local Waypoint defines bits 0-5.
  EXPECT_EQ(error_of<msg::SetLocalWaypoint>(hex_bytes("0d 04 40 dc 46 03 80 91 5c fe 7f")).code,
            ErrorCode::reserved_presence_bits);
}

TEST(JssMalformed, PresentFieldCutShort) {
  const auto e = error_of<msg::SetWrenchEffort>(hex_bytes("05 04 21 00 ff bf 00"));
  EXPECT_EQ(e.code, ErrorCode::truncated);
  EXPECT_EQ(e.field, "propulsive_rotational_effort_z_percent");
  EXPECT_EQ(e.offset, 6u);
}

TEST(JssMalformed, EmbeddedMessageCountBeyondTheBytes) {
  // Create Event whose msg32 says 200 bytes follow; 4 do.
  const auto e = error_of<msg::CreateEvent>(hex_bytes("f0 01 01 00 2c 01 c8 00 00 00 03 24 ff 01"));
  EXPECT_EQ(e.code, ErrorCode::count_out_of_range);
  EXPECT_EQ(e.field, "query_message");
  EXPECT_EQ(e.offset, 6u);
  // A byte count below the embedded message's 2-byte ID.
  const auto short_count = error_of<msg::Event>(hex_bytes("f1 41 00 07 01 00 00 00 03"));
  EXPECT_EQ(short_count.code, ErrorCode::count_out_of_range);
  EXPECT_EQ(short_count.offset, 4u);
}

TEST(JssMalformed, ListCountsBeyondTheBytes) {
  // Report Services claiming 9 nodes in 2 bytes.
  const auto e = error_of<msg::ReportServices>(hex_bytes("03 4b 09 01 00"));
  EXPECT_EQ(e.code, ErrorCode::count_out_of_range);
  EXPECT_EQ(e.field, "nodes");
  // A str8 longer than what is left.
  const auto text = error_of<msg::ReportIdentification>(hex_bytes("00 4b 02 11 27 09 48 75"));
  EXPECT_EQ(text.code, ErrorCode::truncated);
  EXPECT_EQ(text.field, "identification");
  EXPECT_EQ(text.offset, 6u);
  // Report Service List: a u16 subsystem count of 0x0101 in 3 bytes.
  EXPECT_EQ(error_of<msg::ReportServiceList>(hex_bytes("04 4b 01 01 2a")).code, ErrorCode::count_out_of_range);
}

TEST(JssMalformed, UnknownVariantTag) {
  const auto e = error_of<msg::QueryEvents>(hex_bytes("f0 21 07 00"));
  EXPECT_EQ(e.code, ErrorCode::bad_value);
  EXPECT_EQ(e.field, "filter");
  EXPECT_EQ(e.offset, 2u);
  const auto by_id = decode_contents<msg::QueryEvents>(hex_bytes("f0 21 00 03 24"));
  ASSERT_TRUE(by_id);
  EXPECT_EQ(by_id->filter, (codec::TaggedValue{msg::events_filter::kMessageId, 0x2403}));
}

TEST(JssMalformed, TrailingBytes) {
  const auto e = error_of<msg::ReportStatus>(hex_bytes("02 40 01 00 00 00 00 ff"));
  EXPECT_EQ(e.code, ErrorCode::trailing_bytes);
  EXPECT_EQ(e.offset, 7u);
}

TEST(JssMalformed, ReportIdentificationRaLayoutIsNotJss) {
  // The RA layout (authority byte, 80-byte name) read as JSS: the str8 length is the type's high byte.
  std::vector<std::uint8_t> ra = hex_bytes("00 4b 02 00 11 27");
  ra.resize(ra.size() + 80, 0x41);
  EXPECT_FALSE(decode_contents<msg::ReportIdentification>(ra));
}

}  // namespace jaus::test::jss_malformed
