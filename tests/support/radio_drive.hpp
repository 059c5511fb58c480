// A vehicle driven over a field radio with its camera streaming, under
// virtual time (issue 45): the default vehicle's node (node manager,
// primitive driver and visual sensor on the simulated platform, a node host
// as jausd builds it) and an operator's node on a jaus::testing memory
// network whose two links are radios (MemoryLink::set_rate) with a delay,
// jitter and fades as RadioProfile says.
//
// The operator takes control of the driver, opens a Report Image service
// connection at the camera's frame rate (as fast as it can), sends Set
// Wrench Effort 10 times a second, and every 3 s sets an emergency
// (MustArrivePolicy::emergency(), as jausctl and the console do) and clears
// it 1.5 s later. drive_over_radio() returns what happened: the stops' ACK
// times, control lost, the efforts' latency to the vehicle's node, the
// frames received whole. bench_radio_link prints it; radio_drive_test checks
// a short one.
#pragma once

#include <chrono>
#include <cstdint>
#include <map>
#include <memory>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "jaus/base/virtual_time.hpp"
#include "jaus/components/camera.hpp"
#include "jaus/core/component_ids.hpp"
#include "jaus/host/node_host.hpp"
#include "jaus/messages/all.hpp"
#include "jaus/node/node.hpp"
#include "jaus/ocu/must_arrive.hpp"
#include "jaus/testing/memory_link.hpp"

namespace jaus::test_support::radio {

using namespace std::chrono_literals;
using rt::Duration;

struct RadioProfile {
  std::uint64_t bits_per_second = 256'000;  // each way
  std::size_t buffer_bytes = 32 * 1024;    // each radio's
  Duration least_one_way = 100ms;
  Duration jitter = 100ms;      // up to this much more each way
  Duration mean_good = 600ms;   // between fades
  Duration mean_fade = 150ms;   // zero: nothing lost
};

struct DriveOptions {
  RadioProfile radio;
  std::uint64_t budget_bits_per_second = 0;  // the vehicle's send budget; 0: none
  Duration length = 300s;
  std::uint32_t seed = 45;
  rt::LogFn vehicle_log;  // the vehicle host's lines; empty: none
};

const Address kDriver{1, 1, component_id::kPrimitiveDriver, 1};
const Address kCamera{1, 1, component_id::kVisualSensor, 1};
const Address kOperator{2, 1, 40, 1};

inline double ms(Duration d) { return std::chrono::duration<double, std::milli>(d).count(); }

struct Outcome {
  std::vector<double> emergency_ack_ms;
  int emergencies = 0;
  int control_granted = 0;
  int control_lost = 0;  // Reject Component Control while holding it
  std::vector<double> effort_ms;
  int efforts_sent = 0;
  std::vector<rt::TimePoint> frames;
  std::uint64_t frame_bytes = 0;
  std::uint64_t radio_overflowed = 0;
  std::string budget;
};

// The operator's component: takes what the vehicle sends it.
class Operator final : public rt::Component {
 public:
  Operator(rt::ComponentConfig config, rt::Environment env, Outcome& outcome)
      : Component(std::move(config), std::move(env)), outcome_(outcome) {
    using namespace msg;
    handle<ConfirmComponentControl>(Access::anyone, false, [this](const Header&, const ConfirmComponentControl& c) {
      if (c.response_code != control_response::kAccepted || holding_) return;
      holding_ = true;
      ++outcome_.control_granted;
    });
    handle<RejectComponentControl>(Access::anyone, false, [this](const Header&, const RejectComponentControl&) {
      if (holding_) ++outcome_.control_lost;
      holding_ = false;
    });
    handle<ConfirmServiceConnection>(Access::anyone, false,
                                     [this](const Header&, const ConfirmServiceConnection& c) {
                                       streaming_ = c.response_code == 0;
                                     });
    handle<ReportImage>(Access::anyone, false, [this](const Header&, const ReportImage& image) {
      outcome_.frames.push_back(this->env().clock.now());
      outcome_.frame_bytes += image.data.size();
    });
  }
  bool holding() const { return holding_; }
  bool streaming() const { return streaming_; }
  void request_control() { send(kDriver, msg::RequestComponentControl{{200}}); }
  void release_control() {
    send(kDriver, msg::ReleaseComponentControl{});
    holding_ = false;
  }
  void open_stream() {
    send(kCamera, msg::CreateServiceConnection{{msg::ReportImage::code, 10.0, 0}});
  }
  void drive(double percent) {
    msg::SetWrenchEffort effort;
    effort.propulsive_linear_effort_x_percent = percent;
    send(kDriver, effort);
  }

 private:
  Outcome& outcome_;
  bool holding_ = false;
  bool streaming_ = false;
};

inline host::HostConfig vehicle_config(std::uint64_t budget_bits_per_second) {
  host::HostConfig config;
  config.settings.identity.subsystem_name = "radio-vehicle";
  config.settings.identity.node_name = "vehicle";
  config.components = {
      host::ComponentSpec{"node_manager", 1, 1, 0, "node manager", {}, 0, {}},
      host::ComponentSpec{"primitive_driver", kDriver.component, 1, 0, "primitive driver", {}, 0, {}},
      host::ComponentSpec{"visual_sensor", kCamera.component, 1, 0, "visual sensor", {}, 0, {}}};
  // 320 x 240, 10 frames a second, JPEG first: its quality follows the link.
  components::CameraConfig camera;
  camera.image_formats = {components::image_format::kJpeg, components::image_format::kPng};
  config.cameras.cameras = {camera};
  config.send_budget.bits_per_second = budget_bits_per_second;
  return config;
}

inline Outcome drive_over_radio(const DriveOptions& options) {
  const RadioProfile& radio = options.radio;
  rt::VirtualTime time;
  testing::MemoryNetwork network(time, time, radio.least_one_way);
  network.set_jitter(radio.jitter, options.seed);
  auto& vehicle_link = network.attach(kDriver.subsystem, kDriver.node);
  auto& operator_link = network.attach(kOperator.subsystem, kOperator.node);
  for (auto* link : {&vehicle_link, &operator_link}) link->set_rate(radio.bits_per_second, radio.buffer_bytes);
  // One side's fades stand for the path's: both ways lose alike.
  if (radio.mean_fade > Duration::zero()) operator_link.set_burst_loss(radio.mean_good, radio.mean_fade, options.seed);

  Outcome outcome;
  auto host = host::NodeHost::attach(vehicle_config(options.budget_bits_per_second), vehicle_link, time, time,
                                     options.vehicle_log);
  if (!host) throw std::runtime_error("vehicle: " + host.error().message());
  host::NodeHost& vehicle = **host;
  // The efforts' arrival at the vehicle's node, by sequence number.
  std::map<std::uint16_t, rt::TimePoint> effort_sent;
  vehicle_link.on_receive([&](std::span<const std::uint8_t> packet) {
    if (auto h = decode_header(packet); h && h->command_code == msg::SetWrenchEffort::code) {
      if (auto sent = effort_sent.find(h->sequence); sent != effort_sent.end()) {
        outcome.effort_ms.push_back(ms(time.now() - sent->second));
        effort_sent.erase(sent);
      }
    }
    vehicle.node().receive_bytes(packet);
  });
  operator_link.on_transmit([&](const Header& h, std::span<const std::uint8_t>) {
    if (h.command_code == msg::SetWrenchEffort::code) effort_sent.emplace(h.sequence, time.now());
  });

  node::NodeConfig operator_config;
  operator_config.subsystem = kOperator.subsystem;
  operator_config.node = kOperator.node;
  node::Node ocu(operator_config, time, time, operator_link);
  operator_link.deliver_to(ocu);
  rt::ComponentConfig me;
  me.address = kOperator;
  me.name = "operator";
  auto& op = ocu.add_as(std::make_unique<Operator>(me, ocu.environment(), outcome));

  std::vector<std::uint8_t> payload(kMaxPayloadSize);
  auto emergency = [&](bool set) {
    Header h;
    h.command_code = set ? msg::SetEmergency::code : msg::ClearEmergency::code;
    h.priority = priority::kSafetyCritical;
    h.source = kOperator;
    h.destination = kDriver;
    const auto size = set ? wire::encode_payload(msg::SetEmergency{{1}}, payload)
                          : wire::encode_payload(msg::ClearEmergency{{1}}, payload);
    std::span<const std::uint8_t> body(payload.data(), *size);
    if (!set) {
      ocu.send_acknowledged(h, body, ocu::MustArrivePolicy{}, [](const node::AckResolution&) {});
      return;
    }
    ++outcome.emergencies;
    const auto start = time.now();
    ocu.send_acknowledged(h, body, ocu::MustArrivePolicy::emergency(),
                          [&outcome, &time, start](const node::AckResolution& r) {
                            if (r.outcome == node::AckOutcome::acknowledged)
                              outcome.emergency_ack_ms.push_back(ms(time.now() - start));
                          });
  };

  // Every 100 ms: an effort once control is held, the control request and
  // the stream's request again until answered; every 3 s a stop, cleared
  // 1.5 s later.
  const auto start = time.now();
  for (int tick = 0; time.now() - start < options.length; ++tick) {
    if (!op.holding() && tick % 10 == 0) op.request_control();
    if (!op.streaming() && tick % 10 == 5) op.open_stream();
    if (op.holding()) {
      op.drive(tick % 2 ? 20 : 25);
      ++outcome.efforts_sent;
    }
    if (tick >= 30 && tick % 30 == 0) emergency(true);
    if (tick >= 30 && tick % 30 == 15) emergency(false);
    time.advance(100ms);
  }
  // Control given back before the last stops settle (silence would lose it).
  op.release_control();
  time.advance(15s);
  outcome.radio_overflowed = vehicle_link.packets_overflowed() + operator_link.packets_overflowed();
  if (const auto* budgeted = vehicle.send_budget()) outcome.budget = budgeted->summary();
  vehicle.stop("benchmark over");
  return outcome;
}

inline double longest_gap_s(const std::vector<rt::TimePoint>& frames) {
  Duration longest{};
  for (std::size_t i = 1; i < frames.size(); ++i) longest = std::max(longest, frames[i] - frames[i - 1]);
  return std::chrono::duration<double>(longest).count();
}

}  // namespace jaus::test_support::radio
