// `--multicast GROUP[:PORT]` (issue 32: discovery with multicast only): the
// group is parsed and checked, no --to then means the group alone, and
// without it --to keeps its default; the binary refuses a bad group with
// exit 2 and one line. An OCU session opened with a group (and no peers) works.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <string>

#include <sstream>

#include "jaus/ocu/session.hpp"
#include "ocu/cli_values.hpp"
#include "ocu/ocu_commands.hpp"

namespace jausctl::ocu {
namespace {

constexpr std::uint32_t kGroup = 0xE0010001;  // 224.1.0.1

TEST(MulticastOption, AGroupWithOrWithoutAPort) {
  const auto group = parse_multicast_group("224.1.0.1:3795");
  ASSERT_TRUE(group) << group.error().message();
  EXPECT_EQ(group->address, kGroup);
  EXPECT_EQ(group->port, 3795);
  EXPECT_EQ(parse_multicast_group("239.255.0.7")->port, jaus::transport::kJausPort);
  EXPECT_EQ(parse_multicast_group("10.0.0.1:3794").error().message(),
            "bad multicast group '10.0.0.1:3794': expected 224.0.0.0..239.255.255.255[:port]");
  EXPECT_FALSE(parse_multicast_group("224.1.0.1:0"));
  EXPECT_FALSE(parse_multicast_group("group"));
}

TEST(MulticastOption, NoToMeansLoopbackWithoutMulticastAndOnlyTheGroupWithIt) {
  const auto plain = parse_peers({}, "");
  ASSERT_TRUE(plain);
  ASSERT_EQ(plain->to.size(), 1u);
  EXPECT_EQ(plain->to[0].address, 0x7F000001u);
  EXPECT_EQ(plain->to[0].port, jaus::transport::kJausPort);
  EXPECT_FALSE(plain->multicast);

  const auto group_only = parse_peers({}, "224.1.0.1:3794");
  ASSERT_TRUE(group_only);
  EXPECT_TRUE(group_only->to.empty());
  ASSERT_TRUE(group_only->multicast);
  EXPECT_EQ(group_only->multicast->address, kGroup);

  const auto both = parse_peers({"10.0.0.2", "10.0.0.3:4000"}, "224.1.0.1");
  ASSERT_TRUE(both);
  ASSERT_EQ(both->to.size(), 2u);
  EXPECT_EQ(both->to[1].port, 4000);
  EXPECT_TRUE(both->multicast);

  EXPECT_EQ(parse_peers({}, "10.0.0.1").error().message(),
            "--multicast: bad multicast group '10.0.0.1': expected 224.0.0.0..239.255.255.255[:port]");
  EXPECT_EQ(parse_peers({"localhost"}, "").error().message(),
            "--to: bad endpoint 'localhost': expected an IPv4 address a.b.c.d[:port]");
}

// (Multicast is best effort: where the host cannot join, the session still opens.)
TEST(MulticastOption, ASessionOpensWithAGroupAndNoPeersAndDiscoverNamesTheGroup) {
  SessionOptions options;
  options.to.clear();
  options.multicast = jaus::transport::Ipv4Endpoint{kGroup, 0xF00D};  // a port nothing else listens on
  options.bind = jaus::transport::Ipv4Endpoint{0x7F000001, 0};
  auto session = OcuSession::open(options);
  ASSERT_TRUE(session) << session.error().message();
  EXPECT_TRUE((*session)->on_udp());
  std::ostringstream out;
  std::ostringstream err;
  EXPECT_EQ(run_discover(**session, {std::chrono::milliseconds(200), false}, CommandIo{out, err}), kExitFailure);
  EXPECT_EQ(err.str(), "jausctl discover: no JAUS node heard within 0.2 s (asked the multicast group 224.1.0.1:61453)\n");
}

// stdout and stderr of the built jausctl, and its exit code.
struct Run {
  int exit_code = -1;
  std::string output;
};
Run jausctl(const std::string& args) {
  Run r;
  FILE* pipe = popen((std::string(JAUSCTL_PATH) + " " + args + " 2>&1").c_str(), "r");
  if (!pipe) return r;
  std::array<char, 512> buffer{};
  while (const auto n = std::fread(buffer.data(), 1, buffer.size(), pipe)) r.output.append(buffer.data(), n);
  const int status = pclose(pipe);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

TEST(MulticastOption, TheBinaryRefusesABadGroupAndShowsTheOption) {
  const auto bad = jausctl("discover --multicast 10.1.0.1:3794");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_EQ(bad.output,
            "jausctl discover: --multicast: bad multicast group '10.1.0.1:3794': expected "
            "224.0.0.0..239.255.255.255[:port]\n");
  const auto help = jausctl("discover --help");
  EXPECT_EQ(help.exit_code, 0);
  EXPECT_NE(help.output.find("--multicast GROUP[:PORT]"), std::string::npos) << help.output;
}

}  // namespace
}  // namespace jausctl::ocu
