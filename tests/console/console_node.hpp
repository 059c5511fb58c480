// A vehicle node on a jaus::testing memory network under virtual time
// (drive_node_config of tests/components/mobility: the primitive driver and
// pose sensors, plus a velocity sensor, a camera, an arm and a local
// waypoint driver), jaus-console's OperatorConsole on an OCU session
// attached to the network (254.1.40.1, its link tapped so tests see what it
// puts on the wire), and a rival operator (254.2.40.1) that can take control
// over or set an emergency behind the console's back. Pages are simulated:
// frames in through page_frame(), frames out recorded per page.
#pragma once

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "drive_node.hpp"
#include "jaus/console/operator_console.hpp"
#include "jaus/testing/components_ready.hpp"

namespace jaus::test {

inline const Address kConsole{254, 1, 40, 1};
inline const Address kRival{254, 2, 40, 1};
inline const Address kCamera{1, 1, 37, 1};
inline const Address kArm{1, 1, 49, 1};
inline const Address kWaypointDriver{1, 1, 46, 1};

struct SentEffort {
  rt::TimePoint at;
  double linear = 0;
  double angular = 0;
};

class ConsoleNode {
 public:
  // `more`: components of the vehicle beyond these.
  explicit ConsoleNode(std::vector<host::ComponentSpec> more = {})
      : network_(time_, time_), vehicle_link_(network_.attach(1, 1)), console_link_(network_.attach(254, 1)) {
    DriveNodeOptions options;
    options.drivers = {"local_waypoint_driver"};
    auto config = drive_node_config(options);
    config.components.push_back(host::ComponentSpec{"velocity_state_sensor", 42, 1, 0, "", {}, 0, {}});
    config.components.push_back(host::ComponentSpec{"visual_sensor", 37, 1, 0, "", {}, 0, {}});
    config.components.push_back(host::ComponentSpec{"primitive_manipulator", 49, 1, 0, "", {}, 0, {}});
    for (auto& spec : more) config.components.push_back(std::move(spec));
    components::CameraConfig camera;
    camera.id = 1;
    camera.pan = {-1.0, 1.0, 0.5};  // rad, rad/s
    camera.tilt = {-0.5, 0.5, 0.25};
    config.cameras.cameras = {camera};
    components::JointConfig shoulder;  // limits of -pi..pi rad
    shoulder.name = "shoulder";
    shoulder.link_length_m = 1;
    components::JointConfig elbow;
    elbow.name = "elbow";
    elbow.min_position = -1;
    elbow.max_position = 1;
    config.arm.joints = {shoulder, elbow};
    auto attached = host::NodeHost::attach(std::move(config), vehicle_link_, time_, time_);
    if (!attached) throw std::runtime_error(attached.error().message());
    host_ = std::move(*attached);
    vehicle_link_.deliver_to(host_->node());

    console_link_.on_transmit([this](const Header& h, std::span<const std::uint8_t> packet) {
      if (h.command_code != msg::SetWrenchEffort::code || h.destination != kPrimitiveDriver) return;
      msg::SetWrenchEffort effort{};
      if (packet.size() < h.data_size || !wire::decode_payload_into(packet.last(h.data_size), effort)) return;
      efforts_.push_back({time_.now(), effort.propulsive_linear_effort_x_percent.value_or(0),
                          effort.propulsive_rotational_effort_z_percent.value_or(0)});
    });
    ocu::SessionOptions session;
    session.self = kConsole;
    auto op = test_support::attach_ocu(time_, console_link_, session);
    if (!op) throw std::runtime_error(op.error().message());
    session_ = std::move(*op);
    ocu::SessionOptions rival = session;  // a copy: gcc 12 -O1 misreads a second default one (maybe-uninitialized)
    rival.self = kRival;
    auto r = test_support::attach_ocu(time_, network_, rival);
    if (!r) throw std::runtime_error(r.error().message());
    rival_ = std::move(*r);

    console::ConsoleOptions console_options;
    console_options.version = "test";
    console_ = std::make_unique<console::OperatorConsole>(
        *session_, time_, time_, console_options,
        [this](console::PageId to, const std::string& frame) { frames_.push_back({to, nlohmann::json::parse(frame)}); });
    console_->start();
  }
  ~ConsoleNode() {
    console_.reset();
    rival_.reset();
    session_.reset();
    host_->stop("test over");
    vehicle_link_.on_receive({});
    vehicle_link_.set_connected(false);
  }
  ConsoleNode(const ConsoleNode&) = delete;
  ConsoleNode& operator=(const ConsoleNode&) = delete;

  rt::VirtualTime& time() { return time_; }
  console::OperatorConsole& console() { return *console_; }
  ocu::OcuSession& rival() { return *rival_; }
  rt::Component* find(const Address& a) { return host_->node().find(a); }
  rt::PrimaryStatus state_of(const Address& a) { return find(a)->state(); }
  const std::vector<SentEffort>& efforts() const { return efforts_; }
  double speed_mps() {
    auto* source = host_->backends().find<components::PoseSource>();
    auto sample = source ? source->sample() : std::nullopt;
    return sample && sample->velocity_mps ? std::hypot(sample->velocity_mps->x, sample->velocity_mps->y) : 0.0;
  }

  void run_for(rt::Duration d) { testing::run_for(time_, d); }
  bool run_until(const std::function<bool()>& done, rt::Duration limit) {
    return testing::run_until(time_, done, limit);
  }
  bool wait_ready(rt::Duration limit = 10s) {
    const bool ready = run_until([&] { return testing::all_components_ready(host_->node()); }, limit);
    for (const auto& component : testing::components_not_ready(host_->node())) ADD_FAILURE() << component << " is not Ready";
    return ready;
  }

  void page_sends(console::PageId page, const nlohmann::json& frame) { console_->page_frame(page, frame.dump()); }
  // The frames of `type` that reached `page` (sent to it or to every page).
  std::vector<nlohmann::json> frames(console::PageId page, const std::string& type) const {
    std::vector<nlohmann::json> out;
    for (const auto& [to, frame] : frames_)
      if ((to == page || to == console::kEveryPage) && frame.value("type", "") == type) out.push_back(frame);
    return out;
  }
  void clear_frames() { frames_.clear(); }

  // A page holding the drive key: a frame every 50 ms for `d`.
  void hold(console::PageId page, double linear, double angular, rt::Duration d) {
    const auto until = time_.now() + d;
    while (time_.now() < until) {
      page_sends(page, {{"type", "drive"}, {"target", "1.1.33.1"}, {"linear", linear}, {"angular", angular},
                        {"held", true}});
      run_for(50ms);
    }
  }
  // Control of the primitive driver for `page`, held (confirmed and Ready).
  bool take_control(console::PageId page, const Address& target = kPrimitiveDriver, int authority = 5) {
    page_sends(page, {{"type", "control"}, {"target", target.to_string()}, {"action", "request"},
                      {"authority", authority}});
    return run_until([&] { return console_->holds_control(target); }, 3s);
  }

 private:
  rt::VirtualTime time_;
  testing::MemoryNetwork network_;
  testing::MemoryLink& vehicle_link_;
  testing::MemoryLink& console_link_;
  std::unique_ptr<host::NodeHost> host_;
  std::unique_ptr<ocu::OcuSession> session_;
  std::unique_ptr<ocu::OcuSession> rival_;
  std::unique_ptr<console::OperatorConsole> console_;
  std::vector<std::pair<console::PageId, nlohmann::json>> frames_;
  std::vector<SentEffort> efforts_;
};

}  // namespace jaus::test
