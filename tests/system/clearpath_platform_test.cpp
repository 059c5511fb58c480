// The bridge end to end, with real processes: jausd's platform is a separate
// clearpath-sim, over UDP or a PTY (a serial line), and jausctl is the OCU.
// The simulator prints its true state (--status-every), so the checks read
// what the wheels really do, not what jausd believes. Only outcomes are
// asserted, with generous deadlines (a loaded machine, sanitizers).
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <functional>
#include <sstream>
#include <thread>

#include <nlohmann/json.hpp>

#include "clearpath_simulator.hpp"
#include "default_jausd.hpp"

namespace jaus::test {
namespace {

using namespace std::chrono_literals;
using Json = nlohmann::json;

constexpr const char* kNode = "127.0.0.32";
constexpr const char* kSimAddress = "127.0.0.33";
constexpr const char* kDriver = "7.1.33.1";
constexpr const char* kPoseSensor = "7.1.38.1";
constexpr const char* kVelocitySensor = "7.1.42.1";
// 60 % forward, 20 % to the left (JAUS: negative rotational effort).
constexpr const char* kForwardAndLeft =
    R"({"name":"Set Wrench Effort","fields":{"propulsive_linear_effort_x_percent":60,"propulsive_rotational_effort_z_percent":-20}})";

using Simulator = ClearpathSimulator;
bool moving(const Json& s) { return Simulator::moving(s); }
bool stopped(const Json& s) { return Simulator::stopped(s); }

class ClearpathPlatform : public ::testing::TestWithParam<Simulator::Line> {
 protected:
  void start(Simulator::Line line, std::vector<std::string> sim_options = {}) {
    dir = std::filesystem::temp_directory_path() / ("jaus-clearpath-" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    sim = std::make_unique<Simulator>(line, dir, "sim", kSimAddress, std::move(sim_options));
    ASSERT_TRUE(sim->started());
    const auto platform = sim->platform_config();
    ASSERT_TRUE(platform) << sim->process().output();
    jausd = std::make_unique<DefaultJausd>("clearpath", 7, kNode, *platform);
    ASSERT_TRUE(jausd->started());
    // Up, and the driver Ready: the platform answers (longer under sanitizers).
    ASSERT_TRUE(poll_status(kDriver, "ready", 30s)) << jausd->output();
  }
  void TearDown() override {
    jausd.reset();
    sim.reset();
    std::error_code ignored;
    std::filesystem::remove_all(dir, ignored);
  }

  std::unique_ptr<ChildProcess> jausctl(const std::string& name, std::vector<std::string> args,
                                        const std::string& bind) {
    auto child = jausd->jausctl_own_id(name, std::move(args), bind);
    EXPECT_TRUE(child->started());
    return child;
  }
  // Drives forward and left until SIGINT (a test stops it once it has seen
  // what it waits for, not after a time it guessed); 60 s only if it never does.
  std::unique_ptr<ChildProcess> drive() {
    return jausctl("controller",
                   {"control", kDriver, "--authority", "10", "--rate", "10", "--for", "60", "--send", kForwardAndLeft},
                   "127.0.0.34:0");
  }
  // The first JSON line of a jausctl's output.
  std::optional<Json> json_of(ChildProcess& child) {
    if (child.wait(20s) != 0) return std::nullopt;
    std::istringstream lines(child.output());
    for (std::string line; std::getline(lines, line);)
      if (!line.empty() && line.front() == '{') {
        const Json j = Json::parse(line, nullptr, false);
        if (!j.is_discarded()) return j;
      }
    return std::nullopt;
  }
  std::optional<Json> query(const std::string& address, const std::string& code, const std::string& pv) {
    auto child = jausctl("query", {"query", address, code, "--pv", pv, "--timeout", "2"}, "127.0.0.35:0");
    auto j = json_of(*child);
    if (!j || !j->contains("fields")) return std::nullopt;
    return (*j)["fields"];
  }
  bool poll_status(const std::string& address, const std::string& status, std::chrono::seconds deadline) {
    const auto until = std::chrono::steady_clock::now() + deadline;
    while (std::chrono::steady_clock::now() < until) {
      auto child = jausctl("status", {"status", address, "--timeout", "1"}, "127.0.0.36:0");
      if (auto j = json_of(*child); j && j->value("primary_status", "") == status) return true;
      std::this_thread::sleep_for(200ms);
    }
    return false;
  }

  std::filesystem::path dir;
  std::unique_ptr<Simulator> sim;
  std::unique_ptr<DefaultJausd> jausd;
};

TEST_P(ClearpathPlatform, DrivesForwardAndTurnsLeftAndThePoseSaysSo) {
  start(GetParam());
  auto controller = drive();
  ASSERT_TRUE(sim->wait_for(moving, 15s)) << controller->output() << jausd->output();
  // The platform turns left (its yaw rate is right-handed: positive = left)...
  ASSERT_TRUE(sim->wait_for([](const Json& s) { return s["yaw_rate_rps"].get<double>() > 0.2; }, 5s));
  // ...and so do the JAUS reports: yaw rate negative (left) once it turns at full rate.
  std::optional<Json> velocity;
  for (int i = 0; i < 10; ++i) {
    velocity = query(kVelocitySensor, "0x2404", "0x1FF");
    if (velocity && (*velocity)["yaw_rate_rps"].get<double>() < -0.5) break;
    std::this_thread::sleep_for(100ms);
  }
  ASSERT_TRUE(velocity);
  EXPECT_GT((*velocity)["velocity_x_mps"].get<double>(), 0.3) << velocity->dump();
  EXPECT_LT((*velocity)["yaw_rate_rps"].get<double>(), -0.5) << velocity->dump();  // (0.4 - 0.8 m/s) / 0.55 m
  // Turned well left (the simulator's yaw is positive to the left), then released.
  EXPECT_TRUE(sim->wait_for([](const Json& s) { return s["yaw_rad"].get<double>() > 0.5; }, 15s))
      << sim->state()->dump();
  controller->signal(SIGINT);
  EXPECT_EQ(controller->wait(20s), 0) << controller->output();
  // Control released: the wheels stop, and the heading is left of north (start heading 0).
  EXPECT_TRUE(sim->wait_for(stopped, 10s));
  const auto pose = query(kPoseSensor, "0x2402", "0x1FF");
  ASSERT_TRUE(pose);
  EXPECT_LT((*pose)["yaw_rad"].get<double>(), -0.3) << pose->dump();
  EXPECT_LT((*pose)["longitude_deg"].get<double>(), -73.0) << pose->dump();  // drifted west
}

INSTANTIATE_TEST_SUITE_P(OverUdpAndASerialLine, ClearpathPlatform,
                         ::testing::Values(Simulator::Line::udp, Simulator::Line::pty),
                         [](const ::testing::TestParamInfo<Simulator::Line>& line) { return line.param == Simulator::Line::udp ? "udp" : "pty"; });

class ClearpathPlatformUdp : public ClearpathPlatform {};

TEST_F(ClearpathPlatformUdp, SetEmergencyStopsTheWheels) {
  start(Simulator::Line::udp);
  auto controller = drive();
  ASSERT_TRUE(sim->wait_for(moving, 15s)) << controller->output();
  auto emergency = jausctl("emergency", {"emergency", kDriver, "set", "--timeout", "5"}, "127.0.0.37:0");
  EXPECT_EQ(emergency->wait(20s), 0) << emergency->output();
  EXPECT_TRUE(sim->wait_for(stopped, 10s)) << sim->state()->dump();
  std::this_thread::sleep_for(1s);
  EXPECT_TRUE(stopped(*sim->state()));
  // The operator tool stops too: it stopped sending, released control and said why (exit 3).
  EXPECT_EQ(controller->wait(20s), 3) << controller->output();
}

TEST_F(ClearpathPlatformUdp, AKilledJausdLetsThePlatformsWatchdogStopTheWheels) {
  start(Simulator::Line::udp);
  auto controller = drive();
  ASSERT_TRUE(sim->wait_for(moving, 15s));
  jausd->process().signal(SIGKILL);
  // The watchdog (0.5 s without a command) and the deceleration.
  EXPECT_TRUE(sim->wait_for([](const Json& s) { return stopped(s) && s["watchdog_expired"].get<bool>(); }, 10s))
      << sim->state()->dump();
}

TEST_F(ClearpathPlatformUdp, AnUnpluggedPlatformIsFailureThenReadyAndNothingMoves) {
  start(Simulator::Line::udp);
  {
    auto controller = drive();
    ASSERT_TRUE(sim->wait_for(moving, 15s));
    controller->signal(SIGINT);
    EXPECT_EQ(controller->wait(20s), 0);
  }
  sim->process().signal(SIGKILL);
  sim->process().wait(5s);
  EXPECT_TRUE(poll_status(kDriver, "failure", 15s)) << jausd->output();
  // Plugged back: a fresh simulator on the same port, at rest.
  sim = std::make_unique<Simulator>(Simulator::Line::udp, dir, "sim-again", kSimAddress);
  ASSERT_TRUE(sim->started());
  EXPECT_TRUE(poll_status(kDriver, "ready", 20s)) << jausd->output();
  std::this_thread::sleep_for(1s);
  for (const auto& s : sim->states()) EXPECT_TRUE(stopped(s)) << s.dump();
  // And it moves again when commanded.
  auto controller = drive();
  EXPECT_TRUE(sim->wait_for(moving, 15s)) << controller->output();
}

// 15 % of frames each way get a flipped bit (about 1 % of bytes) for 30 s:
// the simulator rejects every corrupted command (its wheels never go faster
// than commanded), jausd rejects every corrupted report (its dead-reckoned
// distance matches the simulator's), commands still get through, and the
// lost probes never make jausd take the platform for deaf.
TEST_F(ClearpathPlatformUdp, CorruptedFramesAreNeverActedOn) {
  start(Simulator::Line::udp, {"--corrupt-rate", "0.15", "--seed", "7"});
  const auto x0 = query(kPoseSensor, "0x2403", "0x7F");  // Report Local Pose
  auto controller = jausctl("controller",
                            {"control", kDriver, "--authority", "10", "--rate", "10", "--for", "5", "--send",
                             R"({"name":"Set Wrench Effort","fields":{"propulsive_linear_effort_x_percent":50}})"},
                            "127.0.0.34:0");
  EXPECT_EQ(controller->wait(60s), 0) << controller->output() << jausd->output();
  ASSERT_TRUE(sim->wait_for(stopped, 5s));
  const auto states = sim->states();
  ASSERT_FALSE(states.empty());
  double fastest = 0;
  bool reached = false;
  for (const auto& s : states) {
    fastest = std::max({fastest, std::abs(s["left_mps"].get<double>()), std::abs(s["right_mps"].get<double>())});
    reached = reached || s["speed_mps"].get<double>() > 0.45;
  }
  EXPECT_LE(fastest, 0.5 + 1e-6);  // 50 % output of a 1 m/s platform, never more
  EXPECT_TRUE(reached);            // and the commands got through
  EXPECT_GT(states.back()["frames_rejected"].get<int>(), 0);
  // Probes and ACKs were lost too, never a second's worth: the platform was never taken for deaf.
  EXPECT_EQ(jausd->output().find("no longer hears us"), std::string::npos) << jausd->output();
  // The platform went straight ahead from its start: its x is the distance.
  // Up to about 2.4 m (5 s at up to 0.5 m/s, accelerating first at 2 m/s^2);
  // less when a stall of this loaded machine let the watchdog stop it, so
  // only far enough for the comparison below to mean something.
  const double travelled = states.back()["x_m"].get<double>();
  EXPECT_GT(travelled, 0.5);
  const auto local = query(kPoseSensor, "0x2403", "0x7F");
  ASSERT_TRUE(local) << jausd->output();
  EXPECT_NEAR((*local)["x_m"].get<double>(), travelled, 0.1 * travelled) << local->dump();
  (void)x0;
}

// A one-way line: the platform stops hearing jausd while its data still flows
// (clearpath-sim's `deaf on`; --deaf-after does it at a set time). While
// driving only setpoints go, never acknowledged: jausd's probe finds out, the
// driver goes to Failure and the controller sees it. When the platform hears
// again the driver is Ready, and nothing moves until a new command.
TEST_F(ClearpathPlatformUdp, APlatformThatNoLongerHearsIsFailureAndNothingMovesWhenItHearsAgain) {
  start(Simulator::Line::udp);
  auto controller = drive();
  ASSERT_TRUE(sim->wait_for(moving, 15s)) << controller->output();
  const auto deaf_at = std::chrono::steady_clock::now();
  ASSERT_TRUE(sim->deafen(true));
  // The controller sees Failure: it stops sending and says so (exit 3).
  EXPECT_EQ(controller->wait(20s), 3) << controller->output() << jausd->output();
  // About a second of probing (the rest is the controller's status report and
  // a loaded machine); without the probe the driver would stay Ready.
  EXPECT_LT(std::chrono::steady_clock::now() - deaf_at, 5s);
  EXPECT_NE(controller->output().find("Failure"), std::string::npos) << controller->output();
  // The platform's own watchdog stopped its wheels.
  EXPECT_TRUE(sim->wait_for([](const Json& s) { return stopped(s) && s["watchdog_expired"].get<bool>(); }, 10s))
      << sim->state()->dump();
  // Still deaf across jausd's reconnects (each goes down again after about a
  // second): the driver stays in Failure, and the loss is logged once.
  std::this_thread::sleep_for(3s);
  EXPECT_TRUE(poll_status(kDriver, "failure", 15s)) << jausd->output();
  const auto said = [&] {
    const auto log = jausd->output();
    std::size_t n = 0;
    for (auto at = log.find("no longer hears us"); at != std::string::npos; at = log.find("no longer hears us", at + 1)) ++n;
    return n;
  };
  EXPECT_EQ(said(), 1u) << jausd->output();

  // It hears again: Ready through the reconnect path, and nothing moves.
  const auto before = sim->states().size();
  ASSERT_TRUE(sim->deafen(false));
  EXPECT_TRUE(poll_status(kDriver, "ready", 20s)) << jausd->output();
  std::this_thread::sleep_for(1s);
  const auto states = sim->states();
  for (std::size_t i = before; i < states.size(); ++i) EXPECT_TRUE(stopped(states[i])) << states[i].dump();
  EXPECT_EQ(said(), 1u) << jausd->output();
  // Until a new command.
  auto again = drive();
  EXPECT_TRUE(sim->wait_for(moving, 15s)) << again->output();
}

}  // namespace
}  // namespace jaus::test
