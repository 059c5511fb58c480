// The node host: every registered component kind can be built, a host opens
// with its configured components and extra ones, a busy address is one error,
// and stop() shuts the components down before the link closes.
#include <gtest/gtest.h>

#include <boost/asio/io_context.hpp>
#include <boost/asio/post.hpp>
#include <csignal>
#include <cstring>  // sigabbrev_np

#include "jaus/base/virtual_time.hpp"
#include "jaus/clearpath/sim/loopback_client.hpp"
#include "jaus/host/component_options.hpp"
#include "jaus/host/node_host.hpp"

#include <algorithm>
#include <functional>
#include <stdexcept>

namespace jaus::host {
namespace {

constexpr std::uint32_t kLoopback = 0x7F000001;

HostConfig loopback_config() {
  HostConfig config;
  config.link.bind = transport::Ipv4Endpoint{kLoopback, 0};
  for (const auto& kind : component_kinds())
    config.components.push_back(ComponentSpec{std::string(kind.name), kind.default_id, 1, 0, "", {}, 0, {}});
  return config;
}

TEST(ComponentKinds, EveryRegisteredKindIsBuiltWithItsIdAndName) {
  rt::VirtualTime time;
  struct NullLink : node::Link {
    void transmit(const Header&, std::span<const std::uint8_t>) override {}
  } link;
  node::Node node(node::NodeConfig{}, time, time, link);
  ComponentSettings settings;
  components::SimulatedVehicle vehicle({}, time);
  components::SimulatedCameras cameras(components::VisualSensorConfig{{components::CameraConfig{}}}, time);
  components::SimulatedArm arm(components::ArmConfig{{components::JointConfig{}}}, time);
  const VehicleBackends backends{&vehicle, &vehicle, &cameras, &arm};
  ASSERT_FALSE(component_kinds().empty());
  for (const auto& kind : component_kinds()) {
    auto made = make_component(ComponentSpec{std::string(kind.name), kind.default_id, 2, 7, "", {}, 0, {}}, settings,
                               node, backends);
    ASSERT_TRUE(made) << kind.name << ": " << made.error().message();
    EXPECT_EQ((*made)->address(), (Address{1, 1, kind.default_id, 2}));
    EXPECT_EQ((*made)->name(), kind.name);  // no name given: the kind's
    EXPECT_EQ((*made)->control().own_authority(), 7);
  }
  auto unknown = make_component(ComponentSpec{"warp_drive", 99, 1, 0, "", {}, 0, {}}, settings, node);
  ASSERT_FALSE(unknown);
  EXPECT_EQ(unknown.error().code, ErrorCode::invalid_argument);
}

TEST(ComponentKinds, AVehicleComponentWithoutAVehicleOrWithABadOptionIsOneError) {
  rt::VirtualTime time;
  struct NullLink : node::Link {
    void transmit(const Header&, std::span<const std::uint8_t>) override {}
  } link;
  node::Node node(node::NodeConfig{}, time, time, link);
  auto driverless = make_component(ComponentSpec{"primitive_driver", 33, 1, 0, "", {}, 0, {}}, {}, node);
  ASSERT_FALSE(driverless);
  EXPECT_EQ(driverless.error().message(), "primitive_driver needs a vehicle drive and the host has none");
  auto blind = make_component(ComponentSpec{"visual_sensor", 37, 1, 0, "", {}, 0, {}}, {}, node);
  ASSERT_FALSE(blind);
  EXPECT_EQ(blind.error().message(), "visual_sensor needs cameras and the host has none");
  auto armless = make_component(ComponentSpec{"primitive_manipulator", 49, 1, 0, "", {}, 0, {}}, {}, node);
  ASSERT_FALSE(armless);
  EXPECT_EQ(armless.error().message(), "primitive_manipulator needs an arm and the host has none");

  components::SimulatedVehicle vehicle({}, time);
  auto bad = make_component(ComponentSpec{"primitive_driver", 33, 1, 0, "", {{"command_timeout_s", "soon"}}, 0, {}}, {},
                            node, {&vehicle, &vehicle});
  ASSERT_FALSE(bad);
  EXPECT_EQ(bad.error().code, ErrorCode::invalid_argument);
  EXPECT_EQ(bad.error().field, "command_timeout_s");
  EXPECT_NE(bad.error().message().find("'soon'"), std::string::npos) << bad.error().message();
}

TEST(ComponentOptions, EachKindsOptionsAreReadAndCheckedWithTheirLine) {
  ComponentSpec driver{"primitive_driver", 33, 1, 0, "", {{"command_timeout_s", "0.25"}, {"stop_brake_percent", "40"}},
                       7, {}};
  const auto options = primitive_driver_options(driver);
  ASSERT_TRUE(options) << options.error().message();
  EXPECT_EQ(options->command_timeout, std::chrono::milliseconds(250));
  EXPECT_EQ(options->stop_brake_percent, 40);

  ComponentSpec sensor{"global_pose_sensor", 38, 1, 0, "", {{"stale_after_s", "2"}, {"local_pose", "false"}}, 9, {}};
  const auto pose = global_pose_sensor_options(sensor);
  ASSERT_TRUE(pose) << pose.error().message();
  EXPECT_EQ(pose->sensor.stale_after, std::chrono::seconds(2));
  EXPECT_FALSE(pose->local_pose);
  EXPECT_FALSE(check_component_options(sensor));

  ComponentSpec bad{"velocity_state_sensor", 42, 1, 0, "", {{"stale_after_s", "0"}}, 11, {{"stale_after_s", 13}}};
  const auto problem = check_component_options(bad);
  ASSERT_TRUE(problem);
  EXPECT_EQ(problem->line, 13);  // the option's own line
  EXPECT_NE(problem->what.find("stale_after_s"), std::string::npos) << problem->what;
  ComponentSpec arm{"primitive_manipulator", 49, 1, 0, "", {{"command_timeout_s", "1.5"}}, 3, {}};
  const auto manipulator = primitive_manipulator_options(arm);
  ASSERT_TRUE(manipulator) << manipulator.error().message();
  EXPECT_EQ(manipulator->command_timeout, std::chrono::milliseconds(1500));
  arm.options["command_timeout_s"] = "-1";
  ASSERT_TRUE(check_component_options(arm));
  EXPECT_NE(check_component_options(arm)->what.find("command_timeout_s"), std::string::npos);

  ComponentSpec brake{"primitive_driver", 33, 1, 0, "", {{"stop_brake_percent", "101"}}, 5, {}};
  ASSERT_TRUE(check_component_options(brake));
  EXPECT_EQ(check_component_options(brake)->line, 5);  // no option line known: the component's
}

TEST(NodeHost, HostsConfiguredAndAddedComponentsAndStopsThemFirst) {
  boost::asio::io_context io;
  auto host = NodeHost::open(loopback_config(), io);
  ASSERT_TRUE(host) << host.error().message();
  NodeHost& h = **host;
  EXPECT_EQ(h.node().local_components().size(), component_kinds().size());
  EXPECT_NE(h.link().local_endpoint().port, 0);

  struct Extra : rt::Component {
    using Component::Component;
  };
  auto& extra = h.emplace<Extra>(h.component_config("extra", 200));
  EXPECT_EQ(extra.address(), (Address{1, 1, 200, 1}));
  EXPECT_EQ(h.node().local_components().size(), component_kinds().size() + 1);

  h.stop("test");
  EXPECT_TRUE(h.stopped());
  EXPECT_TRUE(h.node().local_components().empty());  // every component shut down and left
  h.stop("again");  // idempotent
}

// Safety: whatever ends the event loop, every component's stop path runs
// before run() returns (the platform is commanded to stop).
TEST(NodeHost, AnExceptionEscapingTheLoopStillStopsEveryComponent) {
  boost::asio::io_context io;
  std::vector<std::string> lines;
  auto host = NodeHost::open(loopback_config(), io, [&](rt::LogLevel, const std::string& l) { lines.push_back(l); });
  ASSERT_TRUE(host) << host.error().message();
  boost::asio::post(io, [] { throw std::runtime_error("out of memory"); });
  EXPECT_EQ((*host)->run(io), std::optional<std::string>("out of memory"));
  EXPECT_TRUE((*host)->stopped());
  EXPECT_TRUE((*host)->node().local_components().empty());
  const auto logged = [&](const std::string& text) {
    return std::any_of(lines.begin(), lines.end(), [&](const auto& l) { return l.find(text) != std::string::npos; });
  };
  EXPECT_TRUE(logged("event loop failed: out of memory; stopping"));
  EXPECT_TRUE(logged("stopped (exception: out of memory)"));
}

class NodeHostStopSignal : public ::testing::TestWithParam<int> {};

TEST_P(NodeHostStopSignal, EndsTheLoopWithAnOrderlyStop) {
  boost::asio::io_context io;
  std::vector<std::string> lines;
  auto host = NodeHost::open(loopback_config(), io, [&](rt::LogLevel, const std::string& l) { lines.push_back(l); });
  ASSERT_TRUE(host) << host.error().message();
  const int signal = GetParam();
  // Raised from inside the loop, where run() has its handler installed.
  boost::asio::post(io, [signal] { ::raise(signal); });
  EXPECT_EQ((*host)->run(io), std::nullopt);
  EXPECT_TRUE((*host)->stopped());
  EXPECT_TRUE((*host)->node().local_components().empty());
  const std::string expected = "stopped (SIG" + std::string(sigabbrev_np(signal)) + ")";
  EXPECT_TRUE(std::any_of(lines.begin(), lines.end(), [&](const auto& l) { return l.find(expected) != std::string::npos; }))
      << expected;
}

INSTANTIATE_TEST_SUITE_P(EverySignal, NodeHostStopSignal, ::testing::Values(SIGINT, SIGTERM, SIGHUP, SIGQUIT),
                         [](const ::testing::TestParamInfo<int>& signal) { return std::string(sigabbrev_np(signal.param)); });

TEST(NodeHost, ABusyAddressIsOneIoError) {
  boost::asio::io_context io;
  auto first = NodeHost::open(loopback_config(), io);
  ASSERT_TRUE(first) << first.error().message();
  HostConfig second_config = loopback_config();
  second_config.link.bind = (*first)->link().local_endpoint();
  auto second = NodeHost::open(second_config, io);
  ASSERT_FALSE(second);
  EXPECT_EQ(second.error().code, ErrorCode::io);
  EXPECT_EQ(second.error().message(), transport::to_string(second_config.link.bind) + " is already in use");
}

TEST(NodeHost, AnUnknownKindInTheConfigurationIsAnError) {
  boost::asio::io_context io;
  HostConfig config = loopback_config();
  config.components.push_back(ComponentSpec{"warp_drive", 99, 1, 0, "", {}, 0, {}});
  auto host = NodeHost::open(config, io);
  ASSERT_FALSE(host);
  EXPECT_EQ(host.error().message(), "component kind 'warp_drive' cannot be hosted by this build");
}

// A Clearpath platform (simulated in process): the mobility components run on
// the bridge; the platform's own e-stop holds them all in Emergency until it
// clears, and the driver's JAUS Emergency sets the platform's emergency flag.
TEST(NodeHost, OnAClearpathPlatformItsEstopAndJausEmergencyMirrorEachOther) {
  boost::asio::io_context io;
  HostConfig config = loopback_config();
  config.platform.kind = PlatformSettings::Kind::clearpath_sim;
  config.platform.vehicle.emergency_flags = 0x08;
  config.arm.joints = {components::JointConfig{}};
  config.platform.arm.joints = {{0, 1, 0}};  // the one joint on Clearpath joint 0
  auto host = NodeHost::open(config, io);
  ASSERT_TRUE(host) << host.error().message();
  NodeHost& h = **host;
  ASSERT_NE(h.clearpath_vehicle(), nullptr);
  EXPECT_EQ(h.vehicle(), nullptr);  // no direct simulation
  EXPECT_NE(h.clearpath_arm(), nullptr);
  EXPECT_EQ(h.arm(), nullptr);
  EXPECT_EQ(h.clearpath_cameras(), nullptr);  // no mount mapped: the cameras stay simulated
  auto* driver = h.node().find(Address{1, 1, 33, 1});
  auto* pose = h.node().find(Address{1, 1, 38, 1});
  ASSERT_TRUE(driver && pose);
  // Until `done`, or 10 s: generous, since a loaded 2-core machine under ASan can stall this process.
  const auto run_until = [&](const std::function<bool()>& done) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
    while (!done() && std::chrono::steady_clock::now() < deadline) io.run_for(std::chrono::milliseconds(10));
    return done();
  };
  ASSERT_TRUE(run_until([&] { return driver->state() == rt::PrimaryStatus::ready && pose->state() == rt::PrimaryStatus::ready; }));

  // Someone presses the platform's e-stop (a safety flag the bridge did not set).
  clearpath::SetSafetySystem pressed;
  pressed.flags = 0x08;
  h.platform_client()->send(pressed);
  EXPECT_TRUE(run_until([&] { return driver->state() == rt::PrimaryStatus::emergency && pose->state() == rt::PrimaryStatus::emergency; }));
  clearpath::SetSafetySystem released;
  h.platform_client()->send(released);
  EXPECT_TRUE(run_until([&] { return driver->state() == rt::PrimaryStatus::ready && pose->state() == rt::PrimaryStatus::ready; }));

  // JAUS Emergency on the driver: the platform's flag is set, and is not taken for its own e-stop.
  // Waited for on the platform itself, then a while for its safety status to
  // come back (that it is not taken for an e-stop is also asserted under
  // virtual time, tests/bridge/clearpath_vehicle_test.cpp).
  const auto* platform = dynamic_cast<clearpath::sim::LoopbackClient*>(h.platform_client());
  ASSERT_NE(platform, nullptr);
  driver->hold_hardware_emergency("test");  // any way into Emergency mirrors it
  EXPECT_TRUE(run_until([&] { return (platform->platform().vehicle().safety_flags() & 0x08) != 0; }));
  io.run_for(std::chrono::milliseconds(300));
  EXPECT_EQ(pose->state(), rt::PrimaryStatus::ready);
  driver->release_hardware_emergency("test");
  EXPECT_TRUE(run_until([&] { return driver->state() == rt::PrimaryStatus::ready; }));
  h.stop("test");
}

}  // namespace
}  // namespace jaus::host
