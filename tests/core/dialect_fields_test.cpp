// One description, two dialects (issue 44): a body JSS shares with RA is
// described once; read in wire::Dialect::jss every scaled field is unsigned
// over the RA limits, or over its own where the description gives them
// (wire::Scaled::jss). The RA and openjaus bytes do not change (vectors_test).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <initializer_list>
#include <span>
#include <string>
#include <vector>

#include "jaus/messages/all.hpp"

namespace jaus {
namespace dialect_fields_test {  // named: the unity batches mix this file's helpers with others'

using Bytes = std::vector<std::uint8_t>;

template <class M>
Bytes payload(const M& message, wire::Dialect dialect) {
  std::array<std::uint8_t, 256> out{};
  auto size = wire::encode_payload(message, out, dialect);
  EXPECT_TRUE(size) << (size ? "" : size.error().message());
  return size ? Bytes(out.begin(), out.begin() + static_cast<std::ptrdiff_t>(*size)) : Bytes{};
}

template <class T>
Bytes little_endian(T value) {
  Bytes out(sizeof value);
  std::memcpy(out.data(), &value, sizeof value);  // x86 and arm64 are little-endian
  return out;
}

Bytes concat(std::initializer_list<Bytes> parts) {
  Bytes out;
  for (const auto& p : parts) out.insert(out.end(), p.begin(), p.end());
  return out;
}

TEST(JssDialect, ASignedScaledFieldIsUnsignedOverTheRaLimits) {
  msg::SetWrenchEffort set{};
  set.propulsive_linear_effort_x_percent = 50;
  set.resistive_linear_effort_x_percent = 40;
  const ScaledRange<std::uint16_t> jss_propulsive{-100, 100};
  const ScaledRange<std::int16_t> ra_propulsive{-100, 100};
  const ScaledRange<std::uint8_t> resistive{0, 100};  // unsigned in both
  const Bytes pv = little_endian<std::uint16_t>(0x0041);
  EXPECT_EQ(payload(set, wire::Dialect::jss),
            concat({pv, little_endian(jss_propulsive.encode(50)), little_endian(resistive.encode(40))}));
  EXPECT_EQ(payload(set, wire::Dialect::ra),
            concat({pv, little_endian(ra_propulsive.encode(50)), little_endian(resistive.encode(40))}));
  // 49151 and 16384: the same value, a different integer.
  EXPECT_NE(payload(set, wire::Dialect::jss), payload(set, wire::Dialect::ra));

  auto back = wire::decode_payload<msg::SetWrenchEffort>(payload(set, wire::Dialect::jss), wire::Dialect::jss);
  ASSERT_TRUE(back);
  EXPECT_NEAR(*back->propulsive_linear_effort_x_percent, 50, jss_propulsive.scale());
  EXPECT_NEAR(*back->resistive_linear_effort_x_percent, 40, resistive.scale());
  EXPECT_FALSE(back->propulsive_linear_effort_y_percent);
}

TEST(JssDialect, AFieldWithItsOwnJssRangeUsesIt) {
  // Velocity State: RA +-65.534 m/s (i32), JSS -327.68..327.67 (u32).
  msg::ReportVelocityState report{};
  report.velocity_x_mps = 300;
  const ScaledRange<std::uint32_t> jss_velocity{-327.68, 327.67};
  const ScaledRange<std::int32_t> ra_velocity{-65.534, 65.534};
  const Bytes pv = little_endian<std::uint16_t>(0x0001);
  EXPECT_EQ(payload(report, wire::Dialect::jss), concat({pv, little_endian(jss_velocity.encode(300))}));
  EXPECT_EQ(payload(report, wire::Dialect::ra), concat({pv, little_endian(ra_velocity.encode(65.534))}));  // clamped

  auto back = wire::decode_payload<msg::ReportVelocityState>(payload(report, wire::Dialect::jss), wire::Dialect::jss);
  ASSERT_TRUE(back);
  EXPECT_NEAR(*back->velocity_x_mps, 300, jss_velocity.scale());

  // Travel Speed: RA 0..10000 m/s, JSS 0..327.67; 1 m/s is 200 in JSS.
  EXPECT_EQ(payload(msg::SetTravelSpeed{{1.0}}, wire::Dialect::jss), (Bytes{0xc8, 0x00}));
  EXPECT_EQ(payload(msg::SetTravelSpeed{{1.0}}, wire::Dialect::ra), (Bytes{0x07, 0x00}));
}

TEST(JssDialect, EveryJssIntegerRoundTrips) {
  constexpr auto rate = wire::Scaled<std::int16_t>{-32.767, 32.767}.jss(-32.768, 32.767);
  const auto range = rate.jss_range();
  for (unsigned raw = 0; raw <= 0xFFFF; ++raw)
    ASSERT_EQ(range.encode(range.decode(static_cast<std::uint16_t>(raw))), raw);
  EXPECT_DOUBLE_EQ(rate.jss_step(), 65.535 / 65535.0);
  EXPECT_DOUBLE_EQ(rate.step(), (ScaledRange<std::int16_t>{-32.767, 32.767}.scale()));
}

// Which bodies get a JSS walk with the dialect as a constant: JSS's own
// (read as RA reads them, so RA's walk) and those JSS shares (their own).
static_assert(wire::jss_reads_as_ra<msg::AuthorityBody>());
static_assert(wire::jss_reads_as_ra<msg::TimeBody>());
static_assert(!wire::jss_reads_as_ra<msg::WrenchEffortBody>());  // signed fields
static_assert(!wire::jss_reads_as_ra<msg::TravelSpeedBody>());   // unsigned, JSS's own limits
static_assert(wire::shared_with_jss<msg::WrenchEffortBody>() && !wire::shared_with_jss<msg::AuthorityBody>());

TEST(JssDialect, TheConstantJssWalkWritesWhatTheRunTimeOneWrites) {
  msg::ReportLocalPose pose{};
  pose.x_m = -12.5;
  pose.z_m = -80'000;  // outside RA's z range, inside JSS's
  pose.yaw_rad = 3.0;
  pose.time_stamp = TimeStamp{1, 2, 3, 4, 5};
  std::array<std::uint8_t, 64> constant{}, run_time{};
  UncheckedWriter a(constant.data());
  wire::write_fields(static_cast<const msg::LocalPoseBody&>(pose), a, wire::kJssContext);
  UncheckedWriter b(run_time.data());
  wire::CodecContext ctx{wire::Dialect::jss, {}};
  wire::write_fields(static_cast<const msg::LocalPoseBody&>(pose), b, ctx);
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(constant, run_time);
  // And the whole encoder (which takes the constant walk) agrees, after the presence vector.
  const Bytes encoded = payload(pose, wire::Dialect::jss);
  ASSERT_EQ(encoded.size(), 2 + b.size());
  EXPECT_TRUE(std::equal(encoded.begin() + 2, encoded.end(), run_time.begin()));
}

TEST(JssDialect, TheDocsSayEachDialectsWireType) {
  const std::string ra = wire::fields_doc<msg::WrenchEffortBody>(wire::Dialect::ra);
  const std::string jss = wire::fields_doc<msg::WrenchEffortBody>(wire::Dialect::jss);
  EXPECT_NE(ra.find("`propulsive_linear_effort_x_percent` (bit 0): i16 scaled [-100, 100]"), std::string::npos) << ra;
  EXPECT_NE(jss.find("`propulsive_linear_effort_x_percent` (bit 0): u16 scaled [-100, 100]"), std::string::npos)
      << jss;
  EXPECT_NE(jss.find("`resistive_linear_effort_x_percent` (bit 6): u8 scaled [0, 100]"), std::string::npos) << jss;
  EXPECT_EQ(wire::fields_doc<msg::WrenchEffortBody>(), ra);  // RA is the default

  const std::string pose = wire::fields_doc<msg::LocalPoseBody>(wire::Dialect::jss);
  EXPECT_NE(pose.find("`z_m` (bit 2): u32 scaled [-100000, 100000]"), std::string::npos) << pose;
  EXPECT_NE(wire::fields_doc<msg::LocalPoseBody>().find("`z_m` (bit 2): i32 scaled [-10000, 35000]"),
            std::string::npos);
}

}  // namespace dialect_fields_test
}  // namespace jaus
