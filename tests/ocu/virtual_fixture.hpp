// jausctl's OCU and the target node of target_node.hpp (node manager
// 1.1.1.1, communicator 1.1.35.1, pose sensor 1.1.38.1) in one process on a
// jaus::testing memory network under virtual time: no socket, no real clock.
// A command that waits advances the virtual clock, so a timeout of 30 s
// takes no real time and every time a test reads is exact. The same
// interface as OcuTest (ocu_fixture.hpp): a test moves over by naming this
// fixture.
#pragma once

#include <functional>
#include <memory>
#include <sstream>
#include <stdexcept>

#include "jaus/components/node_manager.hpp"
#include "jaus/ocu/session.hpp"
#include "jaus/testing/memory_link.hpp"
#include "jaus/testing/virtual_time.hpp"
#include "ocu/ocu_commands.hpp"
#include "command_output.hpp"
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

class VirtualOcuTest : public ::testing::Test, public CommandOutput {
 protected:
  void SetUp() override { start_target({}); }

  void start_target(const TargetOptions& options) {
    target.reset();
    target = std::make_unique<VirtualTarget>(time, network, options);
  }

  std::unique_ptr<ocu::OcuSession> open_ocu(jaus::Address self = ocu::kDefaultOcuAddress, std::uint8_t authority = 0) {
    ocu::SessionOptions options;
    options.self = self;
    options.authority = authority;
    auto& link = network.attach(self.subsystem, self.node);
    auto session = ocu::OcuSession::attach(
        options, ocu::SessionEnvironment{&time, &time, &link,
                                         [&link](std::function<void(std::span<const std::uint8_t>)> receiver) {
                                           link.on_receive(std::move(receiver));
                                         },
                                         jaus::testing::stepper(time)});
    if (!session) {
      ADD_FAILURE() << session.error().message();
      return nullptr;
    }
    return std::move(*session);
  }

  // Lets virtual time pass until `done` or 10 s of it.
  bool run_until(const std::function<bool()>& done) { return jaus::testing::run_until(time, done, 10s); }

  // Runs `action` once `condition` holds, looked at every 10 ms of virtual
  // time while a command waits.
  void once(std::function<bool()> condition, std::function<void()> action) {
    time.call_at(time.now() + 10ms, [this, condition = std::move(condition), action = std::move(action)]() mutable {
      if (condition()) return action();
      once(std::move(condition), std::move(action));
    });
  }


  jaus::rt::VirtualTime time;
  jaus::testing::MemoryNetwork network{time, time};
  std::unique_ptr<VirtualTarget> target;
};

}  // namespace jausctl::test
