// Platforms as a registry (host/include/jaus/host/platform_kinds.hpp): the
// kinds the platform libraries register, how settings are checked (and where
// a problem is), and a node built on a test-only kind the host has never heard
// of, with its stop path and emergency hooks called as on a built-in one.
#include <gtest/gtest.h>

#include <algorithm>
#include <charconv>
#include <string>
#include <vector>

#include "jaus/base/virtual_time.hpp"
#include "jaus/host/clearpath_platform.hpp"
#include "jaus/host/model_platform.hpp"
#include "jaus/host/node_host.hpp"
#include "jaus/host/platform_kinds.hpp"
#include "jaus/testing/memory_link.hpp"
#include "jaus/testing/virtual_time.hpp"

namespace jaus::host {
namespace {

using namespace std::chrono_literals;

std::vector<std::string> kind_names() {
  std::vector<std::string> names;
  for (const auto& kind : platform_kinds()) names.emplace_back(kind.name);
  return names;
}

TEST(PlatformKinds, TheBuiltInKindsAreListedWithHowAConfigurationNamesThem) {
  const auto names = kind_names();
  for (const char* name : {"model", "clearpath_sim", "clearpath"})
    EXPECT_NE(std::find(names.begin(), names.end(), name), names.end()) << name;
  EXPECT_EQ(builtin_platform_kinds().size(), 3u);
  ASSERT_NE(platform_kind_written("sim"), nullptr);
  EXPECT_EQ(platform_kind_written("sim")->name, "clearpath_sim");
  EXPECT_EQ(platform_kind_written("model")->name, "model");
  EXPECT_EQ(platform_kind_written("clearpath"), nullptr);  // only by its options
  for (const char* key : {"serial", "baud", "udp", "tcp"}) {
    ASSERT_NE(platform_kind_with_option(key), nullptr) << key;
    EXPECT_EQ(platform_kind_with_option(key)->name, "clearpath");
  }
  EXPECT_EQ(platform_kind_with_option("wheels"), nullptr);
  // A host's default: the components' own simulations.
  EXPECT_EQ(HostConfig{}.platform.kind, "model");
}

TEST(PlatformKinds, AnUnknownKindOrOptionIsRefusedSayingWhere) {
  PlatformSettings settings;
  settings.kind = "hovercraft";
  auto checked = check_platform(settings, {});
  ASSERT_FALSE(checked);
  EXPECT_NE(checked.error().message().find("platform kind 'hovercraft' is not in this build (known: "),
            std::string::npos)
      << checked.error().message();
  settings.kind = "model";
  settings.options = {{"serial", "/dev/ttyS0"}};  // another kind's option
  checked = check_platform(settings, {});
  ASSERT_FALSE(checked);
  EXPECT_EQ(checked.error().field, "serial");
  EXPECT_EQ(checked.error().message(), "platform model takes no option 'serial'");
}

TEST(PlatformKinds, AClearpathPlatformIsWhereItsOptionsSay) {
  clearpath::PlatformEndpoint serial;
  serial.device = "/dev/ttyS3";
  serial.baud = 57600;
  const auto read = clearpath_endpoint(clearpath_platform_settings(serial));
  ASSERT_TRUE(read) << read.error().message();
  EXPECT_EQ(read->kind, clearpath::PlatformEndpoint::Kind::serial);
  EXPECT_EQ(read->device, "/dev/ttyS3");
  EXPECT_EQ(read->baud, 57600u);

  const auto problem = [](std::map<std::string, std::string> options) {
    PlatformSettings settings;
    settings.kind = "clearpath";
    settings.options = std::move(options);
    const auto checked = check_platform(settings, {});
    EXPECT_FALSE(checked);
    return checked ? Error{} : checked.error();
  };
  Error e = problem({});
  EXPECT_EQ(e.message(), "'platform' needs exactly one of serial, udp or tcp");
  EXPECT_EQ(e.field, "");  // the platform itself
  e = problem({{"udp", "1.2.3.4:5"}, {"baud", "9600"}});
  EXPECT_EQ(e.message(), "'platform': baud applies to a serial port only");
  e = problem({{"udp", "nowhere"}});
  EXPECT_EQ(e.message(), "'udp' must be HOST:PORT, got 'nowhere'");
  EXPECT_EQ(e.field, "udp");
  e = problem({{"serial", "/dev/ttyS0"}, {"baud", "12"}});
  EXPECT_EQ(e.message(), "'baud' must be an integer 1200..4000000, got '12'");
  EXPECT_EQ(e.field, "baud");
}

TEST(PlatformKinds, TheSimulatedClearpathPlatformSteersAsTheVehicle) {
  SimulationSettings ackermann;
  ackermann.vehicle.steering = components::Steering::ackermann;
  ClearpathSettings differential;  // differential_output
  auto checked = check_platform(clearpath_sim_platform_settings(differential), ackermann);
  ASSERT_FALSE(checked);
  EXPECT_EQ(checked.error().field, "clearpath");
  EXPECT_NE(checked.error().message().find("vehicle.steering must be differential"), std::string::npos);
  ClearpathSettings steered;
  steered.vehicle.drive = bridge::DriveMode::ackermann;
  EXPECT_TRUE(check_platform(clearpath_sim_platform_settings(steered), ackermann));
  // A real platform steers as it is built: nothing to agree with.
  clearpath::PlatformEndpoint udp;
  udp.kind = clearpath::PlatformEndpoint::Kind::udp;
  udp.port = 7000;
  EXPECT_TRUE(check_platform(clearpath_platform_settings(udp, differential), ackermann));
  // A mapping the arm cannot take: the `clearpath` section first, else the manipulator's.
  ClearpathSettings bad_arm;
  bad_arm.arm.joints = {{0, 1, 0}, {1, 1, 0}};  // two mappings for the default arm's joints
  SimulationSettings one_joint;
  one_joint.arm.joints = {components::JointConfig{}};
  checked = check_platform(clearpath_sim_platform_settings(bad_arm), one_joint);
  ASSERT_FALSE(checked);
  EXPECT_EQ(checked.error().field, "clearpath|manipulator");
}

// ---- a kind of the test's own

// What the host did with the test's platform.
struct RigCalls {
  std::vector<std::string> provided;
  bool followed = false;
  rt::EmergencyLatch* driver = nullptr;
  int reclaims = 0;
  int stops = 0;
};

// Its own section: the wheels' count comes from the option, this from code.
struct RigSettings {
  static constexpr std::string_view kSection = "rig";
  std::string label = "rig";
};

// The components' simulations, as `model`, with every hook the host calls counted.
class RigPlatform final : public Platform {
 public:
  RigPlatform(RigCalls& calls, SimulationSettings simulation, PlatformEnvironment environment)
      : calls_(calls), model_(std::move(simulation), std::move(environment)) {}
  Expected<void> provide(std::string_view interface, rt::Backends& backends) override {
    calls_.provided.emplace_back(interface);
    return model_.provide(interface, backends);
  }
  void follow_emergencies(std::vector<rt::EmergencyLatch*>, rt::EmergencyLatch* driver) override {
    calls_.followed = true;
    calls_.driver = driver;
  }
  void reclaim_stops() override { ++calls_.reclaims; }
  void stop() override {
    ++calls_.stops;
    model_.stop();
  }

 private:
  RigCalls& calls_;
  ModelPlatform model_;
};

Expected<int> wheels(const PlatformSettings& settings) {
  const auto it = settings.options.find("wheels");
  if (it == settings.options.end()) return 4;
  int value = 0;
  const auto [end, ec] = std::from_chars(it->second.data(), it->second.data() + it->second.size(), value);
  if (ec != std::errc{} || end != it->second.data() + it->second.size() || value < 2 || value > 8) {
    Error e = make_error(ErrorCode::invalid_argument, "'wheels' must be an integer 2..8, got '" + it->second + "'");
    e.field = "wheels";
    return unexpected(e);
  }
  return value;
}

// Registered for one test, removed after it (the list is the process's).
class RigKind : public ::testing::Test {
 protected:
  RigKind() {
    PlatformKind kind;
    kind.name = "test_rig";
    kind.written = "rig";
    kind.options = {"wheels"};
    kind.check = [](const PlatformSettings& settings, const SimulationSettings&) -> Expected<void> {
      if (auto w = wheels(settings); !w) return unexpected(w.error());
      return {};
    };
    kind.make = [this](const PlatformSettings& settings, const SimulationSettings& simulation,
                       PlatformEnvironment environment) -> Expected<std::unique_ptr<Platform>> {
      made_wheels = *wheels(settings);  // checked before make
      if (const auto* section = settings.sections.find<RigSettings>()) made_label = section->label;
      return std::unique_ptr<Platform>(std::make_unique<RigPlatform>(calls, std::move(simulation), std::move(environment)));
    };
    added = add_platform_kind(std::move(kind));
  }
  ~RigKind() override { remove_platform_kind("test_rig"); }

  Expected<void> added;
  RigCalls calls;
  int made_wheels = 0;
  std::string made_label;
};

TEST_F(RigKind, IsListedBesideTheBuiltInOnesAndItsNamesAreItsOwn) {
  ASSERT_TRUE(added) << added.error().message();
  ASSERT_NE(find_platform_kind("test_rig"), nullptr);
  EXPECT_EQ(platform_kind_written("rig"), find_platform_kind("test_rig"));
  EXPECT_EQ(platform_kind_with_option("wheels"), find_platform_kind("test_rig"));

  const auto refused = [](PlatformKind kind) {
    const auto r = add_platform_kind(std::move(kind));
    EXPECT_FALSE(r);
    return r ? std::string() : r.error().message();
  };
  const auto make = [](const PlatformSettings&, const SimulationSettings&,
                       PlatformEnvironment) -> Expected<std::unique_ptr<Platform>> { return std::unique_ptr<Platform>(); };
  EXPECT_EQ(refused(PlatformKind{"test_rig", {}, {}, {}, make}), "platform kind 'test_rig' already exists");
  EXPECT_EQ(refused(PlatformKind{"other", "sim", {}, {}, make}),
            "platform kind 'other' is written 'sim', as platform kind 'clearpath_sim' is");
  EXPECT_EQ(refused(PlatformKind{"other", {}, {"udp"}, {}, make}),
            "platform kind 'other' takes option 'udp', which names platform kind 'clearpath'");
  EXPECT_EQ(refused(PlatformKind{"other", {}, {}, {}, {}}), "platform kind 'other' cannot make platforms");
  EXPECT_EQ(refused(PlatformKind{"", {}, {}, {}, make}), "a platform kind needs a name");
  // A kind that makes nothing is refused when a host asks for it.
  ASSERT_TRUE(add_platform_kind(PlatformKind{"empty_rig", {}, {}, {}, make}));
  PlatformSettings empty;
  empty.kind = "empty_rig";
  rt::VirtualTime time;
  const auto none = make_platform(empty, {}, PlatformEnvironment{time, time, nullptr, {}});
  EXPECT_TRUE(remove_platform_kind("empty_rig"));
  ASSERT_FALSE(none);
  EXPECT_EQ(none.error().message(), "platform kind 'empty_rig' made no platform");
  EXPECT_FALSE(remove_platform_kind("empty_rig"));
}

// A node on a platform the host has never heard of: the driver's hardware
// comes from it, its emergency hooks get the driver's latch, the local clear
// reaches it, and the host's stop runs its stop path.
TEST_F(RigKind, ANodeIsBuiltOnIt) {
  ASSERT_TRUE(added) << added.error().message();
  rt::VirtualTime time;
  testing::MemoryNetwork network(time, time);
  HostConfig config;
  config.platform.kind = "test_rig";
  config.platform.options = {{"wheels", "6"}};
  config.platform.sections.set(RigSettings{"six-wheeler"});
  config.components = {ComponentSpec{"node_manager", 1, 1, 0, "", {}, 0, {}},
                       ComponentSpec{"primitive_driver", 33, 1, 0, "", {}, 0, {}}};
  auto host = NodeHost::attach(config, network.attach(1, 1), time, time);
  ASSERT_TRUE(host) << host.error().message();
  EXPECT_EQ(made_wheels, 6);
  EXPECT_EQ(made_label, "six-wheeler");
  EXPECT_NE(std::find(calls.provided.begin(), calls.provided.end(), components::Drive::kInterface),
            calls.provided.end());
  EXPECT_NE((*host)->backends().find<components::Drive>(), nullptr);
  rt::Component& driver = *(*host)->node().find(Address{1, 1, 33, 1});
  EXPECT_TRUE(testing::run_until(time, [&] { return driver.state() == rt::PrimaryStatus::ready; }, 5s));
  EXPECT_TRUE(calls.followed);
  ASSERT_NE(calls.driver, nullptr);
  EXPECT_EQ(calls.driver, (*host)->emergency_latch("vehicle"));
  (*host)->clear_emergency_holds_locally("test");
  EXPECT_EQ(calls.reclaims, 1);
  (*host)->stop("test");
  EXPECT_GE(calls.stops, 1);
}

TEST_F(RigKind, SettingsItsCheckRefusesBuildNoNode) {
  ASSERT_TRUE(added) << added.error().message();
  rt::VirtualTime time;
  testing::MemoryNetwork network(time, time);
  HostConfig config;
  config.platform.kind = "test_rig";
  config.platform.options = {{"wheels", "1"}};
  auto host = NodeHost::attach(config, network.attach(1, 1), time, time);
  ASSERT_FALSE(host);
  EXPECT_EQ(host.error().message(), "'wheels' must be an integer 2..8, got '1'");
  EXPECT_EQ(made_wheels, 0);  // never made
}

}  // namespace
}  // namespace jaus::host
