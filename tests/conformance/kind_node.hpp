// A node of ours with one component of each kind the per-kind cases test,
// a node host attached to a link of a memory network under virtual time
// (subsystem 1, node 1): primitive driver, global pose sensor (with local
// pose), local pose sensor, velocity state sensor, visual sensor and
// primitive manipulator, on the components' own simulated vehicle, two
// cameras and a three-joint arm.
#pragma once

#include <memory>
#include <stdexcept>

#include "jaus/base/virtual_time.hpp"
#include "jaus/host/node_host.hpp"
#include "jaus/testing/memory_link.hpp"

namespace jaus::conform::test {

inline const Address kKindManager{1, 1, 1, 1};
inline const Address kDriver{1, 1, 33, 1};
inline const Address kVisualSensor{1, 1, 37, 1};
inline const Address kGlobalPoseSensor{1, 1, 38, 1};
inline const Address kLocalPoseSensor{1, 1, 41, 1};
inline const Address kVelocityStateSensor{1, 1, 42, 1};
inline const Address kManipulator{1, 1, 49, 1};

class KindNode {
 public:
  KindNode(rt::VirtualTime& time, testing::MemoryNetwork& network) : link_(network.attach(1, 1)) {
    host::HostConfig config;
    config.node.subsystem = 1;
    config.node.node = 1;
    config.settings.identity.subsystem_name = "kinds";
    config.settings.identity.node_name = "kinds";
    auto spec = [](const char* kind, const Address& at, std::map<std::string, std::string> options = {}) {
      return host::ComponentSpec{kind, at.component, 1, 0, kind, std::move(options), 0, {}};
    };
    config.components = {spec("node_manager", kKindManager),
                         spec("primitive_driver", kDriver),
                         spec("global_pose_sensor", kGlobalPoseSensor, {{"local_pose", "true"}}),
                         spec("local_pose_sensor", kLocalPoseSensor),
                         spec("velocity_state_sensor", kVelocityStateSensor),
                         spec("visual_sensor", kVisualSensor),
                         spec("primitive_manipulator", kManipulator)};
    // Two cameras (the selection cases need two) and a three-joint arm,
    // each with the configuration's defaults otherwise.
    components::CameraConfig second;
    second.id = 2;
    config.cameras.cameras = {components::CameraConfig{}, second};
    config.arm.joints.assign(3, components::JointConfig{});
    auto host = host::NodeHost::attach(config, link_, time, time);
    if (!host) throw std::runtime_error(host.error().message());
    host_ = std::move(*host);
    link_.deliver_to(host_->node());
  }
  ~KindNode() {
    host_.reset();  // stopped while its link still carries the last messages
    link_.on_receive({});
    link_.set_connected(false);
  }
  KindNode(const KindNode&) = delete;
  KindNode& operator=(const KindNode&) = delete;
  host::NodeHost& host() { return *host_; }

 private:
  testing::MemoryLink& link_;
  std::unique_ptr<host::NodeHost> host_;
};

}  // namespace jaus::conform::test
