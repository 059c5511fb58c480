// The one Error: codes grouped by domain, and which of them say where in the
// bytes they happened.
#include <gtest/gtest.h>

#include "jaus/base/error.hpp"
#include "jaus/base/expected.hpp"

namespace jaus {
namespace {

TEST(ErrorDomain, EveryCodeBelongsToItsGroup) {
  for (auto code : {ErrorCode::truncated, ErrorCode::bad_value, ErrorCode::unknown_message, ErrorCode::bad_frame,
                    ErrorCode::json})
    EXPECT_EQ(domain(code), ErrorDomain::codec) << to_string(code);
  for (auto code : {ErrorCode::io, ErrorCode::timeout, ErrorCode::interrupted})
    EXPECT_EQ(domain(code), ErrorDomain::io_time) << to_string(code);
  EXPECT_EQ(domain(ErrorCode::invalid_argument), ErrorDomain::usage);
  EXPECT_EQ(domain(ErrorCode::refused), ErrorDomain::peer);
  EXPECT_EQ(domain(ErrorCode::malformed), ErrorDomain::peer);
}

TEST(ErrorDomain, OnlyCodecErrorsHaveAPosition) {
  for (int raw = 0; raw <= static_cast<int>(ErrorCode::malformed); ++raw) {
    const auto code = static_cast<ErrorCode>(raw);
    EXPECT_EQ(has_position(code), domain(code) == ErrorDomain::codec) << to_string(code);
  }
}

TEST(ErrorDomain, NamesEachDomain) {
  EXPECT_EQ(to_string(ErrorDomain::codec), "codec");
  EXPECT_EQ(to_string(ErrorDomain::io_time), "I/O and time");
  EXPECT_EQ(to_string(ErrorDomain::usage), "usage");
  EXPECT_EQ(to_string(ErrorDomain::peer), "peer");
}

TEST(Error, CodecErrorsSayWhereOthersOnlyWhat) {
  const Error codec{ErrorCode::truncated, 23, "latitude_deg", "needs 4 bytes"};
  EXPECT_EQ(codec.message(), "offset 23, field 'latitude_deg': truncated (needs 4 bytes)");
  EXPECT_EQ(make_error(ErrorCode::io, "127.0.0.1:3794 is already in use").message(),
            "127.0.0.1:3794 is already in use");
  EXPECT_EQ(make_error(ErrorCode::refused, "").message(), "refused");
}

Expected<void> succeed() { return {}; }
Expected<void> fail() { return unexpected(make_error(ErrorCode::invalid_argument, "no")); }

TEST(ExpectedVoid, TrueOnSuccessFalseWithTheError) {
  EXPECT_TRUE(succeed());
  const auto failed = fail();
  ASSERT_FALSE(failed);
  EXPECT_EQ(failed.error().code, ErrorCode::invalid_argument);
  EXPECT_EQ(failed.error().message(), "no");
}

}  // namespace
}  // namespace jaus
