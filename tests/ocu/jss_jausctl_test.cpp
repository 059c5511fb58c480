// The built jausctl with --dialect jss against a node with its JSS face on
// loopback (a node host on a thread of this process, opened as jausd opens
// it): discover, status, query, control held past the component's timeout
// until SIGINT, then released.
#include <utility>  // Boost 1.74's Asio headers need it first

#include <gtest/gtest.h>

#include <boost/asio/executor_work_guard.hpp>
#include <boost/asio/post.hpp>
#include <future>
#include <nlohmann/json.hpp>
#include <thread>

#include "jaus/host/node_host.hpp"
#include "jausctl_process.hpp"

namespace jausctl::test {
namespace {

using namespace std::chrono_literals;

const jaus::Address kRaDriver{1, 1, 33, 1};

class JssJausctl : public ::testing::Test {
 protected:
  template <class F>
  auto on_host(F f) {
    std::packaged_task<decltype(f())()> task(f);
    auto result = task.get_future();
    boost::asio::post(context, [&task] { task(); });
    return result.get();
  }

  void SetUp() override {
    jaus::host::HostConfig config;
    config.node.subsystem = 1;
    config.node.node = 1;
    config.link.bind = jaus::transport::Ipv4Endpoint{0x7F000001, 0};
    config.settings.identity.subsystem_name = "jss-vehicle";
    config.settings.defaults.controller_timeout = kControllerTimeout;
    config.components = {jaus::host::ComponentSpec{"node_manager", 1, 1, 0, "", {}, 0, {}},
                         jaus::host::ComponentSpec{"primitive_driver", 33, 1, 0, "driver", {}, 0, {}},
                         jaus::host::ComponentSpec{"velocity_state_sensor", 42, 1, 0, "velocity", {}, 0, {}}};
    config.jss.enabled = true;
    auto opened = jaus::host::NodeHost::open(config, context);
    ASSERT_TRUE(opened) << opened.error().message();
    host = std::move(*opened);
    port = host->udp_link()->local_endpoint().port;
    thread = std::thread([this] { context.run(); });
  }
  void TearDown() override {
    if (host) on_host([&] { host->stop("test over"); });
    work.reset();
    context.stop();
    if (thread.joinable()) thread.join();
    host.reset();
  }
  // What every command takes to reach the node.
  std::vector<std::string> args(std::vector<std::string> command) const {
    command.insert(command.end(), {"--dialect", "jss", "--to", "127.0.0.1:" + std::to_string(port), "--timeout", "5"});
    return command;
  }
  bool eventually(const std::function<bool()>& condition) {
    const auto deadline = std::chrono::steady_clock::now() + 10s;
    while (!on_host(condition)) {
      if (std::chrono::steady_clock::now() > deadline) return false;
      std::this_thread::sleep_for(10ms);
    }
    return true;
  }
  bool driver_controlled() {
    return on_host([&] { return host->node().find(kRaDriver)->control().controller().has_value(); });
  }

  static constexpr jaus::rt::Duration kControllerTimeout = 2s;  // Report Timeout: 2 s
  boost::asio::io_context context;
  std::optional<boost::asio::executor_work_guard<boost::asio::io_context::executor_type>> work{context.get_executor()};
  std::unique_ptr<jaus::host::NodeHost> host;
  std::uint16_t port = 0;
  std::thread thread;
};

TEST_F(JssJausctl, DiscoversStatusAndQueriesTheVelocityState) {
  auto r = run(args({"discover", "--wait", "5"}));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("1             subsystem (vehicle)   10001   jss-vehicle"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("1.1.33        component             -       driver"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("PrimitiveDriver 1.0"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("VelocityStateSensor 1.0"), std::string::npos) << r.out;

  r = run(args({"discover", "--json"}));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto system = nlohmann::json::parse(r.out);
  ASSERT_EQ(system["subsystems"].size(), 1u);
  EXPECT_EQ(system["subsystems"][0]["name"], "jss-vehicle");

  r = run(args({"status", "1.1.33"}));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out)["primary_status"], "ready");

  r = run(args({"query", "1.1.42", "Query Velocity State", "--pv", "0x1"}));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto report = nlohmann::json::parse(r.out);
  EXPECT_EQ(report["name"], "Report Velocity State");
  EXPECT_EQ(report["source"], "1.1.42");
  EXPECT_TRUE(report["fields"].contains("velocity_x_mps")) << r.out;
}

TEST_F(JssJausctl, ControlHeldPastTheTimeoutUntilSigintThenReleased) {
  Jausctl control(args({"control", "1.1.33", "--authority", "9"}));
  ASSERT_TRUE(control.wait_for_output("granted"));
  EXPECT_NE(control.out().find("timeout 2 s, requested again every 1 s"), std::string::npos) << control.out();
  std::this_thread::sleep_for(kControllerTimeout + 1s);  // held past the timeout: requested again
  EXPECT_TRUE(driver_controlled());
  control.signal(SIGINT);
  const auto r = control.finish();
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("control of 1.1.33 released after "), std::string::npos) << r.out;
  EXPECT_TRUE(eventually([&] { return !host->node().find(kRaDriver)->control().controller().has_value(); }));
}

TEST_F(JssJausctl, EmergencySetAndClearedByTheSameId) {
  auto r = run(args({"emergency", "1.1.33", "set", "--as", "200.5.1"}));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out, "1.1.33: emergency set by 200.5.1 (state Emergency)\n");
  r = run(args({"emergency", "1.1.33", "clear", "--as", "200.5.1"}));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out.rfind("1.1.33: emergency cleared by 200.5.1", 0), 0u) << r.out;
}

TEST_F(JssJausctl, SubscribePrintsOneLinePerEventAndCancels) {
  const auto r = run(args({"subscribe", "1.1.42", "Report Velocity State", "--rate", "10", "--count", "3"}));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 3);
  EXPECT_NE(r.err.find("event cancelled"), std::string::npos) << r.err;
}

TEST(JssJausctlInput, BadInputIsOneLineAndExitTwo) {
  auto r = run({"status", "1.1", "--dialect", "jss"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err, "jausctl status: bad JSS ID '1.1': expected S.N.C (subsystem.node.component)\n");
  r = run({"control", "1.255.33", "--authority", "1", "--dialect", "jss"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err, "jausctl control: bad JSS ID '1.255.33': a broadcast ID (65535, 255) is not allowed here\n");
  r = run({"subscribe", "1.1.42", "0x4404", "--dialect", "jss"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err, "jausctl subscribe: give either --rate HZ or --every-change\n");
  r = run({"query", "1.1.42", "0x1234", "--dialect", "jss"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err, "jausctl query: unknown JSS message ID 0x1234 (jausctl msg list --dialect jss shows every ID)\n");
}

TEST(JssJausctlInput, MsgDecodesTheWorkedExampleDatagram) {
  const auto r = run({"msg", "decode",
                      "0200110001010101000101"
                      "2a00002b020000",
                      "--dialect", "jss"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto json = nlohmann::json::parse(r.out);
  ASSERT_EQ(json["packets"].size(), 1u);
  EXPECT_EQ(json["packets"][0]["message"]["name"], "Query Identification");
}

}  // namespace
}  // namespace jausctl::test
