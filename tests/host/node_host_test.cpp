// The node host: every registered component kind can be built, a kind of a
// test's own is hosted like the built-in ones (the host names none), a host
// opens with its configured components and extra ones, a busy address is one
// error, and stop() shuts the components down before the link closes.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/udp.hpp>
#include <boost/asio/post.hpp>

#include "jaus/base/virtual_time.hpp"
#include "jaus/clearpath/sim/loopback_client.hpp"
#include "jaus/components/global_pose_sensor_kind.hpp"
#include "jaus/components/primitive_driver_kind.hpp"
#include "jaus/components/primitive_manipulator_kind.hpp"
#include "jaus/host/component_options.hpp"
#include "jaus/host/clearpath_platform.hpp"
#include "jaus/host/model_platform.hpp"
#include "jaus/host/node_host.hpp"
#include "jaus/jss/judp.hpp"
#include "jaus/testing/memory_link.hpp"
#include "jaus/testing/virtual_time.hpp"
#include "jaus/wire/message.hpp"

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <stdexcept>

namespace jaus::host {
namespace {

using namespace std::chrono_literals;

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
  rt::Backends backends;
  backends.offer<components::Drive>(&vehicle);
  backends.offer<components::PoseSource>(&vehicle);
  backends.offer<components::Cameras>(&cameras);
  backends.offer<components::ManipulatorArm>(&arm);
  ASSERT_FALSE(component_kinds().empty());
  for (const auto& kind : component_kinds()) {
    // A kind with an authority ceiling (the drivers above the primitive driver, issue 42) needs it at 7 or more.
    std::map<std::string, std::string> options;
    if (std::find(kind.options.begin(), kind.options.end(), "max_authority") != kind.options.end())
      options["max_authority"] = "7";
    auto made = make_component(ComponentSpec{std::string(kind.name), kind.default_id, 2, 7, "", options, 0, {}},
                               settings, node, backends);
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
  rt::Backends backends;
  backends.offer<components::Drive>(&vehicle);
  backends.offer<components::PoseSource>(&vehicle);
  auto bad = make_component(ComponentSpec{"primitive_driver", 33, 1, 0, "", {{"command_timeout_s", "soon"}}, 0, {}}, {},
                            node, backends);
  ASSERT_FALSE(bad);
  EXPECT_EQ(bad.error().code, ErrorCode::invalid_argument);
  EXPECT_EQ(bad.error().field, "command_timeout_s");
  EXPECT_NE(bad.error().message().find("'soon'"), std::string::npos) << bad.error().message();
}

TEST(ComponentOptions, EachKindsOptionsAreReadAndCheckedWithTheirLine) {
  ComponentSpec driver{"primitive_driver", 33, 1, 0, "", {{"command_timeout_s", "0.25"}, {"stop_brake_percent", "40"}},
                       7, {}};
  const auto options = components::primitive_driver_options({driver.kind, driver.options});
  ASSERT_TRUE(options) << options.error().message();
  EXPECT_EQ(options->command_timeout, std::chrono::milliseconds(250));
  EXPECT_EQ(options->stop_brake_percent, 40);

  ComponentSpec sensor{"global_pose_sensor", 38, 1, 0, "", {{"stale_after_s", "2"}, {"local_pose", "false"}}, 9, {}};
  const auto pose = components::global_pose_sensor_options({sensor.kind, sensor.options});
  ASSERT_TRUE(pose) << pose.error().message();
  EXPECT_EQ(pose->sensor.stale_after, std::chrono::seconds(2));
  EXPECT_FALSE(pose->local_pose);
  EXPECT_TRUE(check_component_options(sensor));

  ComponentSpec bad{"velocity_state_sensor", 42, 1, 0, "", {{"stale_after_s", "0"}}, 11, {{"stale_after_s", 13}}};
  const auto problem = check_component_options(bad);
  ASSERT_FALSE(problem);
  EXPECT_EQ(problem.error().line, 13);  // the option's own line
  EXPECT_NE(problem.error().what.find("stale_after_s"), std::string::npos) << problem.error().what;
  ComponentSpec arm{"primitive_manipulator", 49, 1, 0, "", {{"command_timeout_s", "1.5"}}, 3, {}};
  const auto manipulator = components::primitive_manipulator_options({arm.kind, arm.options});
  ASSERT_TRUE(manipulator) << manipulator.error().message();
  EXPECT_EQ(manipulator->command_timeout, std::chrono::milliseconds(1500));
  arm.options["command_timeout_s"] = "-1";
  ASSERT_FALSE(check_component_options(arm));
  EXPECT_NE(check_component_options(arm).error().what.find("command_timeout_s"), std::string::npos);

  ComponentSpec brake{"primitive_driver", 33, 1, 0, "", {{"stop_brake_percent", "101"}}, 5, {}};
  ASSERT_FALSE(check_component_options(brake));
  EXPECT_EQ(check_component_options(brake).error().line, 5);  // no option line known: the component's
}

TEST(ComponentKinds, AKindNoListHasIsRefusedEverywhere) {
  EXPECT_EQ(find_component_kind("warp_drive"), nullptr);
  EXPECT_FALSE(has_hardware("warp_drive"));
  EXPECT_FALSE(moves_hardware("warp_drive"));
  EXPECT_TRUE(check_component_options(ComponentSpec{"warp_drive", 99, 1, 0, "", {{"warp", "9"}}, 0, {}}));
  EXPECT_FALSE(remove_component_kind("warp_drive"));
}

// A kind of the test's own, registered at run time: the host builds it from
// a configuration, checks its options, gives it the hardware it needs and a
// latch, and refuses a second kind of the same name. Nothing in the host
// names it, as nothing there names the built-in ones.
struct TestKind {
  TestKind() {
    rt::ComponentKind kind{
        .name = "test_beacon",
        .default_id = 201,
        .options = {"period_s"},
        .needs = {components::PoseSource::kInterface},
        .moves_hardware = false,
        .one_per_node = false,
        .check = rt::check_by([](const rt::KindOptions& o) { return rt::number_option(o, "period_s", 0, 10, 1); }),
        .make = [this](const rt::KindContext& k) -> Expected<std::unique_ptr<rt::Component>> {
          const auto pose = k.need<components::PoseSource>();
          if (!pose) return unexpected(pose.error());
          const auto period = rt::number_option(k.options, "period_s", 0, 10, 1);
          if (!period) return unexpected(period.error());
          ++made;
          period_s = *period;
          struct Beacon : rt::Component {
            using Component::Component;
          };
          return std::unique_ptr<rt::Component>(std::make_unique<Beacon>(k.config, k.env));
        },
    };
    EXPECT_TRUE(add_component_kind(std::move(kind)));
  }
  ~TestKind() { EXPECT_TRUE(remove_component_kind("test_beacon")); }
  int made = 0;
  double period_s = 0;
};

TEST(ComponentKinds, AKindRegisteredByATestIsHostedLikeTheBuiltInOnes) {
  const std::size_t builtin = component_kinds().size();
  {
    TestKind kind;
    ASSERT_EQ(component_kinds().size(), builtin + 1);
    ASSERT_NE(find_component_kind("test_beacon"), nullptr);
    EXPECT_TRUE(has_hardware("test_beacon"));
    EXPECT_FALSE(moves_hardware("test_beacon"));
    const auto taken = add_component_kind(rt::ComponentKind{.name = "test_beacon",
                                                            .default_id = 202,
                                                            .options = {},
                                                            .needs = {},
                                                            .moves_hardware = false,
                                                            .one_per_node = false,
                                                            .check = {},
                                                            .make = [](const rt::KindContext&) {
                                                              return Expected<std::unique_ptr<rt::Component>>(nullptr);
                                                            }});
    ASSERT_FALSE(taken);
    EXPECT_EQ(taken.error().message(), "component kind 'test_beacon' already exists");

    // Its options are its own to check, with the option's line.
    ComponentSpec bad{"test_beacon", 201, 1, 0, "", {{"period_s", "11"}}, 4, {{"period_s", 6}}};
    const auto problem = check_component_options(bad);
    ASSERT_FALSE(problem);
    EXPECT_EQ(problem.error().what, "test_beacon option 'period_s' must be a number 0..10, got '11'");
    EXPECT_EQ(problem.error().line, 6);

    // On a host: made with the simulated vehicle's pose, and held by a latch of its own.
    boost::asio::io_context io;
    HostConfig config;
    config.link.bind = transport::Ipv4Endpoint{kLoopback, 0};
    config.components.push_back(ComponentSpec{"node_manager", 1, 1, 0, "", {}, 0, {}});
    config.components.push_back(ComponentSpec{"test_beacon", 201, 1, 0, "", {{"period_s", "2.5"}}, 0, {}});
    auto host = NodeHost::open(config, io);
    ASSERT_TRUE(host) << host.error().message();
    EXPECT_EQ(kind.made, 1);
    EXPECT_EQ(kind.period_s, 2.5);
    ASSERT_NE((*host)->node().find(Address{1, 1, 201, 1}), nullptr);
    EXPECT_EQ((*host)->node().find(Address{1, 1, 201, 1})->name(), "test_beacon");
    EXPECT_NE((*host)->backends().find<components::PoseSource>(), nullptr);  // made because it needs one
    EXPECT_NE((*host)->emergency_latch("1.1.201.1"), nullptr);
    (*host)->stop("test");

    // Without the hardware it needs: one error naming both.
    rt::VirtualTime time;
    struct NullLink : node::Link {
      void transmit(const Header&, std::span<const std::uint8_t>) override {}
    } link;
    node::Node node(node::NodeConfig{}, time, time, link);
    auto blind = make_component(ComponentSpec{"test_beacon", 201, 1, 0, "", {}, 0, {}}, {}, node);
    ASSERT_FALSE(blind);
    EXPECT_EQ(blind.error().message(), "test_beacon needs a vehicle pose source and the host has none");
  }
  // Removed: unknown again, and the list is the built-in one.
  EXPECT_EQ(component_kinds().size(), builtin);
  EXPECT_EQ(find_component_kind("test_beacon"), nullptr);
  boost::asio::io_context io;
  HostConfig config;
  config.link.bind = transport::Ipv4Endpoint{kLoopback, 0};
  config.components.push_back(ComponentSpec{"test_beacon", 201, 1, 0, "", {}, 0, {}});
  auto host = NodeHost::open(config, io);
  ASSERT_FALSE(host);
  EXPECT_EQ(host.error().message(), "component kind 'test_beacon' cannot be hosted by this build");
}

TEST(NodeHost, HostsConfiguredAndAddedComponentsAndStopsThemFirst) {
  boost::asio::io_context io;
  auto host = NodeHost::open(loopback_config(), io);
  ASSERT_TRUE(host) << host.error().message();
  NodeHost& h = **host;
  EXPECT_EQ(h.node().local_components().size(), component_kinds().size());
  EXPECT_NE(h.udp_link()->local_endpoint().port, 0);

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

// An opened host with the JSS face: AS5669A datagrams on its UDP socket reach
// the face, and its replies go back to the learnt endpoint.
TEST(NodeHost, AnOpenedHostAnswersJssOnItsUdpSocket) {
  boost::asio::io_context io;
  HostConfig config;
  config.link.bind = transport::Ipv4Endpoint{kLoopback, 0};
  config.jss.enabled = true;
  config.components = {ComponentSpec{"node_manager", 1, 1, 0, "", {}, 0, {}}};
  auto host = NodeHost::open(config, io);
  ASSERT_TRUE(host) << host.error().message();
  ASSERT_NE((*host)->jss_face(), nullptr);
  boost::asio::ip::udp::socket client(io, boost::asio::ip::udp::endpoint(boost::asio::ip::address_v4(kLoopback), 0));
  jss::JudpHeader header;
  header.source = jss::JssId{42, 1, 1};
  header.destination = jss::JssId{1, 1, 1};
  const auto query = jss::make_judp_datagram(header, std::vector<std::uint8_t>{0x00, 0x2B, 0x02});
  client.send_to(boost::asio::buffer(query),
                 boost::asio::ip::udp::endpoint(boost::asio::ip::address_v4(kLoopback),
                                                (*host)->udp_link()->local_endpoint().port));
  std::array<std::uint8_t, 2000> buffer{};
  std::size_t size = 0;
  client.async_receive(boost::asio::buffer(buffer), [&](const boost::system::error_code& ec, std::size_t n) {
    if (!ec) size = n;
  });
  const auto deadline = std::chrono::steady_clock::now() + 10s;
  while (size == 0 && std::chrono::steady_clock::now() < deadline) io.run_for(5ms);
  const auto reply = jss::decode_judp_datagram(std::span(buffer).first(size));
  ASSERT_TRUE(reply) << reply.error().message();
  EXPECT_EQ(jss::message_id_of(reply->front().contents), 0x4B00);  // Report Identification
  EXPECT_EQ(reply->front().header.destination, header.source);
  EXPECT_EQ((*host)->udp_link()->counters().jss.datagrams_delivered, 1u);
}

// A vehicle's posture warnings (an open bind, holds not persisted) are the
// node's; an operator's own node (jausctl, jaus-console) says none of them
// and never touches a holds file (issue 49).
TEST(NodeHost, PostureWarningsAreAVehiclesNotAnOperatorUnits) {
  const auto open_logging = [](bool operator_unit) {
    boost::asio::io_context io;
    HostConfig config;
    config.link.bind = transport::Ipv4Endpoint{0, 0};  // every address, any port: open
    config.operator_unit = operator_unit;
    config.components.push_back(ComponentSpec{"node_manager", 1, 1, 0, "", {}, 0, {}});
    std::vector<std::string> lines;
    auto host = NodeHost::open(config, io, [&](rt::LogLevel, const std::string& l) { lines.push_back(l); });
    EXPECT_TRUE(host) << host.error().message();
    if (host) (*host)->stop("test");
    return lines;
  };
  const auto said = [](const std::vector<std::string>& lines, const std::string& text) {
    return std::any_of(lines.begin(), lines.end(), [&](const auto& l) { return l.find(text) != std::string::npos; });
  };
  const auto vehicle = open_logging(false);
  EXPECT_TRUE(said(vehicle, "any host on the network may command this node"));
  if (!std::getenv("STATE_DIRECTORY")) {
    EXPECT_TRUE(said(vehicle, "emergency holds are not persisted"));
  }
  const auto operator_unit = open_logging(true);
  EXPECT_FALSE(said(operator_unit, "any host on the network"));
  EXPECT_FALSE(said(operator_unit, "not persisted"));
}

// Safety: whatever ends the event loop, every component's stop path runs
// before run() returns (the platform is commanded to stop).
TEST(NodeHost, AnExceptionEscapingTheLoopStillStopsEveryComponent) {
  boost::asio::io_context io;
  std::vector<std::string> lines;
  auto host = NodeHost::open(loopback_config(), io, [&](rt::LogLevel, const std::string& l) { lines.push_back(l); });
  ASSERT_TRUE(host) << host.error().message();
  boost::asio::post(io, [] { throw std::runtime_error("out of memory"); });
  const auto ran = (*host)->run(io);
  ASSERT_FALSE(ran);
  EXPECT_EQ(ran.error().message(), "out of memory");
  EXPECT_TRUE((*host)->stopped());
  EXPECT_TRUE((*host)->node().local_components().empty());
  const auto logged = [&](const std::string& text) {
    return std::any_of(lines.begin(), lines.end(), [&](const auto& l) { return l.find(text) != std::string::npos; });
  };
  EXPECT_TRUE(logged("event loop failed: out of memory; stopping"));
  EXPECT_TRUE(logged("stopped (exception: out of memory)"));
}

// The host installs no signal handler (jausd does, tests/system): whatever
// stops the loop, the host stops in order before run() returns.
TEST(NodeHost, TheLoopStoppedIsAnOrderlyStop) {
  boost::asio::io_context io;
  std::vector<std::string> lines;
  auto host = NodeHost::open(loopback_config(), io, [&](rt::LogLevel, const std::string& l) { lines.push_back(l); });
  ASSERT_TRUE(host) << host.error().message();
  boost::asio::post(io, [&io] { io.stop(); });
  EXPECT_TRUE((*host)->run(io));
  EXPECT_TRUE((*host)->stopped());
  EXPECT_TRUE((*host)->node().local_components().empty());
  EXPECT_TRUE(std::any_of(lines.begin(), lines.end(),
                          [](const auto& l) { return l.find("stopped (event loop ended)") != std::string::npos; }));
}

TEST(NodeHost, ABusyAddressIsOneIoError) {
  boost::asio::io_context io;
  auto first = NodeHost::open(loopback_config(), io);
  ASSERT_TRUE(first) << first.error().message();
  HostConfig second_config = loopback_config();
  second_config.link.bind = (*first)->udp_link()->local_endpoint();
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

// A Set Emergency or Clear Emergency from `from`, as the node hands it to `to`.
template <class M>
void deliver(rt::Component& to, const Address& from, const M& message) {
  std::vector<std::uint8_t> payload(kMaxPayloadSize);
  const auto size = wire::encode_payload(message, payload);
  ASSERT_TRUE(size);
  Header header;
  header.command_code = M::code;
  header.source = from;
  header.destination = to.address();
  header.data_size = static_cast<std::uint16_t>(*size);
  to.receive(header, std::span(payload).first(*size));
}

// A Clearpath platform (simulated in process): the mobility components run on
// the bridge; the platform's own e-stop holds them all in Emergency until it
// clears, and the driver's JAUS Emergency sets the platform's emergency flag.
TEST(NodeHost, OnAClearpathPlatformItsEstopAndJausEmergencyMirrorEachOther) {
  boost::asio::io_context io;
  HostConfig config = loopback_config();
  ClearpathSettings settings;
  settings.vehicle.emergency_flags = 0x08;
  config.arm.joints = {components::JointConfig{}};
  settings.arm.joints = {{0, 1, 0}};  // the one joint on Clearpath joint 0
  config.platform = clearpath_sim_platform_settings(settings);
  auto host = NodeHost::open(config, io);
  ASSERT_TRUE(host) << host.error().message();
  NodeHost& h = **host;
  auto* clearpath = h.platform_as<ClearpathPlatform>();
  ASSERT_NE(clearpath, nullptr);
  ASSERT_NE(clearpath->vehicle(), nullptr);
  EXPECT_EQ(clearpath->simulated().vehicle(), nullptr);  // no direct simulation
  EXPECT_NE(clearpath->arm(), nullptr);
  EXPECT_EQ(clearpath->simulated().arm(), nullptr);
  EXPECT_EQ(clearpath->cameras(), nullptr);  // no mount mapped: the cameras stay simulated
  EXPECT_NE(clearpath->simulated().cameras(), nullptr);
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

  // Someone presses the platform's e-stop.
  auto* platform = dynamic_cast<clearpath::sim::LoopbackClient*>(clearpath->client());
  ASSERT_NE(platform, nullptr);
  const auto press = [&](bool on) { platform->platform().press(clearpath::sim::HardwareInput::estop, on, h.clock().now()); };
  press(true);
  EXPECT_TRUE(run_until([&] { return driver->state() == rt::PrimaryStatus::emergency && pose->state() == rt::PrimaryStatus::emergency; }));
  press(false);
  EXPECT_TRUE(run_until([&] { return driver->state() == rt::PrimaryStatus::ready && pose->state() == rt::PrimaryStatus::ready; }));

  // JAUS Emergency on the driver: the platform's flag is set, and is not taken for its own e-stop.
  // Waited for on the platform itself, then a while for its safety status to
  // come back (that it is not taken for an e-stop is also asserted under
  // virtual time, tests/bridge/clearpath_vehicle_test.cpp).
  const Address kOperatorOnTheDriver{9, 1, 40, 1};
  deliver(*driver, kOperatorOnTheDriver, msg::SetEmergency{});
  EXPECT_TRUE(run_until([&] { return (platform->platform().vehicle().commanded_safety() & 0x08) != 0; }));
  io.run_for(std::chrono::milliseconds(300));
  EXPECT_EQ(pose->state(), rt::PrimaryStatus::ready);  // a sensor is not a moving component
  EXPECT_EQ(driver->state(), rt::PrimaryStatus::emergency);
  deliver(*driver, kOperatorOnTheDriver, msg::ClearEmergency{});
  EXPECT_TRUE(run_until([&] { return driver->state() == rt::PrimaryStatus::ready; }));
  EXPECT_EQ(platform->platform().vehicle().commanded_safety() & 0x08, 0);
  h.stop("test");
}

// An attached host: the same node and components on a memory link under
// virtual time, no socket and no real clock; a tester at 2.1.40.1 on the same
// network sends it what an OCU would.
class AttachedHost : public ::testing::Test {
 protected:
  static constexpr Address kTester{2, 1, 40, 1};

  std::unique_ptr<NodeHost> attach(HostConfig config) {
    auto host = NodeHost::attach(std::move(config), host_link, time, time,
                                 [this](rt::LogLevel, const std::string& l) { lines.push_back(l); });
    if (!host) {
      ADD_FAILURE() << host.error().message();
      return nullptr;
    }
    host_link.deliver_to((*host)->node());
    return std::move(*host);
  }
  template <class M>
  void send(const Address& to, const M& message) {
    Header header;
    header.source = kTester;
    header.destination = to;
    std::vector<std::uint8_t> packet(kHeaderSize + kMaxPayloadSize);
    const auto size = wire::encode_message(header, message, packet);
    ASSERT_TRUE(size) << size.error().message();
    packet.resize(*size);
    header.command_code = M::code;
    header.data_size = static_cast<std::uint16_t>(*size - kHeaderSize);
    tester_link.transmit(header, packet);
  }
  // The components that sent the tester a message with this code.
  std::vector<Address> senders_of(std::uint16_t code) const {
    std::vector<Address> senders;
    for (const auto& h : received)
      if (h.command_code == code) senders.push_back(h.source);
    return senders;
  }

  rt::VirtualTime time;
  testing::MemoryNetwork network{time, time};
  testing::MemoryLink& host_link = network.attach(1, 1);
  testing::MemoryLink& tester_link = [this]() -> testing::MemoryLink& {
    auto& link = network.attach(2, 1);
    link.on_receive([this](std::span<const std::uint8_t> bytes) {
      if (auto packet = decode_packet(bytes)) received.push_back(packet->header);
    });
    return link;
  }();
  std::vector<Header> received;
  std::vector<std::string> lines;
};

TEST_F(AttachedHost, OnceAMinuteItSaysWhatWasDroppedAndOnlyWhenSomethingWas) {
  auto host = attach(loopback_config());
  ASSERT_NE(host, nullptr);
  const auto summaries = [&] {
    return std::count_if(lines.begin(), lines.end(),
                         [](const std::string& l) { return l.rfind("in the last minute: ", 0) == 0; });
  };
  time.advance(61s);
  EXPECT_EQ(summaries(), 0);  // nothing dropped: nothing said
  const std::uint8_t junk[] = {0x06, 0x00, 0x01};
  host->node().receive_bytes(junk);
  host->node().receive_bytes(junk);
  time.advance(60s);
  ASSERT_EQ(summaries(), 1);
  const auto line = *std::find_if(lines.begin(), lines.end(),
                                  [](const std::string& l) { return l.rfind("in the last minute: ", 0) == 0; });
  EXPECT_EQ(line, "in the last minute: 2 malformed packets");
  time.advance(60s);
  EXPECT_EQ(summaries(), 1);  // a quiet minute: no line
  host->stop("test");
}

TEST(DropSummary, NamesEachCountThatGrewAndTheReplacedOnlyBesideADrop) {
  DropCounts before;
  DropCounts now = before;
  now.budget_replaced = 40;
  now.received[static_cast<std::size_t>(transport::DropReason::from_self)] = 60;  // our multicast, looped back
  EXPECT_EQ(describe_drops(before, now), "");  // frames replaced by newer are the budget at work
  now.received[static_cast<std::size_t>(transport::DropReason::not_allowed)] = 10;
  now.received[static_cast<std::size_t>(transport::DropReason::truncated)] = 4;
  now.not_sent = 2;
  now.budget_full = 3;
  EXPECT_EQ(describe_drops(before, now),
            "in the last minute: 14 datagrams dropped on receipt (4 truncated, 10 source not allowed), 2 messages not sent, "
            "3 dropped by the send budget (queue full), 40 waiting reports and frames replaced by newer");
}

TEST_F(AttachedHost, EveryBuiltInKindAnswersAQueryOverAMemoryLink) {
  auto host = attach(loopback_config());
  ASSERT_NE(host, nullptr);
  EXPECT_EQ(host->udp_link(), nullptr);  // no socket
  const auto components = host->node().local_components();
  ASSERT_EQ(components.size(), component_kinds().size());
  for (const auto* component : components) send(component->address(), msg::QueryComponentStatus{});
  EXPECT_TRUE(testing::run_until(time, [&] { return senders_of(msg::ReportComponentStatus::code).size() == components.size(); }, 1s));
  for (const auto* component : components) {
    const auto senders = senders_of(msg::ReportComponentStatus::code);
    EXPECT_NE(std::find(senders.begin(), senders.end(), component->address()), senders.end()) << component->name();
  }
  host->stop("test");
  EXPECT_TRUE(host->node().local_components().empty());
  EXPECT_TRUE(std::any_of(lines.begin(), lines.end(), [](const auto& l) { return l.find("stopped (test)") != std::string::npos; }));
}

// Safety under virtual time: a controller that goes silent loses control,
// and the driver stops the vehicle it was driving.
TEST_F(AttachedHost, ItsPrimitiveDriverStopsWhenTheControllerGoesSilent) {
  HostConfig config;
  config.components = {ComponentSpec{"primitive_driver", 33, 1, 0, "", {{"command_timeout_s", "0"}}, 0, {}}};
  auto host = attach(config);
  ASSERT_NE(host, nullptr);
  const Address driver_address{1, 1, 33, 1};
  rt::Component& driver = *host->node().find(driver_address);
  send(driver_address, msg::RequestComponentControl{{255}});
  ASSERT_TRUE(testing::run_until(time, [&] { return driver.control().is_controller(kTester); }, 1s));
  msg::SetWrenchEffort effort;
  effort.propulsive_linear_effort_x_percent = 60;
  send(driver_address, effort);
  auto* vehicle = host->platform_as<ModelPlatform>()->vehicle();
  ASSERT_NE(vehicle, nullptr);
  ASSERT_TRUE(testing::run_until(time, [&] { return vehicle->applied_effort().propulsive_linear.x > 0; }, 1s));
  testing::run_for(time, 2s);
  EXPECT_GT(vehicle->applied_effort().propulsive_linear.x, 0);  // no command timeout configured
  testing::run_for(time, 2s);  // 4 s of silence > the 3 s controller timeout
  EXPECT_FALSE(driver.control().is_controller(kTester));
  EXPECT_EQ(vehicle->applied_effort().propulsive_linear.x, 0);
}

// clearpath_sim on the host's clock and scheduler: the platform's e-stop holds
// the driver in Emergency, in virtual time.
TEST_F(AttachedHost, OnASimulatedClearpathPlatformItsEstopHoldsTheDriver) {
  HostConfig config;
  config.platform.kind = "clearpath_sim";  // by name alone: the kind's settings all default
  config.components = {ComponentSpec{"primitive_driver", 33, 1, 0, "", {}, 0, {}}};
  auto host = attach(config);
  ASSERT_NE(host, nullptr);
  auto& clearpath = *host->platform_as<ClearpathPlatform>();
  auto* loopback = dynamic_cast<clearpath::sim::LoopbackClient*>(clearpath.client());
  ASSERT_NE(loopback, nullptr);
  rt::Component& driver = *host->node().find(Address{1, 1, 33, 1});
  ASSERT_TRUE(testing::run_until(time, [&] { return driver.state() == rt::PrimaryStatus::ready; }, 5s));
  loopback->platform().press(clearpath::sim::HardwareInput::estop, true, time.now());
  EXPECT_TRUE(testing::run_until(time, [&] { return driver.state() == rt::PrimaryStatus::emergency; }, 5s));
  loopback->platform().press(clearpath::sim::HardwareInput::estop, false, time.now());
  EXPECT_TRUE(testing::run_until(time, [&] { return driver.state() == rt::PrimaryStatus::ready; }, 5s));
}

TEST(NodeHostAttach, ARealClearpathPlatformNeedsAnOpenedHost) {
  rt::VirtualTime time;
  testing::MemoryNetwork network(time, time);
  HostConfig config = loopback_config();
  clearpath::PlatformEndpoint endpoint;
  endpoint.kind = clearpath::PlatformEndpoint::Kind::udp;
  endpoint.port = 7000;
  config.platform = clearpath_platform_settings(endpoint);
  auto host = NodeHost::attach(config, network.attach(1, 1), time, time);
  ASSERT_FALSE(host);
  EXPECT_NE(host.error().message().find("NodeHost::open"), std::string::npos) << host.error().message();
}

class EmergencyHolds : public ::testing::Test {
 protected:
  EmergencyHolds() {
    dir = std::filesystem::temp_directory_path() / ("jaus-holds-" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
  }
  ~EmergencyHolds() override { std::filesystem::remove_all(dir); }
  HostConfig config(EmergencyScope scope = EmergencyScope::vehicle) const {
    HostConfig c = loopback_config();
    c.emergency.state_directory = dir.string();
    c.emergency.scope = scope;
    return c;
  }
  static rt::PrimaryStatus state_of(NodeHost& h, std::uint8_t id) { return h.node().find(Address{1, 1, id, 1})->state(); }

  std::filesystem::path dir;
  boost::asio::io_context io;
};

constexpr std::uint8_t kDriverId = 33, kArmId = 49, kCamerasId = 37, kPoseId = 38;
const Address kOperator{9, 1, 40, 1};

// Vehicle scope: Set Emergency to the driver holds the arm and the cameras'
// mounts too; the holder clears it from any of them.
TEST_F(EmergencyHolds, SetEmergencyToOneMovingComponentHoldsTheVehicle) {
  auto host = NodeHost::open(config(), io);
  ASSERT_TRUE(host) << host.error().message();
  NodeHost& h = **host;
  deliver(*h.node().find(Address{1, 1, kDriverId, 1}), kOperator, msg::SetEmergency{});
  for (auto id : {kDriverId, kArmId, kCamerasId}) EXPECT_EQ(state_of(h, id), rt::PrimaryStatus::emergency) << int{id};
  EXPECT_NE(state_of(h, kPoseId), rt::PrimaryStatus::emergency);  // a sensor moves nothing
  deliver(*h.node().find(Address{1, 1, kArmId, 1}), kOperator, msg::ClearEmergency{});
  for (auto id : {kDriverId, kArmId, kCamerasId}) EXPECT_NE(state_of(h, id), rt::PrimaryStatus::emergency) << int{id};
}

TEST_F(EmergencyHolds, ComponentScopeHoldsOnlyTheComponentAsked) {
  auto host = NodeHost::open(config(EmergencyScope::component), io);
  ASSERT_TRUE(host) << host.error().message();
  deliver(*(*host)->node().find(Address{1, 1, kDriverId, 1}), kOperator, msg::SetEmergency{});
  EXPECT_EQ(state_of(**host, kDriverId), rt::PrimaryStatus::emergency);
  EXPECT_NE(state_of(**host, kArmId), rt::PrimaryStatus::emergency);
}

// Holds survive a restart; SIGUSR1's local clear releases holders gone for good.
TEST_F(EmergencyHolds, HoldsSurviveARestartAndTheLocalClearReleasesThem) {
  {
    auto host = NodeHost::open(config(), io);
    ASSERT_TRUE(host) << host.error().message();
    deliver(*(*host)->node().find(Address{1, 1, kArmId, 1}), kOperator, msg::SetEmergency{});
    (*host)->stop("test");
  }
  auto host = NodeHost::open(config(), io);
  ASSERT_TRUE(host) << host.error().message();
  NodeHost& h = **host;
  for (auto id : {kDriverId, kArmId, kCamerasId}) EXPECT_EQ(state_of(h, id), rt::PrimaryStatus::emergency) << int{id};
  ASSERT_NE(h.emergency_latch("vehicle"), nullptr);
  // Delivered past the link, the holder has no host on record: it holds
  // until the local clear (issue 42; bound holders: emergency_binding_test.cpp).
  EXPECT_TRUE(h.emergency_latch("vehicle")->overflowed());
  EXPECT_EQ(h.clear_emergency_holds_locally("test"), 1u);
  for (auto id : {kDriverId, kArmId, kCamerasId}) EXPECT_NE(state_of(h, id), rt::PrimaryStatus::emergency) << int{id};
  h.stop("test");
  // ...and the clear is persisted too.
  auto again = NodeHost::open(config(), io);
  ASSERT_TRUE(again);
  EXPECT_NE(state_of(**again, kDriverId), rt::PrimaryStatus::emergency);
}

// The local clear (SIGUSR1) reaches every component's holds, not only the
// moving ones': the communicator's and a sensor's own latches, the node
// manager's, and the vehicle's shared one, each logged with who held it.
TEST_F(EmergencyHolds, TheLocalClearReleasesTheHoldsOfEveryComponentSensorsAndCommunicatorIncluded) {
  constexpr std::uint8_t kCommunicatorId = 35, kNodeManagerId = 1;
  const Address other_operator{9, 2, 40, 1};
  std::vector<std::string> lines;
  auto host = NodeHost::open(config(), io, [&](rt::LogLevel, const std::string& l) { lines.push_back(l); });
  ASSERT_TRUE(host) << host.error().message();
  NodeHost& h = **host;
  deliver(*h.node().find(Address{1, 1, kCommunicatorId, 1}), kOperator, msg::SetEmergency{});
  deliver(*h.node().find(Address{1, 1, kPoseId, 1}), kOperator, msg::SetEmergency{});
  deliver(*h.node().find(Address{1, 1, kNodeManagerId, 1}), other_operator, msg::SetEmergency{});
  deliver(*h.node().find(Address{1, 1, kDriverId, 1}), other_operator, msg::SetEmergency{});
  const std::vector<std::uint8_t> held{kCommunicatorId, kPoseId, kNodeManagerId, kDriverId, kArmId};
  for (auto id : held) ASSERT_EQ(state_of(h, id), rt::PrimaryStatus::emergency) << int{id};
  EXPECT_EQ(h.clear_emergency_holds_locally("test"), 4u);
  for (auto id : held) EXPECT_NE(state_of(h, id), rt::PrimaryStatus::emergency) << int{id};
  // Those without hardware are back in Ready (the others wait for theirs, not run here).
  EXPECT_EQ(state_of(h, kCommunicatorId), rt::PrimaryStatus::ready);
  EXPECT_EQ(state_of(h, kNodeManagerId), rt::PrimaryStatus::ready);
  const auto logged = [&](const std::string& text) {
    return std::any_of(lines.begin(), lines.end(), [&](const std::string& l) { return l.find(text) != std::string::npos; });
  };
  EXPECT_TRUE(logged("emergency holds cleared locally (test), 1.1.35.1 (communicator): 9.1.40.1"));
  EXPECT_TRUE(logged("emergency holds cleared locally (test), 1.1.38.1: 9.1.40.1"));
  EXPECT_TRUE(logged("emergency holds cleared locally (test), 1.1.1.1 (node_manager): 9.2.40.1"));
  EXPECT_TRUE(logged("emergency holds cleared locally (test), vehicle: 9.2.40.1"));
  // Nothing left: a second clear says so.
  EXPECT_EQ(h.clear_emergency_holds_locally("again"), 0u);
  EXPECT_TRUE(logged("local clear of emergency holds (again): none held"));
}

// Component scope: each component's own latch, every one of them cleared.
TEST_F(EmergencyHolds, TheLocalClearReleasesEveryComponentsOwnLatchInComponentScope) {
  auto host = NodeHost::open(config(EmergencyScope::component), io);
  ASSERT_TRUE(host) << host.error().message();
  NodeHost& h = **host;
  for (const auto* component : h.node().local_components())
    deliver(*h.node().find(component->address()), kOperator, msg::SetEmergency{});
  std::size_t components = 0;
  for (const auto* component : h.node().local_components()) {
    ++components;
    ASSERT_EQ(component->state(), rt::PrimaryStatus::emergency) << component->name();
  }
  EXPECT_EQ(h.clear_emergency_holds_locally("test"), components);
  for (const auto* component : h.node().local_components())
    EXPECT_NE(component->state(), rt::PrimaryStatus::emergency) << component->name();
}

// A disk that fails while running: HoldBinding.AFailingWriteRefusesClearsAndIsSaidOncePerStreak
// (emergency_binding_test.cpp).

TEST_F(EmergencyHolds, AnUnreadableHoldsFileHoldsEverythingUntilTheLocalClear) {
  std::ofstream(dir / "emergency-holds") << "vehicle not-an-address\n";
  auto host = NodeHost::open(config(), io);
  ASSERT_TRUE(host) << host.error().message();
  NodeHost& h = **host;
  for (auto id : {kDriverId, kArmId, kCamerasId, kPoseId}) EXPECT_EQ(state_of(h, id), rt::PrimaryStatus::emergency) << int{id};
  EXPECT_GE(h.clear_emergency_holds_locally("test"), 1u);
  EXPECT_NE(state_of(h, kDriverId), rt::PrimaryStatus::emergency);
}

// ---- the JSS face on an attached host ------------------------------------------
// jss.enabled: the node's link is a FaceLink around the memory link, the face
// is made after the node; what the face sends goes through set_jss_sender's
// function and what a JSS client sends is handed to jss_face()->receive().

class AttachedJssHost : public AttachedHost {
 protected:
  static constexpr jss::JssId kClient{42, 1, 1};  // a JSS operator unit
  static constexpr jss::JssId kDriver{1, 1, 33};  // our primitive driver in JSS

  std::unique_ptr<NodeHost> attach_jss() {
    HostConfig config;
    config.jss.enabled = true;
    config.settings.defaults.controller_timeout = 5s;
    config.settings.identity.subsystem_name = "judged vehicle";
    config.components = {ComponentSpec{"node_manager", 1, 1, 0, "", {}, 0, {}},
                         ComponentSpec{"primitive_driver", 33, 1, 0, "", {}, 0, {}}};
    auto host = attach(config);
    if (host)
      host->set_jss_sender([this](const jss::JssId& to, std::span<const std::uint8_t> datagram) {
        sent_to_jss.push_back({to, {datagram.begin(), datagram.end()}});
      });
    return host;
  }
  void from_client(NodeHost& host, const jss::JssId& to, std::vector<std::uint8_t> contents) {
    jss::JudpHeader header;
    header.source = kClient;
    header.destination = to;
    header.sequence = sequence++;
    host.jss_face()->receive(jss::make_judp_datagram(header, contents), rt::SenderStanding::trusted);
  }
  // The contents of the JSS messages sent to the client with this message ID.
  std::vector<std::vector<std::uint8_t>> to_client(std::uint16_t message_id) const {
    std::vector<std::vector<std::uint8_t>> out;
    for (const auto& [to, datagram] : sent_to_jss) {
      const auto packets = jss::decode_judp_datagram(datagram);
      if (!packets || to != kClient) continue;
      for (const auto& p : *packets)
        if (jss::message_id_of(p.contents) == message_id) out.emplace_back(p.contents.begin(), p.contents.end());
    }
    return out;
  }

  std::vector<std::pair<jss::JssId, std::vector<std::uint8_t>>> sent_to_jss;
  std::uint16_t sequence = 0;
};

TEST_F(AttachedJssHost, OffByDefaultOnWhenEnabledWithTheNodesIdentityAndTimeout) {
  HostConfig off;
  off.components = {ComponentSpec{"node_manager", 1, 1, 0, "", {}, 0, {}}};
  EXPECT_EQ(attach(off)->jss_face(), nullptr);
  auto host = attach_jss();
  ASSERT_NE(host, nullptr);
  ASSERT_NE(host->jss_face(), nullptr);
  EXPECT_EQ(host->jss_face()->config().controller_timeout_s, 5);
  EXPECT_EQ(host->jss_face()->config().subsystem_name, "judged vehicle");
  EXPECT_EQ(host->jss_face()->jss_id_of(Address{1, 1, 33, 1}), kDriver);
}

TEST_F(AttachedJssHost, TheSenderCarriesTheFacesReplies) {
  auto host = attach_jss();
  ASSERT_NE(host, nullptr);
  from_client(*host, jss::JssId{1, 1, 1}, {0x00, 0x2B, 0x02});  // Query Identification, subsystem
  ASSERT_TRUE(testing::run_until(time, [&] { return !to_client(0x4B00).empty(); }, 1s));  // Report Identification
  EXPECT_EQ(host->jss_face()->counters().datagrams_received, 1u);
}

TEST_F(AttachedJssHost, TheFaceLinkHandsAliasTrafficToTheFaceAndTheStopStillReachesIt) {
  auto host = attach_jss();
  ASSERT_NE(host, nullptr);
  rt::Component& driver = *host->node().find(Address{1, 1, 33, 1});
  from_client(*host, kDriver, {0x0D, 0x00, 200});  // Request Control, authority 200
  // The RA Confirm Component Control to the client's alias went to the face, which confirmed in JSS.
  ASSERT_TRUE(testing::run_until(time, [&] { return !to_client(0x000F).empty(); }, 1s));
  EXPECT_EQ(to_client(0x000F).front(), (std::vector<std::uint8_t>{0x0F, 0x00, 0x00}));  // CONTROL_ACCEPTED
  ASSERT_TRUE(driver.control().controller());
  const Address alias = driver.control().controller()->address;
  EXPECT_EQ(alias.subsystem, 250);
  EXPECT_TRUE(host->jss_face()->owns(alias));
  // Nothing for the alias went out on the RA link.
  EXPECT_TRUE(std::none_of(received.begin(), received.end(), [](const Header& h) { return h.destination.subsystem == 250; }));
  // The orderly stop releases control; the face, still there, tells the client in JSS (Reject Control, released).
  host->stop("test");
  EXPECT_FALSE(to_client(0x0010).empty());
  host.reset();  // the face goes first, then the node and the links: no use after free (ASan)
}

}  // namespace
}  // namespace jaus::host
