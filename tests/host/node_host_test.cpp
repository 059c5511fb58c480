// The node host: every registered component kind can be built, a host opens
// with its configured components and extra ones, a busy address is one error,
// and stop() shuts the components down before the link closes.
#include <gtest/gtest.h>

#include <boost/asio/io_context.hpp>

#include "jaus/base/virtual_time.hpp"
#include "jaus/host/node_host.hpp"

namespace jaus::host {
namespace {

constexpr std::uint32_t kLoopback = 0x7F000001;

HostConfig loopback_config() {
  HostConfig config;
  config.link.bind = transport::Ipv4Endpoint{kLoopback, 0};
  for (const auto& kind : component_kinds())
    config.components.push_back(ComponentSpec{std::string(kind.name), kind.default_id, 1, 0, "", {}, 0});
  return config;
}

TEST(ComponentKinds, EveryRegisteredKindIsBuiltWithItsIdAndName) {
  rt::VirtualTime time;
  struct NullLink : node::Link {
    void transmit(const Header&, std::span<const std::uint8_t>) override {}
  } link;
  node::Node node(node::NodeConfig{}, time, time, link);
  ComponentSettings settings;
  ASSERT_FALSE(component_kinds().empty());
  for (const auto& kind : component_kinds()) {
    auto made = make_component(ComponentSpec{std::string(kind.name), kind.default_id, 2, 7, "", {}, 0}, settings, node);
    ASSERT_TRUE(made) << kind.name << ": " << made.error().message();
    EXPECT_EQ((*made)->address(), (Address{1, 1, kind.default_id, 2}));
    EXPECT_EQ((*made)->name(), kind.name);  // no name given: the kind's
    EXPECT_EQ((*made)->control().own_authority(), 7);
  }
  auto unknown = make_component(ComponentSpec{"warp_drive", 99, 1, 0, "", {}, 0}, settings, node);
  ASSERT_FALSE(unknown);
  EXPECT_EQ(unknown.error().code, ErrorCode::invalid_argument);
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
  config.components.push_back(ComponentSpec{"warp_drive", 99, 1, 0, "", {}, 0});
  auto host = NodeHost::open(config, io);
  ASSERT_FALSE(host);
  EXPECT_EQ(host.error().message(), "component kind 'warp_drive' cannot be hosted by this build");
}

}  // namespace
}  // namespace jaus::host
