// Safety of the real loop, on real processes: jausd driving a separate
// clearpath-sim over UDP, its hardware e-stop and pause pressed on its
// standard input, controllers as jausctl processes or raw JAUS datagrams.
// Each test is a failure issue 27 found on real processes, or a row of
// docs/safety.md; the checks read the simulator's true state and events.
#include <gtest/gtest.h>

#include <unistd.h>

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/udp.hpp>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <thread>

#include "../benchmarks/bench_support.hpp"
#include "clearpath_simulator.hpp"
#include "default_jausd.hpp"
#include "jaus/messages/all.hpp"
#include "jss_system.hpp"

namespace jaus::test {
namespace {

using namespace std::chrono_literals;
using Json = nlohmann::json;
using Simulator = ClearpathSimulator;

constexpr const char* kNode = "127.0.0.70";
constexpr const char* kSimAddress = "127.0.0.71";
constexpr int kSubsystem = 8;
const Address kDriverAddress{kSubsystem, 1, 33, 1};
constexpr const char* kDriver = "8.1.33.1";
constexpr const char* kPoseSensor = "8.1.38.1";
constexpr const char* kForward =
    R"({"name":"Set Wrench Effort","fields":{"propulsive_linear_effort_x_percent":60}})";

class Safety : public ::testing::Test {
 protected:
  Safety() {
    // Not jausd's own directory (DefaultJausd removes that): the holds outlive a jausd.
    dir = std::filesystem::temp_directory_path() / ("jaus-safety-test-" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir / "state");
  }
  ~Safety() override {
    jausd.reset();
    sim.reset();
    std::error_code ignored;
    std::filesystem::remove_all(dir, ignored);
  }

  void start_sim(const std::string& name = "sim", std::vector<std::string> options = {}) {
    sim = std::make_unique<Simulator>(Simulator::Line::udp, dir, name, kSimAddress, std::move(options));
    ASSERT_TRUE(sim->started());
  }
  // jausd on the simulator, the Husky's e-stop bit as its emergency flag, holds persisted.
  void start_jausd(bool wait_ready = true, const std::string& more = "clearpath: {emergency_flags: 0x08}\n") {
    jausd = std::make_unique<DefaultJausd>("safety", kSubsystem, kNode,
                                           std::string("platform: {udp: ") + kSimAddress + ":7300}\n" + more +
                                               "state_directory: " + (dir / "state").string() + "\n",
                                           "", std::vector<std::string>{"--pid-file", pid_file().string()});
    ASSERT_TRUE(jausd->started());
    if (wait_ready) {  // the driver at the platform's first data, the sensors at their first fresh sample
      ASSERT_TRUE(poll_status(kDriver, "ready", 30s)) << jausd->output();
      ASSERT_TRUE(poll_status(kPoseSensor, "ready", 10s)) << jausd->output();
    }
  }
  void start() {
    start_sim();
    start_jausd();
  }

  std::unique_ptr<ChildProcess> jausctl(const std::string& name, std::vector<std::string> args, const std::string& bind) {
    auto child = jausd->jausctl_own_id(name, std::move(args), bind);
    EXPECT_TRUE(child->started());
    return child;
  }
  // A controller that streams 60 % forward at 10 Hz while the driver is Ready
  // (and, with --resume-when-ready, whenever it is Ready again): the most
  // careless operator tool, the one jausd must defend the vehicle against.
  std::unique_ptr<ChildProcess> careless_controller() {
    return jausctl("controller",
                   {"control", kDriver, "--authority", "10", "--rate", "10", "--for", "60", "--send", kForward,
                    "--resume-when-ready"},
                   "127.0.0.72:0");
  }
  std::optional<std::string> status_of(const std::string& address) {
    auto child = jausctl("status", {"status", address, "--timeout", "1"}, "127.0.0.73:0");
    if (child->wait(20s) != 0) {
      last_failure = child->output();
      return std::nullopt;
    }
    std::istringstream lines(child->output());
    for (std::string line; std::getline(lines, line);)
      if (!line.empty() && line.front() == '{') {
        const Json j = Json::parse(line, nullptr, false);
        if (!j.is_discarded()) return j.value("primary_status", "");
      }
    return std::nullopt;
  }
  bool poll_status(const std::string& address, const std::string& status, std::chrono::seconds deadline) {
    const auto until = std::chrono::steady_clock::now() + deadline;
    while (std::chrono::steady_clock::now() < until) {
      last_status = status_of(address);
      if (last_status == status) return true;
      std::this_thread::sleep_for(200ms);
    }
    ADD_FAILURE() << address << " not " << status << " within " << deadline.count() << " s; last seen: "
                  << last_status.value_or("(no answer: " + last_failure + ")");
    return false;
  }
  std::optional<std::string> last_status;
  std::string last_failure;
  // Every status seen while `d` passes, polled.
  std::vector<std::string> statuses_during(const std::string& address, std::chrono::seconds d) {
    std::vector<std::string> seen;
    const auto until = std::chrono::steady_clock::now() + d;
    // One jausctl every 200 ms: each is a new peer of the node, whose table holds max_peers (256).
    while (std::chrono::steady_clock::now() < until) {
      if (auto s = status_of(address)) seen.push_back(*s);
      std::this_thread::sleep_for(200ms);
    }
    return seen;
  }
  // A controller streaming 60 % forward at 10 Hz that stops for good at the
  // first stop it sees (exit 3): what `jausctl control --send` does by default.
  std::unique_ptr<ChildProcess> stopping_controller() {
    return jausctl("controller",
                   {"control", kDriver, "--authority", "10", "--rate", "10", "--for", "60", "--send", kForward},
                   "127.0.0.72:0");
  }
  // A field of `address`'s Report Component Status as `jausctl status` prints
  // it ("stops": the stop counter, "secondary_status"), none without an answer.
  std::optional<std::uint32_t> status_field(const std::string& address, const std::string& field) {
    auto child = jausctl("status-" + field, {"status", address, "--timeout", "1"}, "127.0.0.73:0");
    if (child->wait(20s) != 0) return std::nullopt;
    std::istringstream lines(child->output());
    for (std::string line; std::getline(lines, line);)
      if (!line.empty() && line.front() == '{') {
        const Json j = Json::parse(line, nullptr, false);
        if (!j.is_discarded() && j.contains(field)) return j[field].get<std::uint32_t>();
      }
    return std::nullopt;
  }
  std::optional<std::uint32_t> stops_of(const std::string& address) { return status_field(address, "stops"); }
  int emergency(const std::string& what, const std::string& as) {
    auto child = jausd->jausctl("emergency-" + what, {"emergency", kDriver, what, "--timeout", "5"}, "127.0.0.74:0", as);
    return child->wait(20s).value_or(-1);
  }
  bool all_stopped_since(std::size_t first_state) const {
    const auto states = sim->states();
    for (std::size_t i = first_state; i < states.size(); ++i)
      if (!Simulator::stopped(states[i])) return false;
    return true;
  }

  std::filesystem::path pid_file() const { return dir / "jausd.pid"; }
  // SIGUSR1 to the jausd its PID file names, as the docs tell an operator.
  void local_clear_through_the_pid_file() {
    std::ifstream in(pid_file());
    long pid = 0;
    ASSERT_TRUE(in >> pid) << pid_file() << " holds no process ID";
    ASSERT_GT(pid, 0);
    ASSERT_EQ(::kill(static_cast<pid_t>(pid), SIGUSR1), 0) << std::strerror(errno);
  }

  std::filesystem::path dir;
  std::unique_ptr<Simulator> sim;
  std::unique_ptr<DefaultJausd> jausd;
};

// Raw JAUS datagrams from many operators, each its own socket (one endpoint
// is one node), spread over three hosts (127.0.0.75-77): jausd records at
// most 8 endpoints per host while they hold state (docs/safety.md, "Hostile
// network"), so 24 operators can be told apart; beyond that they are
// unrecorded, and their holds are the kind only the local clear releases.
class Operators {
 public:
  template <class M>
  void send(std::uint8_t operator_subsystem, const M& message) {
    const auto bytes = bench::datagram(Address{operator_subsystem, 1, 40, 1}, kDriverAddress, message, 12);
    socket_of(operator_subsystem)
        .send_to(boost::asio::buffer(bytes), boost::asio::ip::udp::endpoint(boost::asio::ip::make_address(kNode), 3794));
    std::this_thread::sleep_for(2ms);  // in order, and no burst the kernel would drop
  }

 private:
  boost::asio::ip::udp::socket& socket_of(std::uint8_t operator_subsystem) {
    auto it = sockets_.find(operator_subsystem);
    if (it == sockets_.end()) {
      const std::string host = "127.0.0." + std::to_string(75 + operator_subsystem % 3);
      it = sockets_
               .emplace(operator_subsystem, boost::asio::ip::udp::socket(
                                                io_, boost::asio::ip::udp::endpoint(
                                                         boost::asio::ip::make_address(host), 0)))
               .first;
    }
    return it->second;
  }
  boost::asio::io_context io_;
  std::map<std::uint8_t, boost::asio::ip::udp::socket> sockets_;
};

// Issue 27, failure 1: a pause on the platform was erased by jausd's own
// safety word and the streaming controller drove on. Now the pause holds the
// vehicle in Emergency until the platform releases it, whatever streams.
TEST_F(Safety, APlatformPauseHoldsTheVehicleUntilThePlatformReleasesIt) {
  start();
  auto controller = careless_controller();
  ASSERT_TRUE(sim->wait_for(Simulator::moving, 15s)) << controller->output();
  ASSERT_TRUE(sim->press("pause", true));
  ASSERT_TRUE(sim->wait_for(Simulator::stopped, 10s));
  const auto first = sim->states().size();
  const auto seen = statuses_during(kDriver, 4s);
  ASSERT_FALSE(seen.empty());
  for (const auto& s : seen) EXPECT_EQ(s, "emergency");  // never Ready while paused: no flip-flop
  EXPECT_TRUE(all_stopped_since(first));
  const auto now = *sim->state();
  EXPECT_EQ(now["safety_flags"].get<int>() & 0x10, 0x10) << now.dump();  // the pause is still there
  ASSERT_TRUE(sim->press("pause", false));
  EXPECT_TRUE(poll_status(kDriver, "ready", 10s)) << jausd->output();
}

// Issue 42: a stop shorter than a status period. Another OCU sets and clears
// the emergency back to back (2 ms apart) while `jausctl control --send`
// drives: the driver stops, and the controller, which samples the status at
// 10 Hz, sees it (reported at once, and counted in every later report): it
// stops for good (exit 3), and the wheels stay at rest. Every time.
TEST_F(Safety, AnEmergencySetAndClearedBackToBackStopsTheControllerForGood) {
  start();
  Operators operators;
  for (int round = 1; round <= 3; ++round) {
    SCOPED_TRACE("round " + std::to_string(round));
    auto controller = stopping_controller();
    ASSERT_TRUE(sim->wait_for(Simulator::moving, 15s)) << controller->output();
    const auto stops = stops_of(kDriver);
    ASSERT_TRUE(stops);
    operators.send(20, msg::SetEmergency{{1}});
    operators.send(20, msg::ClearEmergency{{1}});
    EXPECT_EQ(controller->wait(20s), 3) << controller->output();
    EXPECT_TRUE(controller->output_shows("stopped sending Set Wrench Effort")) << controller->output();
    ASSERT_TRUE(sim->wait_for(Simulator::stopped, 10s));
    const auto first = sim->states().size();
    EXPECT_EQ(stops_of(kDriver), *stops + 1);  // the stop happened, once, and is over
    EXPECT_TRUE(poll_status(kDriver, "ready", 10s));
    EXPECT_TRUE(all_stopped_since(first)) << "the wheels turned again after the controller stopped";
  }
}

// Issue 42: a platform pause of 50 ms, between two of the 10 Hz safety
// status samples jausd used to take, went unseen (wheels 0.60 -> 0.41 ->
// 0.60 m/s). At 50 Hz every pause of 20 ms or more falls on a sample: the
// driver enters Emergency, and the controller stops for good. Every time.
TEST_F(Safety, AFiftyMillisecondPlatformPauseIsSeenEveryTime) {
  start();
  for (int round = 1; round <= 3; ++round) {
    SCOPED_TRACE("round " + std::to_string(round));
    auto controller = stopping_controller();
    ASSERT_TRUE(sim->wait_for(Simulator::moving, 15s)) << controller->output();
    const auto stops = stops_of(kDriver);
    ASSERT_TRUE(stops);
    ASSERT_TRUE(sim->press_for("pause", 50));
    EXPECT_EQ(controller->wait(20s), 3) << controller->output();
    EXPECT_TRUE(controller->output_shows("stopped sending Set Wrench Effort")) << controller->output();
    ASSERT_TRUE(sim->wait_for(Simulator::stopped, 10s));
    const auto first = sim->states().size();
    EXPECT_TRUE(poll_status(kDriver, "ready", 10s));  // released by the platform, seen released
    EXPECT_EQ(stops_of(kDriver), *stops + 1);
    EXPECT_TRUE(all_stopped_since(first)) << "the wheels turned again after the controller stopped";
  }
}

// Issue 27, failure 2: a controller killed mid-stream was stopped only by the
// platform's watchdog. Now jausd's command timeout writes the zero first.
TEST_F(Safety, AKilledControllerIsStoppedByJausdBeforeThePlatformsWatchdog) {
  start();
  auto controller = careless_controller();
  ASSERT_TRUE(sim->wait_for(Simulator::moving, 15s)) << controller->output();
  const auto events_before = sim->events().size();
  controller->signal(SIGKILL);
  ASSERT_TRUE(sim->wait_for(Simulator::stopped, 10s));
  std::this_thread::sleep_for(1500ms);  // long enough for the watchdog too, after the zero
  std::optional<std::int64_t> zero, watchdog;
  const auto events = sim->events();
  for (std::size_t i = events_before; i < events.size(); ++i) {
    const auto& e = events[i];
    if (e["event"] == "zero_command" && !zero) zero = e["steady_ns"].get<std::int64_t>();
    if (e["event"] == "safety" && (e["flags"].get<int>() & 0x01) && !watchdog) watchdog = e["steady_ns"].get<std::int64_t>();
  }
  ASSERT_TRUE(zero) << "jausd never wrote a zero; the platform's watchdog did the stopping";
  if (watchdog) {
    EXPECT_LT(*zero, *watchdog);
  }
  EXPECT_TRUE(jausd->output_shows("no Set Wrench Effort for 0.500 s")) << jausd->output();
}

// Issue 27, failure 3: twenty operators set Emergency, nineteen cleared, and
// the driver was Ready. Now every holder holds; beyond the recorded ones the
// latch holds until the local clear (SIGUSR1), logged.
TEST_F(Safety, EveryEmergencyHolderIsKeptAndTheLocalClearReleasesThoseGoneForGood) {
  start();
  Operators operators;
  for (std::uint8_t i = 0; i < 20; ++i) operators.send(100 + i, msg::SetEmergency{});
  for (std::uint8_t i = 0; i < 19; ++i) operators.send(100 + i, msg::ClearEmergency{});
  for (const auto& s : statuses_during(kDriver, 1s)) EXPECT_EQ(s, "emergency");
  operators.send(119, msg::ClearEmergency{});
  EXPECT_TRUE(poll_status(kDriver, "ready", 10s)) << jausd->output();
  // 70 holders: more than can be recorded (by the node's routes: 8 endpoints a
  // host; by the latch: 64); their own clears cannot release them all.
  for (std::uint8_t i = 0; i < 70; ++i) operators.send(100 + i, msg::SetEmergency{});
  for (std::uint8_t i = 0; i < 70; ++i) operators.send(100 + i, msg::ClearEmergency{});
  std::this_thread::sleep_for(500ms);
  EXPECT_EQ(status_of(kDriver), "emergency");
  jausd->process().signal(SIGUSR1);
  EXPECT_TRUE(poll_status(kDriver, "ready", 10s)) << jausd->output();
  EXPECT_TRUE(jausd->output_shows("emergency holds cleared locally (SIGUSR1)")) << jausd->output();
}

// Issue 49: the local clear (SIGUSR1, sent to the jausd its PID file names)
// releases every Set Emergency hold on every component, the communicator's
// and a sensor's as well as the vehicle's, logged with who held what; at an
// orderly exit the PID file goes.
TEST_F(Safety, TheLocalClearThroughThePidFileReleasesTheCommunicatorAndASensor) {
  start();
  for (const char* held : {"8.1.35.1", kPoseSensor}) {
    auto set = jausd->jausctl(std::string("set-") + held, {"emergency", held, "set", "--timeout", "5"},
                              "127.0.0.74:0", "254.74.40.7");
    ASSERT_EQ(set->wait(20s), 0) << set->output();
    ASSERT_TRUE(poll_status(held, "emergency", 10s));
  }
  ASSERT_TRUE(std::filesystem::exists(pid_file())) << jausd->output();
  local_clear_through_the_pid_file();
  EXPECT_TRUE(poll_status("8.1.35.1", "ready", 10s)) << jausd->output();
  EXPECT_TRUE(poll_status(kPoseSensor, "ready", 10s)) << jausd->output();
  EXPECT_TRUE(jausd->output_shows("emergency holds cleared locally (SIGUSR1), 8.1.35.1 (communicator): 254.74.40.7"))
      << jausd->output();
  EXPECT_TRUE(jausd->output_shows("emergency holds cleared locally (SIGUSR1), 8.1.38.1: 254.74.40.7"))
      << jausd->output();
  jausd->process().signal(SIGTERM);
  EXPECT_EQ(jausd->process().wait(20s), 0) << jausd->output();
  EXPECT_FALSE(std::filesystem::exists(pid_file()));
}

// Issue 27, failure 4: an OCU shut a sensor down, and the next platform
// e-stop called into the destroyed component. jausd stays up and stops.
TEST_F(Safety, AShutDownSensorAndThenAPlatformEstopLeaveJausdRunning) {
  start();
  auto shutdown = jausctl("shutdown", {"control", kPoseSensor, "--authority", "10", "--rate", "1", "--send",
                                       R"({"name":"Shutdown"})"},
                          "127.0.0.76:0");
  // Shut down, the sensor drops control (Reject Component Control: the tool exits 1) and leaves the node.
  EXPECT_TRUE(shutdown->wait(30s)) << shutdown->output();
  ASSERT_TRUE(jausd->output_shows("global_pose_sensor 8.1.38.1: Ready -> Shutdown")) << jausd->output();
  std::this_thread::sleep_for(500ms);
  ASSERT_TRUE(sim->press("estop", true));
  EXPECT_TRUE(poll_status(kDriver, "emergency", 10s)) << jausd->output();
  ASSERT_TRUE(sim->press("estop", false));
  EXPECT_TRUE(poll_status(kDriver, "ready", 10s)) << jausd->output();
  EXPECT_TRUE(jausd->process().running()) << jausd->output();
}

// Issue 27, failure 5: Standby, the platform's link lost and back, and the
// driver was Ready (the controller drove again). Now it is Standby again.
TEST_F(Safety, StandbySurvivesALostPlatformLink) {
  start();
  auto controller = careless_controller();
  ASSERT_TRUE(sim->wait_for(Simulator::moving, 15s)) << controller->output();
  auto standby = jausctl("standby", {"send", kDriver, R"({"name":"Standby"})"}, "127.0.0.74:0");
  EXPECT_EQ(standby->wait(20s), 0) << standby->output();
  ASSERT_TRUE(poll_status(kDriver, "standby", 10s));
  sim->process().signal(SIGKILL);
  sim->process().wait(5s);
  EXPECT_TRUE(poll_status(kDriver, "failure", 15s)) << jausd->output();
  start_sim("sim-again");
  EXPECT_TRUE(poll_status(kDriver, "standby", 20s)) << jausd->output();
  std::this_thread::sleep_for(1s);
  for (const auto& s : sim->states()) EXPECT_TRUE(Simulator::stopped(s)) << s.dump();
}

// The Husky's e-stop shares jausd's emergency bit (0x08): pressed while a Set
// Emergency holds the vehicle, the JAUS clear must not release it, nor make
// it flip between Emergency and Ready at the status rate.
TEST_F(Safety, AHardwareEstopOnJausdsOwnBitNeverFlipFlops) {
  start();
  ASSERT_EQ(emergency("set", "254.74.40.9"), 0);
  ASSERT_TRUE(sim->wait_for([](const Json& s) { return (s["safety_flags"].get<int>() & 0x08) != 0; }, 10s));
  ASSERT_TRUE(sim->press("estop", true));
  std::this_thread::sleep_for(300ms);
  EXPECT_NE(emergency("clear", "254.74.40.9"), 0);  // still in Emergency: the platform's e-stop holds it
  for (const auto& s : statuses_during(kDriver, 3s)) EXPECT_EQ(s, "emergency");
  const auto now = *sim->state();
  EXPECT_EQ(now["safety_flags"].get<int>() & 0x08, 0x08) << now.dump();
  EXPECT_EQ(now["hardware_inputs"].get<int>(), 0x08) << now.dump();
  ASSERT_TRUE(sim->press("estop", false));
  EXPECT_TRUE(poll_status(kDriver, "ready", 10s)) << jausd->output();
}

// Set Emergency to the driver holds the arm and the camera mounts too
// (emergency_scope: vehicle), and its sender clears it from any of them.
TEST_F(Safety, SetEmergencyToTheDriverHoldsEveryMovingComponent) {
  start();
  ASSERT_EQ(emergency("set", "254.74.40.9"), 0);
  EXPECT_TRUE(poll_status("8.1.49.1", "emergency", 10s));  // the manipulator
  EXPECT_TRUE(poll_status("8.1.37.1", "emergency", 10s));  // the visual sensor's mounts
  EXPECT_EQ(status_of(kPoseSensor), "ready");              // a sensor moves nothing
  auto clear = jausd->jausctl("clear-arm", {"emergency", "8.1.49.1", "clear", "--timeout", "5"}, "127.0.0.74:0",
                              "254.74.40.9");
  EXPECT_EQ(clear->wait(20s), 0) << clear->output();
  EXPECT_TRUE(poll_status(kDriver, "ready", 10s)) << jausd->output();
}

// Issue 30 on real processes: a route of the local waypoint driver (8.1.46.1)
// drives a separate clearpath-sim through the primitive driver. An operator
// taking the primitive driver with a higher authority stops the vehicle at
// once and nothing restarts it when the operator lets go; Set Emergency on
// the primitive driver stops it and Clear Emergency does not restart it. The
// route's own controller is a jausctl holding the waypoint driver; its
// commands go with `jausctl send` under its ID from its host.
TEST_F(Safety, AWaypointRouteStopsForAnOperatorAndForSetEmergencyAndNothingRestartsIt) {
  start();
  constexpr const char* kWaypointDriver = "8.1.46.1";
  constexpr const char* kRouteHost = "127.0.0.75";
  constexpr const char* kRouteOwner = "254.75.40.1";
  auto owner = jausd->jausctl("route-owner", {"control", kWaypointDriver, "--authority", "5", "--for", "120"},
                              std::string(kRouteHost) + ":3794", kRouteOwner);
  const auto granted_until = std::chrono::steady_clock::now() + 20s;
  while (!owner->output_contains("granted")) {
    ASSERT_TRUE(owner->running()) << owner->output();
    ASSERT_LT(std::chrono::steady_clock::now(), granted_until) << owner->output();
    std::this_thread::sleep_for(100ms);
  }
  const auto route_command = [&](const std::string& json) {
    auto child = jausd->jausctl("route-command", {"send", kWaypointDriver, json, "--timeout", "0.2"},
                                std::string(kRouteHost) + ":0", kRouteOwner);
    ASSERT_EQ(child->wait(20s), 0) << json << "\n" << child->output();
  };
  const auto driving_bits = [&] { return status_field(kWaypointDriver, "secondary_status"); };
  constexpr std::uint32_t kDriving = 1u << 16, kLostControl = 1u << 18;
  // A long straight route (40 m north), loaded in Standby, started by Resume.
  const auto start_route = [&] {
    route_command(R"({"name":"Standby"})");
    route_command(R"({"name":"Set Travel Speed","fields":{"speed_mps":0.6}})");
    route_command(R"({"name":"Set Local Waypoint","fields":{"waypoint_number":0,"x_m":40,"y_m":0}})");
    route_command(R"({"name":"Resume"})");
    ASSERT_TRUE(sim->wait_for(Simulator::moving, 15s)) << jausd->output();
  };

  // 1. An operator of higher authority takes the primitive driver mid-route.
  start_route();
  auto operator_hold = jausctl("operator", {"control", kDriver, "--authority", "10", "--for", "3"}, "127.0.0.76:0");
  // Generous: the operator's jausctl starts and asks under sanitizers on a loaded machine.
  ASSERT_TRUE(sim->wait_for(Simulator::stopped, 15s)) << operator_hold->output() << jausd->output();
  auto bits = driving_bits();
  ASSERT_TRUE(bits) << last_failure;
  EXPECT_FALSE(*bits & kDriving);
  EXPECT_TRUE(*bits & kLostControl);
  EXPECT_EQ(operator_hold->wait(20s), 0) << operator_hold->output();  // released at --for
  const auto after_release = sim->states().size();
  std::this_thread::sleep_for(3s);
  EXPECT_TRUE(all_stopped_since(after_release)) << "the route restarted after the operator let go";
  EXPECT_TRUE(jausd->output_shows("lost control of the primitive driver")) << jausd->output();

  // 2. Set Emergency on the primitive driver mid-route; Clear Emergency restarts nothing.
  start_route();
  ASSERT_EQ(emergency("set", "254.74.40.9"), 0);
  ASSERT_TRUE(sim->wait_for(Simulator::stopped, 15s)) << jausd->output();
  ASSERT_EQ(emergency("clear", "254.74.40.9"), 0);
  ASSERT_TRUE(poll_status(kDriver, "ready", 10s)) << jausd->output();
  const auto after_clear = sim->states().size();
  std::this_thread::sleep_for(3s);
  EXPECT_TRUE(all_stopped_since(after_clear)) << "the route restarted after Clear Emergency";
  bits = driving_bits();
  ASSERT_TRUE(bits) << last_failure;
  EXPECT_FALSE(*bits & kDriving);
  EXPECT_TRUE(owner->running()) << owner->output();  // the route's owner still holds the waypoint driver
}

// An Ackermann platform keeps its steering angle when the operator lets go.
TEST_F(Safety, AnAckermannStopHoldsTheSteeringAngle) {
  start_sim("sim", {"--drive", "ackermann"});
  start_jausd(true, "vehicle: {steering: ackermann}\n");
  auto controller = jausctl("controller",
                            {"control", kDriver, "--authority", "10", "--rate", "10", "--for", "60", "--send",
                             R"({"name":"Set Wrench Effort","fields":{"propulsive_linear_effort_x_percent":40,)"
                             R"("propulsive_rotational_effort_z_percent":-30}})"},
                            "127.0.0.72:0");
  ASSERT_TRUE(sim->wait_for([](const Json& s) { return s["speed_mps"].get<double>() > 0.2; }, 15s))
      << controller->output();
  EXPECT_NEAR(sim->state()->at("steering_percent").get<double>(), 30, 0.5);  // Clearpath's steering: positive left
  controller->signal(SIGINT);  // released: the driver stops
  EXPECT_EQ(controller->wait(20s), 0) << controller->output();
  ASSERT_TRUE(sim->wait_for(Simulator::stopped, 10s));
  EXPECT_NEAR(sim->state()->at("steering_percent").get<double>(), 30, 0.5) << sim->state()->dump();
}

// Holds survive a restart of jausd (state_directory), and the platform's
// emergency flag an earlier run left is jausd's own, not a platform stop.
TEST_F(Safety, EmergencyHoldsSurviveARestartOfJausd) {
  start();
  ASSERT_EQ(emergency("set", "254.74.40.9"), 0);
  ASSERT_TRUE(poll_status(kDriver, "emergency", 10s));
  ASSERT_TRUE(sim->wait_for([](const Json& s) { return (s["safety_flags"].get<int>() & 0x08) != 0; }, 10s));
  jausd->process().signal(SIGTERM);  // every component shut down while held
  ASSERT_EQ(jausd->process().wait(20s), 0) << jausd->output();
  jausd.reset();
  std::this_thread::sleep_for(500ms);
  EXPECT_EQ(sim->state()->at("safety_flags").get<int>() & 0x08, 0x08) << "the shutdown cleared the emergency flag";
  // The flag stays on the platform while jausd is away; the restarted one comes up held.
  start_jausd(/*wait_ready=*/false);
  EXPECT_TRUE(poll_status(kDriver, "emergency", 30s)) << jausd->output();
  EXPECT_TRUE(jausd->output_shows("emergency held since before the restart (vehicle): 254.74.40.9"));
  ASSERT_EQ(emergency("clear", "254.74.40.9"), 0);
  EXPECT_TRUE(poll_status(kDriver, "ready", 10s)) << jausd->output();
  EXPECT_TRUE(sim->wait_for([](const Json& s) { return (s["safety_flags"].get<int>() & 0x08) == 0; }, 10s));
}

// Issue 42, finding 2: a JSS operator's hold survives a restart bound to its
// JSS ID and host. Another JSS operator (another host, never held anything)
// is given another alias slot and its Clear Emergency releases nothing; the
// holder's JSS ID from another host is refused; the holder clears from its host.
TEST_F(Safety, AfterARestartOnlyTheJssHolderFromItsHostClearsItsStop) {
  const std::string with_jss = std::string("clearpath: {emergency_flags: 0x08}\n") + jss_on_config();
  const jss::JssId driver{kSubsystem, 1, 33};
  const jss::JssId holder_id{200, 5, 40};
  start_sim();
  start_jausd(true, with_jss);
  {
    auto holder = open_jss_operator(holder_id, "127.0.0.75", kNode, "holder");
    ASSERT_TRUE(holder);
    holder->send(driver, jss::msg::SetEmergency{{1}}, jss::JudpPriority::safety_critical);
    holder->run_for(300ms);
  }
  ASSERT_TRUE(poll_status(kDriver, "emergency", 10s));
  jausd->process().signal(SIGTERM);
  ASSERT_EQ(jausd->process().wait(20s), 0) << jausd->output();
  jausd.reset();
  start_jausd(/*wait_ready=*/false, with_jss);
  ASSERT_TRUE(poll_status(kDriver, "emergency", 30s)) << jausd->output();
  EXPECT_TRUE(jausd->output_shows("(JSS 200.5.40 from 127.0.0.75)")) << jausd->output();
  auto other = open_jss_operator(jss::JssId{77, 3, 1}, "127.0.0.76", kNode, "other operator");
  ASSERT_TRUE(other);
  auto impostor = open_jss_operator(holder_id, "127.0.0.76", kNode, "impostor");
  ASSERT_TRUE(impostor);
  for (int i = 0; i < 3; ++i) {
    other->send(driver, jss::msg::ClearEmergency{{1}});
    impostor->send(driver, jss::msg::ClearEmergency{{1}});
    other->run_for(300ms);
  }
  EXPECT_EQ(status_of(kDriver), "emergency") << jausd->output();
  EXPECT_TRUE(jausd->output_shows("spoofed, or two peers with one ID")) << jausd->output();
  auto holder = open_jss_operator(holder_id, "127.0.0.75", kNode, "holder again");  // a new port, its host
  ASSERT_TRUE(holder);
  holder->send(driver, jss::msg::ClearEmergency{{1}});
  holder->run_for(300ms);
  EXPECT_TRUE(poll_status(kDriver, "ready", 10s)) << jausd->output();
}

// Issue 42, finding 5: a state directory jausd cannot write refuses the
// start (a path through a regular file: root is refused too), said clearly.
TEST_F(Safety, JausdRefusesToStartOnAStateDirectoryItCannotWrite) {
  std::ofstream(dir / "not-a-directory") << "a file\n";
  DefaultJausd refused("safety-refused", kSubsystem, kNode,
                       "state_directory: " + (dir / "not-a-directory" / "state").string() + "\n");
  ASSERT_TRUE(refused.started());
  EXPECT_EQ(refused.process().wait(20s), 2) << refused.output();
  EXPECT_TRUE(refused.output_shows("cannot be created")) << refused.output();
  EXPECT_TRUE(refused.output_shows("not started")) << refused.output();
}

// Issue 42, finding 5: a write that fails while jausd runs (the state
// directory replaced by a file: root is not stopped by permissions) is
// logged once, and no Clear Emergency is taken until the holds are written
// again: the OCU's clear ends with the driver still in Emergency.
TEST_F(Safety, WhileHoldsCannotBePersistedNoClearEmergencyIsTaken) {
  start();
  ASSERT_EQ(emergency("set", "254.74.40.9"), 0);
  ASSERT_TRUE(poll_status(kDriver, "emergency", 10s));
  std::filesystem::rename(dir / "state", dir / "state.away");
  std::ofstream(dir / "state") << "the disk is gone\n";
  ASSERT_EQ(emergency("set", "254.74.40.8"), 0);  // a change to write: the write fails
  const auto said = [&](const std::string& text) { return jausd->output_shows(text, 20s); };
  ASSERT_TRUE(said("emergency holds not persisted")) << jausd->output();
  EXPECT_NE(emergency("clear", "254.74.40.8"), 0);
  EXPECT_NE(emergency("clear", "254.74.40.9"), 0);
  EXPECT_EQ(status_of(kDriver), "emergency");
  EXPECT_TRUE(jausd->output_shows("refused: the emergency holds cannot be persisted")) << jausd->output();
  // The disk is back: the next retry writes the holds, and the clears are taken.
  std::filesystem::remove(dir / "state");
  std::filesystem::rename(dir / "state.away", dir / "state");
  ASSERT_TRUE(said("emergency holds persisted again")) << jausd->output();
  EXPECT_NE(emergency("clear", "254.74.40.8"), 0);  // taken, but 254.74.40.9 still holds
  EXPECT_EQ(emergency("clear", "254.74.40.9"), 0);
  EXPECT_TRUE(poll_status(kDriver, "ready", 10s)) << jausd->output();
}

// Until the platform speaks, the vehicle's components are initialising, not
// Ready then failed; nothing is commanded meanwhile.
TEST_F(Safety, WithoutItsPlatformTheDriverWaitsInInitialize) {
  start_jausd(/*wait_ready=*/false);
  std::this_thread::sleep_for(2s);
  EXPECT_EQ(status_of(kDriver), "initialize");
  EXPECT_FALSE(jausd->output_contains("-> Failure")) << jausd->output();
  start_sim();
  EXPECT_TRUE(poll_status(kDriver, "ready", 20s)) << jausd->output();
}

}  // namespace
}  // namespace jaus::test
