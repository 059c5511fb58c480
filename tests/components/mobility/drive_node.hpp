// A vehicle node for the drivers above the primitive driver (issue 30), whole,
// under virtual time: a node host attached to a jaus::testing memory network
// hosting the node manager, the primitive driver 1.1.33.1, the pose sensors
// and the driver kinds under test, on the simulated vehicle (`model`) or the
// in-process Clearpath platform (`clearpath_sim`, through the bridge), either
// drivetrain; and an operator (an OCU session at 254.1.40.1) that sends what
// a test wants and sees every reply.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "jaus/base/virtual_time.hpp"
#include "jaus/components/mobility_driver.hpp"
#include "jaus/components/primitive_driver.hpp"
#include "jaus/host/model_platform.hpp"
#include "jaus/host/clearpath_platform.hpp"
#include "jaus/host/node_host.hpp"
#include "jaus/messages/all.hpp"
#include "jaus/ocu/session.hpp"
#include "jaus/testing/components_ready.hpp"
#include "jaus/testing/memory_link.hpp"
#include "jaus/testing/virtual_time.hpp"
#include "memory_ocu.hpp"

namespace jaus::test {

using namespace std::chrono_literals;

inline const Address kPrimitiveDriver{1, 1, 33, 1};
inline const Address kOperator{254, 1, 40, 1};

enum class PlatformUnderTest { model, clearpath_sim };

inline std::string platform_name(PlatformUnderTest p) { return p == PlatformUnderTest::model ? "model" : "clearpath_sim"; }

struct DriveNodeOptions {
  PlatformUnderTest platform = PlatformUnderTest::model;
  components::Steering steering = components::Steering::differential;
  // The driver kinds under test, each at its kind's ID, instance 1, authority
  // `driver_authority`, with these options.
  std::vector<std::string> drivers{};  // {}: a designated initializer may leave it out (GCC's -Wmissing-field-initializers)
  std::map<std::string, std::string> driver_options{};
  std::uint8_t driver_authority = 1;
  std::uint8_t operator_authority = 5;  // above the drivers': an operator takes over
};

inline host::HostConfig drive_node_config(const DriveNodeOptions& o) {
  host::HostConfig c;
  c.settings.identity.subsystem_name = "drive-test";
  c.settings.identity.node_name = "vehicle";
  c.vehicle.steering = o.steering;
  c.components = {host::ComponentSpec{"node_manager", 1, 1, 0, "", {}, 0, {}},
                  host::ComponentSpec{"primitive_driver", 33, 1, 0, "", {}, 0, {}},
                  host::ComponentSpec{"global_pose_sensor", 38, 1, 0, "", {}, 0, {}},
                  host::ComponentSpec{"local_pose_sensor", 41, 1, 0, "", {}, 0, {}}};
  for (const auto& kind : o.drivers) {
    const host::ComponentKind* k = host::find_component_kind(kind);
    if (!k) throw std::invalid_argument("no component kind " + kind);
    c.components.push_back(host::ComponentSpec{kind, k->default_id, 1, o.driver_authority, "", o.driver_options, 0, {}});
  }
  if (o.platform == PlatformUnderTest::clearpath_sim) {
    // As jausd maps `vehicle:` onto the simulated Clearpath platform and the bridge.
    auto& p = c.platform.sections.set(host::ClearpathSettings{});
    c.platform.kind = "clearpath_sim";
    const auto& v = c.vehicle;
    p.sim.vehicle.drive = v.steering == components::Steering::ackermann ? clearpath::sim::Drive::ackermann
                                                                        : clearpath::sim::Drive::differential;
    p.sim.vehicle.track_width = v.specifications.track_width_m.value_or(0.55);
    p.sim.vehicle.wheelbase = v.wheel_base_m;
    p.sim.vehicle.max_steering_angle = v.max_steering_rad;
    p.vehicle.drive = v.steering == components::Steering::ackermann ? bridge::DriveMode::ackermann
                                                                    : bridge::DriveMode::differential_output;
    p.vehicle.max_speed_mps = v.max_speed_mps;
    p.vehicle.max_yaw_rate_rps = v.max_yaw_rate_rps;
    p.vehicle.max_acceleration_mps2 = v.max_acceleration_mps2;
    p.vehicle.track_width_m = v.specifications.track_width_m.value_or(0.55);
    p.vehicle.wheel_base_m = v.wheel_base_m;
    p.vehicle.max_steering_rad = v.max_steering_rad;
    p.vehicle.specifications = v.specifications;
    p.vehicle.datum = v.start;
    p.vehicle.datum_heading_rad = v.start_heading_rad;
    p.vehicle.local_frame = v.local_frame;
  }
  return c;
}

class DriveNode {
 public:
  explicit DriveNode(DriveNodeOptions options, host::HostConfig config)
      : options_(std::move(options)), network_(time_, time_), link_(network_.attach(1, 1)) {
    auto attached = host::NodeHost::attach(std::move(config), link_, time_, time_);
    if (!attached) throw std::runtime_error(attached.error().message());
    host_ = std::move(*attached);
    link_.deliver_to(host_->node());
    ocu::SessionOptions session;
    session.self = kOperator;
    session.authority = options_.operator_authority;
    auto op = test_support::attach_ocu(time_, network_, session);
    if (!op) throw std::runtime_error(op.error().message());
    operator_ = std::move(*op);
  }
  explicit DriveNode(DriveNodeOptions options) : DriveNode(options, drive_node_config(options)) {}
  ~DriveNode() {
    operator_.reset();
    host_->stop("test over");
    link_.on_receive({});
    link_.set_connected(false);
  }
  DriveNode(const DriveNode&) = delete;
  DriveNode& operator=(const DriveNode&) = delete;

  rt::VirtualTime& time() { return time_; }
  host::NodeHost& host() { return *host_; }
  ocu::OcuSession& op() { return *operator_; }
  rt::Component* find(const Address& a) { return host_->node().find(a); }
  components::PrimitiveDriver& primitive_driver() {
    return dynamic_cast<components::PrimitiveDriver&>(*find(kPrimitiveDriver));
  }
  template <class C>
  C& component(const Address& a) {
    return dynamic_cast<C&>(*find(a));
  }

  // The vehicle's pose as the pose source has it now (either platform).
  components::PoseSample pose() {
    components::PoseSource* source = host_->backends().find<components::PoseSource>();
    if (!source) throw std::runtime_error("the host has no pose source");
    auto sample = source->sample();
    if (!sample) throw std::runtime_error("the pose source has no sample yet");
    return *sample;
  }
  double speed_mps() {
    const auto s = pose();
    return s.velocity_mps ? std::hypot(s.velocity_mps->x, s.velocity_mps->y) : 0.0;
  }

  void run_for(rt::Duration d) { testing::run_for(time_, d); }
  bool run_until(const std::function<bool()>& done, rt::Duration limit) {
    return testing::run_until(time_, done, limit);
  }
  // Every component Ready (the drivers wait for the primitive driver's specifications).
  bool wait_ready(rt::Duration limit = 10s) {
    return run_until([&] { return testing::all_components_ready(host_->node()); }, limit);
  }

  // The operator sends `message` to `to` and waits up to `timeout` for a reply
  // with one of `codes`; the reply decoded as R.
  template <class R, class M>
  std::optional<R> ask(const Address& to, const M& message, rt::Duration timeout = 1s) {
    auto reply = operator_->request(to, message, {R::code}, timeout);
    if (!reply) return std::nullopt;
    R decoded{};
    if (!wire::decode_payload_into(reply->payload, decoded, wire::Dialect::ra, kHeaderSize)) return std::nullopt;
    return decoded;
  }
  // Request Component Control of `to` with the operator's authority: true when confirmed.
  bool take_control(const Address& to) {
    auto confirm = ask<msg::ConfirmComponentControl>(to, msg::RequestComponentControl{{options_.operator_authority}});
    return confirm && confirm->response_code == msg::control_response::kAccepted;
  }
  template <class M>
  void send(const Address& to, const M& message) {
    operator_->send(to, message);
  }
  rt::PrimaryStatus state_of(const Address& a) { return find(a)->state(); }

 private:
  DriveNodeOptions options_;
  rt::VirtualTime time_;
  testing::MemoryNetwork network_;
  testing::MemoryLink& link_;
  std::unique_ptr<host::NodeHost> host_;
  std::unique_ptr<ocu::OcuSession> operator_;
};

}  // namespace jaus::test
