// Every Clearpath reference frame of tests/data as a UDP datagram (host port
// 40001 -> platform port 40002, or back), dissected by tshark with the
// generated plugin and compared field by field with `jausctl clearpath
// decode --from host|platform`; and a frame with a bad CRC flagged.
#include <gtest/gtest.h>

#include <fstream>

#include "clearpath_frame_check.hpp"
#include "jaus/base/hex.hpp"
#include "pcap_writer.hpp"

namespace jaus::test {
namespace clearpath_frames_test {  // named: the unity build mixes this file's names with others'

struct ReferenceFrame {
  std::string type;
  bool from_platform;
  std::vector<std::uint8_t> bytes;
};

std::vector<ReferenceFrame> reference_frames() {
  std::ifstream in(std::string(JAUS_TEST_DATA_DIR) + "/clearpath-reference-frames.txt");
  std::vector<ReferenceFrame> out;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    const auto first = line.find("  ");
    const auto last = line.rfind("  ");
    ReferenceFrame frame{line.substr(0, first), line.find("dir=p2h") != std::string::npos, {}};
    if (first == std::string::npos || last == first) throw std::runtime_error("bad reference frame line: " + line);
    auto bytes = jaus::parse_hex(line.substr(last + 2));
    if (!bytes) throw std::runtime_error("bad reference frame line: " + line + ": " + bytes.error().message());
    frame.bytes = std::move(*bytes);
    out.push_back(std::move(frame));
  }
  return out;
}

const UdpEndpoint kHost{{127, 0, 0, 64}, 40001};
const UdpEndpoint kPlatform{{127, 0, 0, 65}, 40002};

TEST(TsharkClearpathFrames, EveryReferenceFrameShowsWhatJausctlDecodes) {
  JAUS_REQUIRE_TSHARK();
  TsharkSession session("clearpath");
  const auto frames = reference_frames();
  ASSERT_FALSE(frames.empty());
  PcapWriter pcap((session.dir() / "frames.pcap").string());
  for (const auto& f : frames)
    pcap.add(f.from_platform ? kPlatform : kHost, f.from_platform ? kHost : kPlatform, f.bytes);
  auto corrupt = frames.front().bytes;
  corrupt.back() ^= 0xFF;
  pcap.add(kHost, kPlatform, corrupt);
  pcap.close();

  std::string failure;
  const auto layers = session.dissect(session.dir() / "frames.pcap", {"clearpath.platform_port:40002"}, failure);
  ASSERT_EQ(layers.size(), frames.size() + 1) << failure;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    SCOPED_TRACE("frame " + frames[i].type + " (packet " + std::to_string(i + 1) + ")");
    ASSERT_FALSE(layers[i].is_null()) << "not Clearpath to tshark";
    for (const auto& problem : check_clearpath_frame(session, layers[i], frames[i].bytes, frames[i].from_platform))
      ADD_FAILURE() << problem;
  }
  FieldValues bad;
  flatten_tshark(layers.back(), "", bad);
  EXPECT_EQ(bad.count("clearpath.bad_crc"), 1u) << layers.back().dump();
}

}  // namespace clearpath_frames_test
}  // namespace jaus::test
