// A node of hand-made components (broken on purpose, scripted) on a link of
// a jaus::testing memory network under virtual time, for tests that need
// components no configuration makes: emplace<C>(name, component, args...)
// adds one at subsystem.node.component.1.
#pragma once

#include <memory>
#include <string>
#include <utility>

#include "jaus/base/virtual_time.hpp"
#include "jaus/node/node.hpp"
#include "jaus/runtime/component.hpp"
#include "jaus/testing/memory_link.hpp"

namespace jaus::test_support {

class MemoryNode {
 public:
  MemoryNode(rt::VirtualTime& time, testing::MemoryNetwork& network, node::NodeConfig config)
      : link_(network.attach(config.subsystem, config.node)) {
    node_ = std::make_unique<node::Node>(config, time, time, link_);
    link_.deliver_to(*node_);
  }
  ~MemoryNode() {
    node_->shutdown("test over");
    link_.on_receive({});
    link_.set_connected(false);
  }
  MemoryNode(const MemoryNode&) = delete;
  MemoryNode& operator=(const MemoryNode&) = delete;

  // The configuration of component `component` (instance 1) of this node.
  rt::ComponentConfig component_config(std::string name, std::uint8_t component) const {
    rt::ComponentConfig c;
    c.name = std::move(name);
    c.address = Address{node_->config().subsystem, node_->config().node, component, 1};
    return c;
  }
  template <class C, class... Args>
  C& emplace(std::string name, std::uint8_t component, Args&&... args) {
    return add<C>(component_config(std::move(name), component), std::forward<Args>(args)...);
  }
  template <class C, class... Args>
  C& add(rt::ComponentConfig config, Args&&... args) {
    return node_->add_as(std::make_unique<C>(std::move(config), node_->environment(), std::forward<Args>(args)...));
  }

  node::Node& node() { return *node_; }
  testing::MemoryLink& link() { return link_; }

 private:
  testing::MemoryLink& link_;
  std::unique_ptr<node::Node> node_;
};

}  // namespace jaus::test_support
