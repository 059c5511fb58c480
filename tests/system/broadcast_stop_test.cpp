// The operator's stop tools tell the truth (issue 49), with real processes:
// `jausctl emergency 1.255.255.255 set` run the moment jausd starts stops
// every component of the subsystem, each confirming it, every time; to a
// subsystem with nobody it fails saying nobody confirmed it; and one user's
// runs are one operator, so `set` then `clear` needs no --as. jausd on
// 127.0.0.130, jausctl from 127.0.0.131, the test's own OCU (to read every
// component's state) on 127.0.0.132. Only outcomes are asserted, with
// generous deadlines (ASan on a loaded machine).
#include <gtest/gtest.h>

#include <fstream>
#include <set>
#include <sstream>
#include <thread>

#include "default_jausd.hpp"
#include "jaus/messages/all.hpp"
#include "jaus/ocu/session.hpp"

namespace jaus::test {
namespace {

using namespace std::chrono_literals;

constexpr const char* kNode = "127.0.0.130";
constexpr const char* kJausctlBind = "127.0.0.131:0";
const Address kManager{1, 1, 1, 1};

// "... confirmed by 13 components (1.1.1.1, 1.1.33.1, ...) in 0.7 s": the list.
std::set<std::string> confirmed_in(const std::string& output) {
  std::set<std::string> out;
  const auto at = output.find("components (");
  if (at == std::string::npos) return out;
  const auto start = at + std::string("components (").size();
  std::istringstream list(output.substr(start, output.find(')', start) - start));
  for (std::string item; std::getline(list, item, ',');) out.insert(item.substr(item.find_first_not_of(' ')));
  return out;
}

// The test's own OCU, to read what the node says of itself.
class Observer {
 public:
  Observer() {
    ocu::SessionOptions options;
    // Not in subsystem 254, where jausctl keeps its operator ID
    // (kept_operator_id.hpp): a drawn 254.132 once made the node refuse ours.
    options.self = Address{253, 132, 40, 1};
    options.to = {transport::Ipv4Endpoint{*transport::parse_ipv4(kNode), transport::kJausPort}};
    options.bind = transport::Ipv4Endpoint{*transport::parse_ipv4("127.0.0.132"), 0};
    auto opened = ocu::OcuSession::open(options);
    if (!opened) throw std::runtime_error(opened.error().message());
    session_ = std::move(*opened);
  }

  // Every component of node 1 (its node manager's Report Configuration).
  std::set<std::string> components() {
    for (int attempt = 0; attempt < 20; ++attempt) {
      auto reply = session_->request(kManager, msg::QueryConfiguration{{msg::identification::kNode}},
                                     {msg::ReportConfiguration::code}, 1s);
      if (!reply) continue;
      msg::ReportConfiguration decoded{};
      if (!wire::decode_payload_into(reply->payload, decoded, wire::Dialect::ra, kHeaderSize)) continue;
      std::set<std::string> out;
      for (const auto& node : decoded.nodes)
        for (const auto& c : node.components)
          out.insert(Address{1, node.node_id, c.component_id, c.instance}.to_string());
      return out;
    }
    return {};
  }

  // The primary status of `component` (Report Component Status), if it answers.
  std::optional<unsigned> status(const std::string& component) {
    const auto address = *Address::parse(component);
    for (int attempt = 0; attempt < 10; ++attempt) {
      auto reply = session_->request(address, msg::QueryComponentStatus{}, {msg::ReportComponentStatus::code}, 1s);
      if (!reply) continue;
      msg::ReportComponentStatus report{};
      if (wire::decode_payload_into(reply->payload, report, wire::Dialect::ra, kHeaderSize))
        return report.primary_status & 0x0F;
    }
    return std::nullopt;
  }

 private:
  std::unique_ptr<ocu::OcuSession> session_;
};

constexpr unsigned kEmergency = static_cast<unsigned>(msg::PrimaryStatus::emergency);
constexpr unsigned kReady = static_cast<unsigned>(msg::PrimaryStatus::ready);

// The "done when" of issue 49, from a fresh start each time: jausd started
// and, at once, the broadcast stop; every component confirms it and reports
// Emergency. 20 fresh starts in the Release tree, as the issue asks (about a
// second each); 4 in the sanitizer tree, where each takes several.
#if defined(__has_feature)
#if __has_feature(address_sanitizer)
#define JAUS_BROADCAST_STOP_ASAN 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__)
#define JAUS_BROADCAST_STOP_ASAN 1
#endif
#ifdef JAUS_BROADCAST_STOP_ASAN
constexpr int kFreshStarts = 4;
#else
constexpr int kFreshStarts = 20;
#endif
TEST(BroadcastStop, FromAFreshStartEveryComponentOfTheSubsystemStopsAndConfirmsIt) {
  for (int run = 0; run < kFreshStarts; ++run) {
    SCOPED_TRACE("fresh start " + std::to_string(run));
    DefaultJausd jausd("broadcast-stop-" + std::to_string(run), 1, kNode);
    ASSERT_TRUE(jausd.started());
    // At once: the node may not even have its socket yet.
    auto stop = jausd.jausctl("stop", {"emergency", "1.255.255.255", "set", "--timeout", "20"}, kJausctlBind);
    ASSERT_EQ(stop->wait(60s), 0) << stop->output() << jausd.output();
    const auto confirmed = confirmed_in(stop->output());
    Observer observer;
    const auto components = observer.components();
    ASSERT_FALSE(components.empty()) << jausd.output();
    EXPECT_EQ(confirmed, components) << stop->output();
    EXPECT_NE(stop->output().find("confirmed by " + std::to_string(components.size()) + " components"),
              std::string::npos)
        << stop->output();
    for (const auto& component : components) EXPECT_EQ(observer.status(component), kEmergency) << component;
  }
}

TEST(BroadcastStop, ToASubsystemWithNobodyItFailsSayingNobodyConfirmedIt) {
  DefaultJausd jausd("broadcast-nobody", 1, kNode);
  ASSERT_TRUE(jausd.started());
  auto stop = jausd.jausctl("stop", {"emergency", "9.255.255.255", "set", "--timeout", "1"}, kJausctlBind);
  ASSERT_EQ(stop->wait(60s), 1) << stop->output();
  EXPECT_NE(stop->output().find("Set Emergency to 9.255.255.255 by 254."), std::string::npos) << stop->output();
  EXPECT_NE(stop->output().find(": no component confirmed it within "), std::string::npos) << stop->output();
  EXPECT_EQ(stop->output().find(" sent "), std::string::npos) << "never 'sent' for what nobody confirmed";
  Observer observer;
  EXPECT_EQ(observer.status("1.1.33.1"), kReady) << "another subsystem's stop";
}

// One user's runs are one operator: the ID kept in its state directory.
TEST(BroadcastStop, SetThenClearWithoutAsIsOneOperator) {
  DefaultJausd jausd("broadcast-set-clear", 1, kNode);
  ASSERT_TRUE(jausd.started());
  auto set = jausd.jausctl("set", {"emergency", "1.255.255.255", "set", "--timeout", "20"}, kJausctlBind);
  ASSERT_EQ(set->wait(60s), 0) << set->output() << jausd.output();
  std::ifstream kept_file(jausd.state_home() / "jaus" / "operator-id");
  std::string kept;
  std::getline(kept_file, kept);
  ASSERT_FALSE(kept.empty());
  EXPECT_NE(set->output().find("Set Emergency to 1.255.255.255 by " + kept + ": confirmed by "), std::string::npos)
      << set->output();
  Observer observer;
  EXPECT_EQ(observer.status("1.1.33.1"), kEmergency);

  auto clear = jausd.jausctl("clear", {"emergency", "1.255.255.255", "clear", "--timeout", "5"}, kJausctlBind);
  ASSERT_EQ(clear->wait(60s), 0) << clear->output() << jausd.output();
  EXPECT_NE(clear->output().find("Clear Emergency to 1.255.255.255 by " + kept + ": confirmed by "), std::string::npos)
      << clear->output();
  const auto until = std::chrono::steady_clock::now() + 20s;
  std::optional<unsigned> state;
  while ((state = observer.status("1.1.33.1")) != kReady && std::chrono::steady_clock::now() < until)
    std::this_thread::sleep_for(100ms);
  EXPECT_EQ(state, kReady) << jausd.output();
}

}  // namespace
}  // namespace jaus::test
