// A JAUS node for jausctl's OCU to talk to, in-process: node manager 1.1.1.1,
// communicator 1.1.35.1 (controllable) and a pose sensor 1.1.38.1 that
// answers Query Global Pose and provides Report Global Pose on service
// connections, behind a UDP link on 127.0.0.1 and an ephemeral port.
#pragma once

#include <utility>  // Boost 1.74's Asio headers need it first

#include <gtest/gtest.h>

#include <boost/asio/io_context.hpp>
#include <memory>
#include <stdexcept>

#include "jaus/messages/all.hpp"
#include "jaus/node/node.hpp"
#include "jaus/components/communicator.hpp"
#include "jaus/components/node_manager.hpp"
#include "jaus/transport/asio_runtime.hpp"
#include "jaus/transport/udp_link.hpp"

namespace jausctl::test {

using namespace std::chrono_literals;

inline constexpr std::uint32_t kLoopback = 0x7F000001;
inline const jaus::Address kTargetManager{1, 1, 1, 1};
inline const jaus::Address kCommunicator{1, 1, 35, 1};
inline const jaus::Address kPoseSensor{1, 1, 38, 1};
inline const jaus::Address kNobody{1, 1, 42, 1};  // no such component on the target

class PoseSensor final : public jaus::rt::Component {
 public:
  static constexpr std::uint32_t kAvailable = 0x7F;  // latitude .. yaw, attitude rms

  PoseSensor(jaus::rt::ComponentConfig config, jaus::rt::Environment env)
      : Component(std::move(config), std::move(env)) {
    handle<jaus::msg::QueryGlobalPose>(Access::anyone, false,
                                       [this](const jaus::Header& h, const jaus::msg::QueryGlobalPose& q) {
                                         auto report = pose();
                                         jaus::wire::mask_presence(report, q.presence_vector);
                                         send(h.source, report);
                                       });
    provide<jaus::msg::ReportGlobalPose>(kAvailable, [] { return pose(); });
  }

  static jaus::msg::ReportGlobalPose pose() {
    jaus::msg::ReportGlobalPose p;
    p.latitude_deg = 45.5;
    p.longitude_deg = -73.6;
    p.elevation_m = 30;
    p.position_rms_m = 1;
    p.roll_rad = 0;
    p.pitch_rad = 0;
    p.yaw_rad = 1;
    return p;
  }
};

struct TargetOptions {
  jaus::rt::Duration controller_timeout = 3s;
  bool reject_refused = false;
  std::uint8_t subsystem = 1;  // the component addresses above are those of subsystem 1
};

class TargetNode {
 public:
  explicit TargetNode(boost::asio::io_context& io, TargetOptions options = {}) : runtime_(io) {
    jaus::transport::UdpLinkOptions link_options;
    link_options.subsystem = options.subsystem;
    link_options.node = 1;
    link_options.bind = jaus::transport::Ipv4Endpoint{kLoopback, 0};
    auto link = jaus::transport::UdpLink::open(io, runtime_, runtime_, link_options);
    if (!link) throw std::runtime_error(link.error());
    link_ = std::move(*link);
    jaus::node::NodeConfig node_config;
    node_config.subsystem = options.subsystem;
    node_ = std::make_unique<jaus::node::Node>(node_config, runtime_, runtime_, *link_);
    link_->on_packet([this](std::span<const std::uint8_t> packet) { node_->receive(packet); });

    jaus::rt::NodeManagerConfig identity;
    identity.subsystem_name = "test-vehicle";
    identity.node_name = "test-node";
    manager_ = static_cast<jaus::rt::NodeManager*>(&node_->add(std::make_unique<jaus::rt::NodeManager>(
        config("node manager", kTargetManager, options), node_->environment(), *node_, identity)));
    node_->set_node_manager(manager_);
    communicator_ = static_cast<jaus::rt::Communicator*>(&node_->add(std::make_unique<jaus::rt::Communicator>(
        config("communicator", kCommunicator, options), node_->environment())));
    pose_ = static_cast<PoseSensor*>(
        &node_->add(std::make_unique<PoseSensor>(config("pose sensor", kPoseSensor, options), node_->environment())));
    link_->start();
  }

  jaus::transport::Ipv4Endpoint endpoint() const { return link_->local_endpoint(); }
  // The network goes quiet (cable pulled, process frozen): nothing in or out.
  void go_silent() { link_->close(); }
  jaus::node::Node& node() { return *node_; }
  jaus::rt::Communicator& communicator() { return *communicator_; }
  PoseSensor& pose_sensor() { return *pose_; }
  jaus::transport::AsioRuntime& runtime() { return runtime_; }

 private:
  static jaus::rt::ComponentConfig config(const char* name, const jaus::Address& address, const TargetOptions& o) {
    jaus::rt::ComponentConfig c;
    c.name = name;
    c.address = jaus::Address{o.subsystem, address.node, address.component, address.instance};
    c.controller_timeout = o.controller_timeout;
    c.reject_refused_requests = o.reject_refused;
    return c;
  }

  jaus::transport::AsioRuntime runtime_;
  std::unique_ptr<jaus::transport::UdpLink> link_;
  std::unique_ptr<jaus::node::Node> node_;
  jaus::rt::NodeManager* manager_ = nullptr;
  jaus::rt::Communicator* communicator_ = nullptr;
  PoseSensor* pose_ = nullptr;
};

}  // namespace jausctl::test
