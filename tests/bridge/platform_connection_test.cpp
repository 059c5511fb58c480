// What the platform sends that the bridge cannot use: a damaged frame or one
// that does not decode is never delivered, and the log says where and why, a
// few lines per window and then a count (docs/safety.md, "Serial corruption").
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "jaus/base/virtual_time.hpp"
#include "jaus/bridge/platform_connection.hpp"
#include "jaus/clearpath/codec.hpp"
#include "jaus/clearpath/frame.hpp"
#include "jaus/clearpath/sim/loopback_client.hpp"

namespace jaus::test {
namespace {

namespace bridge = jaus::bridge;
namespace cp = jaus::clearpath;
namespace sim = jaus::clearpath::sim;
using namespace std::chrono_literals;

constexpr std::uint16_t kPlatformName = 0x8002;

class PlatformConnectionInput : public ::testing::Test {
 protected:
  PlatformConnectionInput()
      : loopback(time, time),
        platform(loopback, time, [this](rt::LogLevel level, const std::string& line) {
          if (level == rt::LogLevel::warn) warnings.push_back(line);
        }) {
    platform.on_data(kPlatformName, [this](const cp::Envelope&) { ++names_delivered; });
  }

  // A Platform Name frame from the platform, as the platform would write it.
  static std::vector<std::uint8_t> name_frame(std::uint32_t timestamp) {
    return *cp::encode(cp::Envelope{{0, timestamp, 0, kPlatformName}, cp::AnyMessage{cp::PlatformName{"husky", false}}});
  }
  void from_platform(const std::vector<std::uint8_t>& bytes) { loopback.core().on_bytes(bytes, time.now()); }
  std::size_t warnings_with(const std::string& text) const {
    return static_cast<std::size_t>(std::count_if(warnings.begin(), warnings.end(), [&](const std::string& line) {
      return line.find(text) != std::string::npos;
    }));
  }

  rt::VirtualTime time;
  sim::LoopbackClient loopback;
  std::vector<std::string> warnings;
  bridge::PlatformConnection platform;
  int names_delivered = 0;
};

TEST_F(PlatformConnectionInput, AFrameWithABadCrcIsNotDeliveredAndTheLogSaysWhereAndWhy) {
  auto bad = name_frame(7);
  bad[bad.size() - 1] ^= 0x01;  // the CRC's last byte
  from_platform(bad);
  from_platform(name_frame(8));

  EXPECT_EQ(names_delivered, 1);  // the good one only
  EXPECT_EQ(loopback.core().parser_counters().bad_crc, 1u);
  ASSERT_EQ(warnings_with("Clearpath platform: input passed over: offset 0, field 'crc': bad frame (bad CRC, type 0x8002"),
            1u)
      << (warnings.empty() ? std::string("no warning") : warnings.front());
}

TEST_F(PlatformConnectionInput, AFrameThatDoesNotDecodeIsNotDeliveredAndTheLogNamesItsType) {
  const std::vector<std::uint8_t> one_byte{0x01};  // far shorter than any Platform Name
  from_platform(*cp::encode_frame(cp::FrameHeader{0, 9, 0, kPlatformName}, one_byte));

  EXPECT_EQ(names_delivered, 0);
  EXPECT_EQ(loopback.core().counters().decode_errors, 1u);
  EXPECT_EQ(warnings_with("Clearpath platform: input passed over:"), 1u);
  EXPECT_EQ(warnings_with("frame of type 0x8002: "), 1u) << (warnings.empty() ? std::string() : warnings.front());
}

TEST_F(PlatformConnectionInput, ANoisyLineIsAFewLinesAndThenACount) {
  auto bad = name_frame(7);
  bad[bad.size() - 1] ^= 0x01;
  for (int i = 0; i < 50; ++i) from_platform(bad);
  EXPECT_EQ(loopback.core().parser_counters().bad_crc, 50u);  // every one counted
  // (Each damaged frame is two lines' worth: its bad CRC, then the rest of it
  // skipped as garbage while the parser finds the next start byte.)
  EXPECT_EQ(warnings_with("input passed over"),
            static_cast<std::size_t>(bridge::PlatformConnection::kProblemLinesPerWindow));
  EXPECT_GE(warnings_with("bad CRC"), 1u);

  time.advance(rt::kRepeatedLogWindow + 1s);
  from_platform(bad);
  EXPECT_EQ(warnings_with(" more like this in the last"), 1u) << warnings.back();
  EXPECT_EQ(names_delivered, 0);
}

}  // namespace
}  // namespace jaus::test
