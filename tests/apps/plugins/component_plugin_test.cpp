// Component plugins in process: every way a plugin is refused, as an error
// naming the file (never a crash), and a plugin's kind configured, checked
// and hosted on a node under virtual time, answering a query.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <optional>
#include <string>

#include "jaus/base/version.hpp"
#include "jaus/host/component_kinds.hpp"
#include "jaus/host/component_options.hpp"
#include "jaus/host/component_plugins.hpp"
#include "jaus/host/jss_translators.hpp"
#include "jaus/jss/contents.hpp"
#include "jaus/jss/judp.hpp"
#include "jaus/jss/messages/mobility.hpp"
#include "jaus/jss_face/face.hpp"
#include "jaus/messages/platform_messages.hpp"
#include "jaus/testing/memory_link.hpp"
#include "jaus/testing/virtual_time.hpp"
#include "host_config.hpp"
#include "jaus/host/node_host.hpp"
#include "jausd_config.hpp"

namespace {

using jaus::host::load_component_plugin;
namespace fs = std::filesystem;

// The error loading `path` gives (a failure when it loads).
std::string refusal(const std::string& path) {
  const auto loaded = load_component_plugin(path);
  if (loaded) {
    ADD_FAILURE() << path << " loaded";
    return {};
  }
  EXPECT_EQ(loaded.error().code, jaus::ErrorCode::invalid_argument);
  return loaded.error().message();
}

TEST(ComponentPlugins, APluginOfAnotherAbiIsRefusedOnItsFirstField) {
  EXPECT_EQ(refusal(WRONG_ABI_PLUGIN), std::string(WRONG_ABI_PLUGIN) +
                                           ": plugin ABI 2, this jausd loads ABI 1: rebuild the plugin against this jaus");
}

TEST(ComponentPlugins, APluginOfAnotherJausVersionIsRefused) {
  EXPECT_EQ(refusal(WRONG_VERSION_PLUGIN), std::string(WRONG_VERSION_PLUGIN) +
                                               ": plugin 'old_version' was built against jaus 0.0.1, this jausd is " +
                                               std::string(jaus::kVersion) + ": rebuild it");
}

TEST(ComponentPlugins, ALibraryWithoutTheEntryPointIsNotAPlugin) {
  EXPECT_EQ(refusal(NO_ENTRY_PLUGIN),
            std::string(NO_ENTRY_PLUGIN) + ": not a jaus component plugin: no jaus_component_plugin symbol (write "
                                           "JAUS_COMPONENT_PLUGIN, jaus/runtime/component_plugin.hpp), nor a platform "
                                           "plugin: no jaus_platform_plugin symbol (JAUS_PLATFORM_PLUGIN, "
                                           "jaus/host/platform_plugin.hpp), nor a JSS plugin: no jaus_jss_plugin symbol "
                                           "(JAUS_JSS_PLUGIN, jaus/host/jss_plugin.hpp)");
}

TEST(ComponentPlugins, AnUndefinedSymbolIsRefusedWhenOpened) {
  const std::string error = refusal(UNDEFINED_SYMBOL_PLUGIN);
  EXPECT_EQ(error.rfind(std::string(UNDEFINED_SYMBOL_PLUGIN) + ": cannot load the plugin: ", 0), 0u) << error;
  EXPECT_NE(error.find("undefined symbol"), std::string::npos) << error;
  EXPECT_NE(error.find("jaus_test_defined_nowhere"), std::string::npos) << error;
}

TEST(ComponentPlugins, AKindNameAlreadyTakenIsRefusedAndNothingIsAdded) {
  const auto kinds = jaus::host::component_kinds().size();
  EXPECT_EQ(refusal(TAKEN_KIND_PLUGIN),
            std::string(TAKEN_KIND_PLUGIN) +
                ": plugin 'taken_kind' brings kind 'primitive_driver', a name already taken by a built-in kind");
  EXPECT_EQ(jaus::host::component_kinds().size(), kinds);
}

TEST(ComponentPlugins, AKindsFunctionThatThrowsIsAnError) {
  EXPECT_EQ(refusal(THROWING_KINDS_PLUGIN),
            std::string(THROWING_KINDS_PLUGIN) +
                ": plugin 'throwing_kinds' listing its kinds threw: no odometer board found");
}

TEST(ComponentPlugins, AMissingFileIsAnErrorNamingIt) {
  const std::string missing = (fs::path(TEST_ODOMETER_PLUGIN).parent_path() / "libnowhere.so").string();
  const std::string error = refusal(missing);
  EXPECT_EQ(error.rfind(missing + ": cannot load the plugin: ", 0), 0u) << error;
}

// The operator's side of the query.
class Operator final : public jaus::rt::Component {
 public:
  Operator(jaus::rt::ComponentConfig config, jaus::rt::Environment env) : Component(std::move(config), std::move(env)) {
    handle<jaus::msg::ReportVelocityState>(
        Access::anyone, false, [this](const jaus::Header&, const jaus::msg::ReportVelocityState& r) { report = r; });
  }
  void ask(const jaus::Address& to) { send(to, jaus::msg::QueryVelocityState{{0x0001}}); }
  std::optional<jaus::msg::ReportVelocityState> report;
};

TEST(ComponentPlugins, APluginKindIsConfiguredCheckedAndHosted) {
  const auto loaded = load_component_plugin(TEST_ODOMETER_PLUGIN);
  ASSERT_TRUE(loaded) << loaded.error().message();
  EXPECT_EQ(loaded->name, "test_odometer");
  EXPECT_EQ(loaded->kinds, std::vector<std::string>{"plugin_odometer"});
  // Loading the same file again adds nothing and is no error.
  const auto again = load_component_plugin(TEST_ODOMETER_PLUGIN);
  ASSERT_TRUE(again) << again.error().message();
  EXPECT_EQ(again->kinds, loaded->kinds);

  // In a configuration: listed relative to its folder, options checked with the option's line.
  const fs::path folder = fs::path(TEST_ODOMETER_PLUGIN).parent_path();
  const std::string head = "plugins: [libtest_odometer.so]\ncomponents:\n  - kind: node_manager\n"
                           "  - kind: plugin_odometer\n    options:\n";
  const auto bad = jausd::load_config_string(head + "      speed_mps: 11\n", "test.yaml", folder);
  ASSERT_FALSE(bad);
  EXPECT_EQ(bad.error().message(), "test.yaml:6: plugin_odometer option 'speed_mps' must be a number 0..10, got '11'");
  const auto config = jausd::load_config_string(head + "      speed_mps: 2.5\n", "test.yaml", folder);
  ASSERT_TRUE(config) << config.error().message();
  ASSERT_EQ(config->plugins.size(), 1u);
  EXPECT_EQ(jausd::plugin_summaries(*config),
            std::vector<std::string>{"plugin 'test_odometer' (" + std::string(TEST_ODOMETER_PLUGIN) +
                                     "): component kinds plugin_odometer; JSS services plugin odometer"});
  // Text from memory names no folder: its plugin list is refused, nothing loaded.
  const auto from_memory = jausd::load_config_string(head + "      speed_mps: 2.5\n", "memory.yaml");
  ASSERT_FALSE(from_memory);
  EXPECT_EQ(from_memory.error().message(),
            "memory.yaml:1: 'plugins' are loaded only from a configuration file (jausd --config FILE)");

  // Hosted: made as jausd makes it, on node 1.1, queried from node 1.2.
  jaus::rt::VirtualTime time;
  jaus::testing::MemoryNetwork network(time, time);
  auto& robot_link = network.attach(1, 1);
  auto& station_link = network.attach(1, 2);
  jaus::node::NodeConfig robot_config, station_config;
  station_config.node = 2;
  jaus::node::Node robot(robot_config, time, time, robot_link);
  jaus::node::Node station(station_config, time, time, station_link);
  robot_link.deliver_to(robot);
  station_link.deliver_to(station);
  const auto& spec = config->components.at(1);
  auto made = jaus::host::make_component(spec, jaus::host::ComponentSettings{}, robot);
  ASSERT_TRUE(made) << made.error().message();
  robot.add(std::move(*made));
  jaus::rt::ComponentConfig operator_config;
  operator_config.name = "operator";
  operator_config.address = {1, 2, 40, 1};
  auto& op = station.add_as(std::make_unique<Operator>(operator_config, station.environment()));
  op.ask({1, 1, 150, 1});
  ASSERT_TRUE(jaus::testing::run_until(time, [&] { return op.report.has_value(); }, std::chrono::seconds(1)));
  ASSERT_TRUE(op.report->velocity_x_mps);
  EXPECT_NEAR(*op.report->velocity_x_mps, 2.5, 0.01);
}

TEST(JssPlugins, APluginKindsJssServiceComesWithItAndAnswersAJssClient) {
  const auto loaded = load_component_plugin(TEST_ODOMETER_PLUGIN);
  ASSERT_TRUE(loaded) << loaded.error().message();
  EXPECT_EQ(loaded->jss_services, std::vector<std::string>{"plugin odometer"});
  // The face is handed the built-in kinds' services, then the plugin's.
  const auto services = jaus::host::jss_translators();
  EXPECT_EQ(services.size(), jaus::host::builtin_jss_translators().size() + 1);
  EXPECT_EQ(jaus::host::plugin_jss_translators().size(), 1u);

  const fs::path folder = fs::path(TEST_ODOMETER_PLUGIN).parent_path();
  const auto config = jausd::load_config_string(
      "plugins: [libtest_odometer.so]\ncomponents:\n  - kind: node_manager\n  - kind: plugin_odometer\n    options:\n"
      "      speed_mps: 3.5\n",
      "test.yaml", folder);
  ASSERT_TRUE(config) << config.error().message();

  // The kind on node 1.1 behind a JSS face made as a node host makes it.
  jaus::rt::VirtualTime time;
  jaus::testing::MemoryNetwork network(time, time);
  auto& link = network.attach(1, 1);
  jaus::jss_face::FaceLink face_link(link);
  jaus::node::Node robot(jaus::node::NodeConfig{}, time, time, face_link);
  link.deliver_to(robot);
  auto made = jaus::host::make_component(config->components.at(1), jaus::host::ComponentSettings{}, robot);
  ASSERT_TRUE(made) << made.error().message();
  robot.add(std::move(*made));
  std::vector<std::vector<std::uint8_t>> sent;
  jaus::jss_face::JssFace face({}, services, robot, [&](const jaus::jss::JssId&, std::span<const std::uint8_t> d) {
    sent.emplace_back(d.begin(), d.end());
  });
  face_link.attach(&face);

  // A JSS client asks JSS component 1.1.150 (the plugin kind's RA ID) for its velocity.
  jaus::jss::JudpHeader query;
  query.source = jaus::jss::JssId{42, 1, 1};
  query.destination = jaus::jss::JssId{1, 1, 150};
  const auto contents = jaus::jss::encode_contents(jaus::jss::msg::QueryVelocityState{{0x0001}});
  face.receive(jaus::jss::make_judp_datagram(query, contents), jaus::rt::SenderStanding::trusted);
  std::optional<jaus::jss::msg::ReportVelocityState> report;
  const auto heard = [&] {
    for (const auto& datagram : sent) {
      const auto packets = jaus::jss::decode_judp_datagram(datagram);
      if (!packets) continue;
      for (const auto& packet : *packets)
        if (jaus::jss::message_id_of(packet.contents) == jaus::jss::msg::ReportVelocityState::code)
          if (auto r = jaus::jss::decode_contents<jaus::jss::msg::ReportVelocityState>(packet.contents)) report = *r;
    }
    return report.has_value();
  };
  ASSERT_TRUE(jaus::testing::run_until(time, heard, std::chrono::seconds(1)));
  ASSERT_TRUE(report->velocity_x_mps);
  EXPECT_NEAR(*report->velocity_x_mps, 3.5, 0.01);
  face_link.attach(nullptr);
}

TEST(PlatformPlugins, APlatformPluginOfAnotherAbiIsRefusedOnItsFirstField) {
  EXPECT_NE(refusal(WRONG_ABI_PLATFORM_PLUGIN).find("platform plugin ABI 2, this jausd loads ABI 1"), std::string::npos);
  EXPECT_EQ(jaus::host::find_platform_kind("plugin_rig"), nullptr);
}

// A platform kind from a plugin: listed, named in a configuration by its
// option (checked with the option's line), and a node built on it whose
// driver's hardware it provides and whose stop path it runs.
TEST(PlatformPlugins, APluginPlatformIsConfiguredCheckedAndCarriesANode) {
  const auto loaded = load_component_plugin(TEST_RIG_PLATFORM_PLUGIN);
  ASSERT_TRUE(loaded) << loaded.error().message();
  EXPECT_EQ(loaded->name, "test_rig_platform");
  EXPECT_TRUE(loaded->kinds.empty());
  EXPECT_EQ(loaded->platform_kinds, std::vector<std::string>{"plugin_rig"});
  ASSERT_NE(jaus::host::platform_kind_with_option("plugin_wheels"), nullptr);

  const fs::path folder = fs::path(TEST_RIG_PLATFORM_PLUGIN).parent_path();
  const std::string head = "plugins: [libtest_rig_platform.so]\n";
  const std::string components = "components:\n  - kind: node_manager\n  - kind: primitive_driver\n";
  const auto bad = jausd::load_config_string(head + "platform:\n  plugin_wheels: 9\n" + components, "test.yaml", folder);
  ASSERT_FALSE(bad);
  EXPECT_EQ(bad.error().message(), "test.yaml:3: 'plugin_wheels' must be an integer 2..8, got '9'");
  // An exception from its check is an error naming the plugin and the kind, at the platform's line.
  const auto thrown = jausd::load_config_string(head + "platform: {plugin_wheels: explode}\n" + components, "test.yaml", folder);
  ASSERT_FALSE(thrown);
  EXPECT_EQ(thrown.error().message(), "test.yaml:2: plugin 'test_rig_platform' (" + std::string(TEST_RIG_PLATFORM_PLUGIN) +
                                          ") platform kind 'plugin_rig' checking its settings threw: wheels exploded");
  EXPECT_TRUE(jausd::load_config_string(head + "platform: plugin_rig\n" + components, "test.yaml", folder));
  const auto config = jausd::load_config_string(head + "platform: {plugin_wheels: 6}\n" + components, "test.yaml", folder);
  ASSERT_TRUE(config) << config.error().message();
  EXPECT_EQ(config->platform.kind, "plugin_rig");
  EXPECT_EQ(jausd::plugin_summaries(*config),
            std::vector<std::string>{"plugin 'test_rig_platform' (" + std::string(TEST_RIG_PLATFORM_PLUGIN) +
                                     "): platform kinds plugin_rig"});

  jaus::rt::VirtualTime time;
  jaus::testing::MemoryNetwork network(time, time);
  std::vector<std::string> lines;
  auto host = jaus::host::NodeHost::attach(jausd::host_config(*config), network.attach(1, 1), time, time,
                                           [&](jaus::rt::LogLevel, const std::string& l) { lines.push_back(l); });
  ASSERT_TRUE(host) << host.error().message();
  const auto logged = [&](const std::string& text) {
    return std::find(lines.begin(), lines.end(), text) != lines.end();
  };
  EXPECT_TRUE(logged("plugin rig: 6 wheels"));
  EXPECT_NE((*host)->backends().find<jaus::components::Drive>(), nullptr);  // the driver's, from the plugin's platform
  jaus::rt::Component& driver = *(*host)->node().find(jaus::Address{1, 1, 33, 1});
  EXPECT_TRUE(jaus::testing::run_until(time, [&] { return driver.state() == jaus::rt::PrimaryStatus::ready; },
                                       std::chrono::seconds(5)));
  (*host)->stop("test");
  EXPECT_TRUE(logged("plugin rig: stopped"));
}

TEST(ComponentPlugins, AnExceptionFromAKindsCheckOrMakeIsAnErrorNamingThePluginAndKind) {
  const auto loaded = load_component_plugin(THROWING_MAKER_PLUGIN);
  ASSERT_TRUE(loaded) << loaded.error().message();
  const std::string who = "plugin 'throwing_maker' (" + std::string(THROWING_MAKER_PLUGIN) + ") kind 'throwing_maker'";
  jaus::host::ComponentSpec spec{"throwing_maker", 200, 1, 0, "", {{"explode", "yes"}}, 7, {}};
  const auto checked = jaus::host::check_component_options(spec);
  ASSERT_FALSE(checked);
  EXPECT_EQ(checked.error().what, who + " checking its options threw: options exploded");
  EXPECT_EQ(checked.error().line, 7);

  jaus::rt::VirtualTime time;
  jaus::testing::MemoryNetwork network(time, time);
  auto& link = network.attach(1, 1);
  jaus::node::Node robot(jaus::node::NodeConfig{}, time, time, link);
  spec.options.clear();
  const auto made = jaus::host::make_component(spec, jaus::host::ComponentSettings{}, robot);
  ASSERT_FALSE(made);
  EXPECT_EQ(made.error().message(), who + " making a component threw: device busy");
}

}  // namespace
