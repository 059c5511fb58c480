// A node of ours with one component of each kind the per-kind cases test,
// in process on 127.0.0.1 and an ephemeral port (subsystem 1): primitive
// driver, global pose sensor (with local pose), velocity state sensor,
// visual sensor and primitive manipulator, on the components' own simulated
// vehicle, two cameras and a three-joint arm.
#pragma once

#include <utility>  // Boost 1.74's Asio headers need it first

#include <boost/asio/io_context.hpp>
#include <memory>
#include <stdexcept>

#include "jaus/host/node_host.hpp"

namespace jaus::conform::test {

inline const Address kKindManager{1, 1, 1, 1};
inline const Address kDriver{1, 1, 33, 1};
inline const Address kVisualSensor{1, 1, 37, 1};
inline const Address kGlobalPoseSensor{1, 1, 38, 1};
inline const Address kVelocityStateSensor{1, 1, 42, 1};
inline const Address kManipulator{1, 1, 49, 1};

class KindNode {
 public:
  explicit KindNode(boost::asio::io_context& io) {
    host::HostConfig config;
    config.node.subsystem = 1;
    config.node.node = 1;
    config.link.bind = transport::Ipv4Endpoint{0x7F000001, 0};
    config.settings.identity.subsystem_name = "kinds";
    config.settings.identity.node_name = "kinds";
    auto spec = [](const char* kind, const Address& at, std::map<std::string, std::string> options = {}) {
      return host::ComponentSpec{kind, at.component, 1, 0, kind, std::move(options), 0, {}};
    };
    config.components = {spec("node_manager", kKindManager),
                         spec("primitive_driver", kDriver),
                         spec("global_pose_sensor", kGlobalPoseSensor, {{"local_pose", "true"}}),
                         spec("velocity_state_sensor", kVelocityStateSensor),
                         spec("visual_sensor", kVisualSensor),
                         spec("primitive_manipulator", kManipulator)};
    // Two cameras (the selection cases need two) and a three-joint arm,
    // each with the configuration's defaults otherwise.
    components::CameraConfig second;
    second.id = 2;
    config.cameras.cameras = {components::CameraConfig{}, second};
    config.arm.joints.assign(3, components::JointConfig{});
    auto host = host::NodeHost::open(config, io);
    if (!host) throw std::runtime_error(host.error().message());
    host_ = std::move(*host);
  }
  transport::Ipv4Endpoint endpoint() const { return host_->udp_link()->local_endpoint(); }
  host::NodeHost& host() { return *host_; }

 private:
  std::unique_ptr<host::NodeHost> host_;
};

}  // namespace jaus::conform::test
