// The target node of target_node.hpp (node manager 1.1.1.1, communicator
// 1.1.35.1, pose sensor 1.1.38.1; on another subsystem with
// TargetOptions::subsystem) on a link of a jaus::testing memory network
// under virtual time: no socket, no real clock. No primitive driver and no
// static peers (the network routes by address).
#pragma once

#include <memory>
#include <stdexcept>

#include "jaus/components/communicator.hpp"
#include "jaus/components/node_manager.hpp"
#include "jaus/testing/memory_link.hpp"
#include "target_node.hpp"

namespace jausctl::test {

class VirtualTarget {
 public:
  VirtualTarget(jaus::rt::VirtualTime& time, jaus::testing::MemoryNetwork& network, const TargetOptions& options)
      : link_(network.attach(options.subsystem, 1)) {
    if (options.primitive_driver || !options.peers.empty())
      throw std::invalid_argument("a virtual target has no primitive driver and no static peers");
    jaus::node::NodeConfig config;
    config.subsystem = options.subsystem;
    config.node = 1;
    config.liveness.node_timeout = options.subsystem_timeout;
    config.liveness.subsystem_timeout = options.subsystem_timeout;
    node_ = std::make_unique<jaus::node::Node>(config, time, time, link_);
    link_.deliver_to(*node_);
    const auto component = [&](const jaus::Address& a, const char* name) {
      jaus::rt::ComponentConfig c;
      c.name = name;
      c.address = jaus::Address{options.subsystem, 1, a.component, 1};
      c.controller_timeout = options.controller_timeout;
      c.reject_refused_requests = options.reject_refused;
      return c;
    };
    jaus::components::NodeManagerConfig identity;
    identity.subsystem_name = "test-vehicle";
    identity.node_name = "test-node";
    node_->add(std::make_unique<jaus::components::NodeManager>(component(kTargetManager, "node manager"),
                                                               node_->environment(), *node_, identity));
    communicator_ = &node_->add_as(std::make_unique<jaus::components::Communicator>(
        component(kCommunicator, "communicator"), node_->environment()));
    pose_ = &node_->add_as(std::make_unique<PoseSensor>(component(kPoseSensor, "pose sensor"), node_->environment()));
  }
  ~VirtualTarget() {
    node_->shutdown("test over");
    link_.on_receive({});
    link_.set_connected(false);  // a target started in its place gets a link of its own
  }
  VirtualTarget(const VirtualTarget&) = delete;
  VirtualTarget& operator=(const VirtualTarget&) = delete;

  // The network goes quiet (cable pulled, process frozen): nothing in or out.
  void go_silent() { link_.set_connected(false); }
  jaus::node::Node& node() { return *node_; }
  jaus::testing::MemoryLink& link() { return link_; }
  jaus::components::Communicator& communicator() { return *communicator_; }
  PoseSensor& pose_sensor() { return *pose_; }

 private:
  jaus::testing::MemoryLink& link_;
  std::unique_ptr<jaus::node::Node> node_;
  jaus::components::Communicator* communicator_ = nullptr;
  PoseSensor* pose_ = nullptr;
};

}  // namespace jausctl::test
