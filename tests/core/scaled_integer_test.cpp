#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "jaus/core/scaled_integer.hpp"
#include "jaus/core/time_stamp.hpp"

namespace jaus {
namespace {

TEST(ScaledInteger, UnsignedUsesFullRangeWithLowerBias) {
  constexpr ScaledRange<std::uint16_t> rate{0, 1092};
  EXPECT_DOUBLE_EQ(rate.scale(), 1092.0 / 65535.0);
  EXPECT_EQ(rate.encode(0), 0);
  EXPECT_EQ(rate.encode(1092), 65535);
  EXPECT_EQ(rate.encode(10), 600);  // Confirm Event Request vector: 10 Hz -> 0x0258
  EXPECT_NEAR(rate.decode(600), 10, rate.scale());
}

TEST(ScaledInteger, SignedIsSymmetricAroundTheMidpoint) {
  constexpr ScaledRange<std::int16_t> angle{-std::numbers::pi, std::numbers::pi};
  EXPECT_DOUBLE_EQ(angle.scale(), 2 * std::numbers::pi / 65534.0);
  EXPECT_EQ(angle.encode(0), 0);
  EXPECT_EQ(angle.encode(std::numbers::pi), 32767);
  EXPECT_EQ(angle.encode(-std::numbers::pi), -32767);
  EXPECT_DOUBLE_EQ(angle.decode(32767), std::numbers::pi);
  // -32768 lies outside the encoding; it reads as the lower limit.
  EXPECT_DOUBLE_EQ(angle.decode(-32768), -std::numbers::pi);
}

TEST(ScaledInteger, SignedWithOffsetRangeUsesTheMidpointBias) {
  constexpr ScaledRange<std::int32_t> elevation{-10'000, 35'000};
  EXPECT_DOUBLE_EQ(elevation.bias(), 12'500);
  EXPECT_EQ(elevation.encode(12'500), 0);
  EXPECT_NEAR(elevation.decode(elevation.encode(-41.5)), -41.5, elevation.scale());
}

TEST(ScaledInteger, ClampsOutOfRangeAndNonFiniteValues) {
  constexpr ScaledRange<std::uint8_t> percent{0, 100};
  EXPECT_EQ(percent.encode(250), 255);
  EXPECT_EQ(percent.encode(-3), 0);
  EXPECT_EQ(percent.encode(std::nan("")), 0);
  EXPECT_EQ(percent.encode(INFINITY), 255);
}

TEST(ScaledInteger, RoundsHalfAwayFromZero) {
  constexpr ScaledRange<std::int8_t> unit{-127, 127};  // scale 1
  EXPECT_EQ(unit.encode(2.5), 3);
  EXPECT_EQ(unit.encode(-2.5), -3);
  EXPECT_EQ(unit.encode(-2.4), -2);
}

TEST(ScaledInteger, EveryRawValueRoundTrips) {
  constexpr ScaledRange<std::int16_t> r{-100, 100};
  for (int raw = -32767; raw <= 32767; ++raw)
    ASSERT_EQ(r.encode(r.decode(static_cast<std::int16_t>(raw))), raw);
}

TEST(TimeStamp, PacksPartsIntoTheirBits) {
  const TimeStamp t{789, 42, 37, 13, 21};
  ASSERT_TRUE(t.pack());
  EXPECT_EQ(*t.pack(), 0xAB65AB15u);  // from the RA 3.3 peer's vectors
  EXPECT_EQ(TimeStamp::unpack(*t.pack()), t);
  EXPECT_FALSE((TimeStamp{1024, 0, 0, 0, 1}.pack()));
}

TEST(DateStamp, PacksYearsSince2000) {
  const DateStamp d{21, 11, 2024};
  ASSERT_TRUE(d.pack());
  EXPECT_EQ(DateStamp::unpack(*d.pack()), d);
  EXPECT_FALSE((DateStamp{1, 1, 1999}.pack()));
  EXPECT_FALSE((DateStamp{1, 1, 2128}.pack()));
}

}  // namespace
}  // namespace jaus
