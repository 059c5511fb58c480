// Issue 42: emergency holds bound to who made them, across restarts, and
// holds that cannot be kept failing safe. An opened host on loopback takes
// its datagrams through UdpLink::receive_datagram from made-up endpoints
// (127.0.0.x: other hosts); the io_context is polled, never run freely.
//   - the holds file: dialect, ID and host per holder; a generation number
//     in the file and its sidecar, a stale file unreadable;
//   - a restart binds an RA holder's route and a JSS holder's alias slot and
//     JSS route to the host it held from: the same holder clears, nobody else;
//   - a file of the previous version: holds that only the local clear releases;
//   - a state directory that cannot be written refuses the start; a write
//     that fails while running refuses Clear Emergency, said once a streak.
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <boost/asio/io_context.hpp>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "jaus/host/node_host.hpp"
#include "jaus/jss/all.hpp"
#include "jaus/jss/judp.hpp"
#include "jaus/messages/all.hpp"
#include "jaus/wire/message.hpp"

namespace jaus::host {
namespace {

using namespace std::chrono_literals;

constexpr std::uint32_t kLoopback = 0x7F000001;
constexpr std::uint32_t kOperatorHost = 0x7F000009;  // 127.0.0.9
constexpr std::uint32_t kOtherHost = 0x7F000005;     // 127.0.0.5
const Address kOperator{9, 1, 40, 1};
const Address kDriver{1, 1, 33, 1};
const jss::JssId kJssDriver{1, 1, 33};
const jss::JssId kJssOperator{200, 5, 40};
const jss::JssId kOtherJssOperator{77, 3, 1};

std::string read_text(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// ---- the file --------------------------------------------------------------------

class HoldsFile : public ::testing::Test {
 protected:
  HoldsFile() {
    dir = std::filesystem::temp_directory_path() / ("jaus-holds-file-" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
  }
  ~HoldsFile() override { std::filesystem::remove_all(dir); }
  std::filesystem::path dir;
  std::filesystem::path file() const { return dir / "emergency-holds"; }
};

TEST_F(HoldsFile, EachHolderKeepsItsDialectIdAndHost) {
  PersistedHolds holds;
  holds["vehicle"].holders = {PersistedHolder{kOperator, HolderDialect::ra, std::nullopt, kOperatorHost},
                              PersistedHolder{Address{250, 1, 40, 1}, HolderDialect::jss, kJssOperator, 0xC0A80115},
                              PersistedHolder{Address{3, 1, 40, 1}, HolderDialect::ra, std::nullopt, std::nullopt}};
  holds["1.1.38.1"].overflowed = true;
  ASSERT_TRUE(write_emergency_holds(file(), holds, 7));
  const std::string text = read_text(file());
  EXPECT_NE(text.find("vehicle ra 9.1.40.1 127.0.0.9\n"), std::string::npos) << text;
  EXPECT_NE(text.find("vehicle jss 250.1.40.1 200.5.40 192.168.1.21\n"), std::string::npos) << text;
  EXPECT_NE(text.find("vehicle ra 3.1.40.1 -\n"), std::string::npos) << text;
  EXPECT_EQ(read_text(generation_file(file())), "7\n");
  const auto read = read_emergency_holds(file());
  ASSERT_TRUE(read) << read.error().message();
  EXPECT_EQ(read->holds, holds);
  EXPECT_EQ(read->generation, 7u);
  EXPECT_FALSE(read->previous_version);
}

// A holds file older than the last change written (put back from a copy, or
// lost) is never "no holds": it is unreadable, and the host holds everything.
TEST_F(HoldsFile, AStaleOrLostFileIsUnreadable) {
  PersistedHolds holds;
  holds["vehicle"].holders = {PersistedHolder{kOperator, HolderDialect::ra, std::nullopt, kOperatorHost}};
  ASSERT_TRUE(write_emergency_holds(file(), holds, 1));
  std::filesystem::copy_file(file(), dir / "old");
  ASSERT_TRUE(write_emergency_holds(file(), {}, 2));  // the hold was cleared...
  ASSERT_TRUE(read_emergency_holds(file()));
  std::filesystem::rename(dir / "old", file());  // ...and the old file came back
  auto read = read_emergency_holds(file());
  ASSERT_FALSE(read);
  EXPECT_NE(read.error().message().find("stale"), std::string::npos) << read.error().message();
  std::filesystem::remove(file());  // lost: the sidecar says holds were written
  read = read_emergency_holds(file());
  ASSERT_FALSE(read);
  EXPECT_NE(read.error().message().find("missing"), std::string::npos) << read.error().message();
  std::filesystem::remove(generation_file(file()));  // neither: never written, no holds
  read = read_emergency_holds(file());
  ASSERT_TRUE(read);
  EXPECT_TRUE(read->holds.empty());
}

TEST_F(HoldsFile, APreviousVersionsFileIsReadAsHoldersBoundToNoHost) {
  std::ofstream(file()) << "# old\nvehicle 9.1.40.1\nvehicle overflow\n";
  const auto read = read_emergency_holds(file());
  ASSERT_TRUE(read) << read.error().message();
  EXPECT_TRUE(read->previous_version);
  ASSERT_EQ(read->holds.at("vehicle").holders.size(), 1u);
  const PersistedHolder& h = read->holds.at("vehicle").holders.front();
  EXPECT_EQ(h.holder, kOperator);
  EXPECT_EQ(h.dialect, HolderDialect::unknown);
  EXPECT_FALSE(h.host);
  EXPECT_TRUE(read->holds.at("vehicle").overflowed);
  // ...but not beside a sidecar of ours: then it is a stale copy.
  std::ofstream(generation_file(file())) << "3\n";
  EXPECT_FALSE(read_emergency_holds(file()));
}

// ---- the host ---------------------------------------------------------------------

class HoldBinding : public ::testing::Test {
 protected:
  HoldBinding() {
    dir = std::filesystem::temp_directory_path() / ("jaus-hold-binding-" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
  }
  ~HoldBinding() override {
    std::error_code ec;
    std::filesystem::remove_all(dir, ec);
    std::filesystem::remove_all(away(), ec);
  }
  std::filesystem::path away() const { return dir.string() + ".away"; }

  HostConfig config(bool jss = false) const {
    HostConfig c;
    c.link.bind = transport::Ipv4Endpoint{kLoopback, 0};
    c.components = {ComponentSpec{"node_manager", 1, 1, 0, "", {}, 0, {}},
                    ComponentSpec{"primitive_driver", 33, 1, 0, "", {}, 0, {}}};
    c.emergency.state_directory = dir.string();
    c.jss.enabled = jss;
    return c;
  }
  std::unique_ptr<NodeHost> open(bool jss = false) {
    auto host = NodeHost::open(config(jss), io, [this](rt::LogLevel, const std::string& l) { lines.push_back(l); });
    EXPECT_TRUE(host) << host.error().message();
    return host ? std::move(*host) : nullptr;
  }
  std::size_t lines_with(const std::string& text) const {
    return static_cast<std::size_t>(
        std::count_if(lines.begin(), lines.end(), [&](const std::string& l) { return l.find(text) != std::string::npos; }));
  }

  // An RA message from `from` (its datagram from `host`:`port`), as the network brings it.
  template <class M>
  void ra(NodeHost& host, std::uint32_t ip, std::uint16_t port, const Address& from, const M& message) {
    Header header;
    header.source = from;
    header.destination = kDriver;
    std::vector<std::uint8_t> packet(kHeaderSize + kMaxPayloadSize);
    const auto size = wire::encode_message(header, message, packet);
    ASSERT_TRUE(size) << size.error().message();
    packet.resize(*size);
    const auto prefix = transport::frame_prefix(transport::Framing::opc, packet.size());
    std::vector<std::uint8_t> datagram(prefix.view().begin(), prefix.view().end());
    datagram.insert(datagram.end(), packet.begin(), packet.end());
    host.udp_link()->receive_datagram(transport::Ipv4Endpoint{ip, port}, datagram);
    io.poll();
  }
  // A JSS message from the JSS client `from` (its datagram from `ip`:`port`) to our driver.
  template <class M>
  void from_jss(NodeHost& host, std::uint32_t ip, std::uint16_t port, const jss::JssId& from, const M& message) {
    jss::JudpHeader header;
    header.source = from;
    header.destination = kJssDriver;
    header.sequence = sequence++;
    host.udp_link()->receive_datagram(transport::Ipv4Endpoint{ip, port},
                                      jss::make_judp_datagram(header, jss::encode_contents(message)));
    io.poll();
  }
  static bool in_emergency(NodeHost& host) {
    return host.node().find(kDriver)->state() == rt::PrimaryStatus::emergency;
  }

  std::filesystem::path dir;
  boost::asio::io_context io;
  std::vector<std::string> lines;
  std::uint16_t sequence = 0;
};

// Finding 2, RA: the holder's ID is bound to its host from the start of the
// next run; from another host it is a refused claim, from its own host (a
// new port: its OCU restarted too) it clears.
TEST_F(HoldBinding, AnRaHolderIsItsHostsAcrossARestart) {
  {
    auto host = open();
    ASSERT_TRUE(host);
    ra(*host, kOperatorHost, 40000, kOperator, msg::SetEmergency{});
    ASSERT_TRUE(in_emergency(*host));
    host->stop("test");
  }
  EXPECT_NE(read_text(dir / "emergency-holds").find("vehicle ra 9.1.40.1 127.0.0.9"), std::string::npos);
  auto host = open();
  ASSERT_TRUE(host);
  EXPECT_TRUE(in_emergency(*host));
  EXPECT_EQ(host->emergency_latch("vehicle")->holders(), std::vector<Address>{kOperator});
  ra(*host, kOtherHost, 40000, kOperator, msg::ClearEmergency{});  // its ID, another host
  EXPECT_TRUE(in_emergency(*host));
  EXPECT_EQ(host->udp_link()->counters().dropped_for(transport::DropReason::route_claim), 1u);
  ra(*host, kOperatorHost, 41000, kOperator, msg::ClearEmergency{});
  EXPECT_FALSE(in_emergency(*host));
}

// Finding 2, JSS: the JSS holder gets its alias slot back, bound to its JSS
// ID and host; another JSS client (another host, never held anything) gets
// another slot and its Clear Emergency releases nothing; the holder's JSS ID
// from another host is refused; an RA datagram forging the alias is dropped.
TEST_F(HoldBinding, AJssHolderGetsItsSlotBackAndNoOtherClientClearsIt) {
  const Address alias{250, 1, 40, 1};
  {
    auto host = open(/*jss=*/true);
    ASSERT_TRUE(host);
    from_jss(*host, kOperatorHost, 3794, kJssOperator, jss::msg::SetEmergency{{1}});
    ASSERT_TRUE(in_emergency(*host));
    ASSERT_EQ(host->emergency_latch("vehicle")->holders(), std::vector<Address>{alias});
    host->stop("test");
  }
  EXPECT_NE(read_text(dir / "emergency-holds").find("vehicle jss 250.1.40.1 200.5.40 127.0.0.9"), std::string::npos);
  auto host = open(/*jss=*/true);
  ASSERT_TRUE(host);
  EXPECT_TRUE(in_emergency(*host));
  EXPECT_EQ(host->jss_face()->client_of_alias(alias), kJssOperator);
  from_jss(*host, kOtherHost, 3794, kOtherJssOperator, jss::msg::ClearEmergency{{1}});
  EXPECT_TRUE(in_emergency(*host));
  EXPECT_EQ(host->jss_face()->client_of_alias(Address{250, 2, 1, 1}), kOtherJssOperator);  // slot 2, not 1
  from_jss(*host, kOtherHost, 3795, kJssOperator, jss::msg::ClearEmergency{{1}});  // its JSS ID, another host
  EXPECT_TRUE(in_emergency(*host));
  EXPECT_EQ(host->udp_link()->counters().dropped_for(transport::DropReason::route_claim), 1u);
  ra(*host, kOperatorHost, 40000, alias, msg::ClearEmergency{});  // the alias over RA, even from its host
  EXPECT_TRUE(in_emergency(*host));
  EXPECT_EQ(host->udp_link()->counters().dropped_for(transport::DropReason::alias_source), 1u);
  from_jss(*host, kOperatorHost, 3900, kJssOperator, jss::msg::ClearEmergency{{1}});  // the holder, its host
  EXPECT_FALSE(in_emergency(*host));
}

// A file of the previous version names no host: its holders are held until
// the local clear, which the same ID cannot shortcut from anywhere.
TEST_F(HoldBinding, APreviousVersionsHoldIsReleasedOnlyByTheLocalClear) {
  std::ofstream(dir / "emergency-holds") << "vehicle 9.1.40.1\n";
  auto host = open();
  ASSERT_TRUE(host);
  EXPECT_TRUE(in_emergency(*host));
  EXPECT_EQ(lines_with("previous version"), 1u);
  ra(*host, kOperatorHost, 40000, kOperator, msg::ClearEmergency{});
  EXPECT_TRUE(in_emergency(*host));
  EXPECT_GE(host->clear_emergency_holds_locally("test"), 1u);
  EXPECT_FALSE(in_emergency(*host));
}

TEST_F(HoldBinding, AStaleHoldsFileHoldsEverythingUntilTheLocalClear) {
  ASSERT_TRUE(write_emergency_holds(dir / "emergency-holds", {}, 4));
  std::ofstream(generation_file(dir / "emergency-holds")) << "5\n";  // a change the file does not have
  auto host = open();
  ASSERT_TRUE(host);
  EXPECT_TRUE(in_emergency(*host));
  EXPECT_EQ(lines_with("stale"), 1u);
  EXPECT_GE(host->clear_emergency_holds_locally("test"), 1u);
  EXPECT_FALSE(in_emergency(*host));
}

// Finding 5: a state directory that cannot take a file refuses the start
// (as root too: a path through a regular file is no directory for anyone).
TEST_F(HoldBinding, AStateDirectoryThatCannotBeWrittenRefusesTheStart) {
  std::ofstream(dir / "file") << "not a directory\n";
  HostConfig c = config();
  c.emergency.state_directory = (dir / "file" / "state").string();
  auto host = NodeHost::open(c, io);
  ASSERT_FALSE(host);
  EXPECT_NE(host.error().message().find("not started"), std::string::npos) << host.error().message();
  c.emergency.state_directory = (dir / "file").string();
  host = NodeHost::open(c, io);
  ASSERT_FALSE(host);
  EXPECT_NE(host.error().message().find("not a directory"), std::string::npos) << host.error().message();
}

// Finding 5: a write that fails while running (the directory replaced by a
// file: root is not stopped by permissions) is said once per failing streak
// at error level, and refuses Clear Emergency; once a write succeeds again
// (retried on a timer) it is said, and the clear is taken.
TEST_F(HoldBinding, AFailingWriteRefusesClearsAndIsSaidOncePerStreak) {
  auto host = open();
  ASSERT_TRUE(host);
  ra(*host, kOperatorHost, 40000, kOperator, msg::SetEmergency{});
  ASSERT_TRUE(in_emergency(*host));
  std::filesystem::rename(dir, away());
  std::ofstream(dir) << "the state directory is gone\n";
  const Address second{9, 2, 40, 1};
  for (int i = 0; i < 10; ++i) {
    ra(*host, kOperatorHost, 40001, second, msg::SetEmergency{});  // a change to write: it fails
    ra(*host, kOperatorHost, 40000, kOperator, msg::ClearEmergency{});
    ra(*host, kOperatorHost, 40001, second, msg::ClearEmergency{});
  }
  EXPECT_TRUE(in_emergency(*host));
  EXPECT_EQ(host->emergency_latch("vehicle")->holders(), (std::vector<Address>{kOperator, second}));
  EXPECT_EQ(lines_with("emergency holds not persisted"), 1u);
  EXPECT_GE(lines_with("refused: the emergency holds cannot be persisted"), 1u);
  // The disk is back: the retry writes, and the clears are taken again.
  std::filesystem::remove(dir);
  std::filesystem::rename(away(), dir);
  const auto deadline = std::chrono::steady_clock::now() + 20s;
  while (lines_with("persisted again") == 0 && std::chrono::steady_clock::now() < deadline) io.run_for(50ms);
  EXPECT_EQ(lines_with("persisted again"), 1u);
  EXPECT_NE(read_text(dir / "emergency-holds").find("vehicle ra 9.2.40.1 127.0.0.9"), std::string::npos);
  ra(*host, kOperatorHost, 40000, kOperator, msg::ClearEmergency{});
  ra(*host, kOperatorHost, 40001, second, msg::ClearEmergency{});
  EXPECT_FALSE(in_emergency(*host));
  host->stop("test");
  EXPECT_EQ(read_text(dir / "emergency-holds").find(" ra "), std::string::npos);
}

}  // namespace
}  // namespace jaus::host
