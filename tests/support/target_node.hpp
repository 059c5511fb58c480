// A JAUS node for an OCU (jausctl's, the conformance runner's) to talk to,
// in-process, on a node host: node manager 1.1.1.1, communicator 1.1.35.1
// (controllable) and a pose sensor 1.1.38.1 that answers Query Global Pose
// and provides Report Global Pose on service connections, behind a UDP link
// on 127.0.0.1 and an ephemeral port; on request a primitive driver 1.1.33.1
// on the host's simulated vehicle. virtual_target.hpp: the same on a memory
// network.
#pragma once

#include <utility>  // Boost 1.74's Asio headers need it first

#include <gtest/gtest.h>

#include <boost/asio/io_context.hpp>
#include <memory>
#include <stdexcept>

#include "jaus/components/communicator.hpp"
#include "jaus/components/primitive_driver.hpp"
#include "jaus/host/node_host.hpp"
#include "jaus/messages/all.hpp"

namespace jausctl::test {

using namespace std::chrono_literals;

inline constexpr std::uint32_t kLoopback = 0x7F000001;
inline const jaus::Address kTargetManager{1, 1, 1, 1};
inline const jaus::Address kCommunicator{1, 1, 35, 1};
inline const jaus::Address kPoseSensor{1, 1, 38, 1};
inline const jaus::Address kDriver{1, 1, 33, 1};  // with TargetOptions::primitive_driver
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
  std::vector<jaus::transport::Ipv4Endpoint> peers = {};  // static peers
  jaus::rt::Duration subsystem_timeout = 5s;              // a silent node or subsystem is lost after this
  bool primitive_driver = false;                          // host kDriver too
};

// The target's node host configuration, on whatever carries it: the link
// settings are the socket target's own.
inline jaus::host::HostConfig target_config(const TargetOptions& options) {
  jaus::host::HostConfig config;
  config.node.subsystem = options.subsystem;
  config.node.liveness.node_timeout = options.subsystem_timeout;
  config.node.liveness.subsystem_timeout = options.subsystem_timeout;
  config.settings.defaults.controller_timeout = options.controller_timeout;
  config.settings.defaults.reject_refused_requests = options.reject_refused;
  config.settings.identity.subsystem_name = "test-vehicle";
  config.settings.identity.node_name = "test-node";
  config.components = {jaus::host::ComponentSpec{"node_manager", kTargetManager.component, 1, 0, "node manager", {}, 0, {}},
                       jaus::host::ComponentSpec{"communicator", kCommunicator.component, 1, 0, "communicator", {}, 0, {}}};
  if (options.primitive_driver)
    config.components.push_back(
        jaus::host::ComponentSpec{"primitive_driver", kDriver.component, 1, 0, "primitive driver", {}, 0, {}});
  return config;
}

// What the tests read and drive in a target's host: the communicator, the
// pose sensor (added to the host here) and the primitive driver, if any.
class TargetComponents {
 public:
  TargetComponents(jaus::host::NodeHost& host, const TargetOptions& options) {
    communicator_ = dynamic_cast<jaus::components::Communicator*>(
        host.node().find(jaus::Address{options.subsystem, 1, kCommunicator.component, 1}));
    if (!communicator_) throw std::runtime_error("the target hosts no communicator");
    pose_ = &host.emplace<PoseSensor>(host.component_config("pose sensor", kPoseSensor.component));
    if (options.primitive_driver) {
      driver_ = dynamic_cast<jaus::components::PrimitiveDriver*>(
          host.node().find(jaus::Address{options.subsystem, 1, kDriver.component, 1}));
      if (!driver_) throw std::runtime_error("the target hosts no primitive driver");
    }
  }

  jaus::components::Communicator& communicator() { return *communicator_; }
  PoseSensor& pose_sensor() { return *pose_; }
  jaus::components::PrimitiveDriver& driver() { return *driver_; }
  // Set Wrench Efforts that reached the driver: applied, or refused (outside
  // Ready, or not from the controller) when it is the only command sent to it.
  std::uint64_t efforts_arrived() const {
    const auto& refused = driver_->counters();
    return driver_->driver_counters().efforts_applied + refused.refused_wrong_state + refused.refused_not_controller;
  }

 private:
  jaus::components::Communicator* communicator_ = nullptr;
  PoseSensor* pose_ = nullptr;
  jaus::components::PrimitiveDriver* driver_ = nullptr;
};

// The host, made before the components the tests reach in it.
struct TargetHost {
  std::unique_ptr<jaus::host::NodeHost> host;
};

class TargetNode : private TargetHost, public TargetComponents {
 public:
  explicit TargetNode(boost::asio::io_context& io, TargetOptions options = {})
      : TargetHost{open_host(io, options)}, TargetComponents(*host, options) {}

  jaus::transport::Ipv4Endpoint endpoint() const { return host->udp_link()->local_endpoint(); }
  // The network goes quiet (cable pulled, process frozen): nothing in or out.
  void go_silent() { host->udp_link()->close(); }
  jaus::node::Node& node() { return host->node(); }
  jaus::transport::UdpLink& link() { return *host->udp_link(); }
  jaus::rt::Clock& clock() { return host->clock(); }

 private:
  static std::unique_ptr<jaus::host::NodeHost> open_host(boost::asio::io_context& io, const TargetOptions& options) {
    jaus::host::HostConfig config = target_config(options);
    config.link.bind = jaus::transport::Ipv4Endpoint{kLoopback, 0};
    // The node an OCU talks to also bridges to the other subsystems it hears
    // (the cross-subsystem discovery tests reach a peer through it).
    config.link.relay = true;
    for (const auto& peer : options.peers) config.link.peers.push_back({peer, jaus::transport::Framing::opc});
    auto opened = jaus::host::NodeHost::open(config, io);
    if (!opened) throw std::runtime_error(opened.error().message());
    return std::move(*opened);
  }
};

}  // namespace jausctl::test
