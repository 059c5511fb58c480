// A whole simulated vehicle with its JSS face, under virtual time, and a JSS
// client that speaks AS5669A datagrams straight to the face: the node host
// (node manager, primitive driver, the pose and velocity sensors, the local
// waypoint driver on the simulated vehicle) attached to a FaceLink around a
// memory link, the face made on host->node() as jausd does; what the face
// sends is decoded and kept for the test.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "jaus/base/virtual_time.hpp"
#include "jaus/components/local_waypoint_driver.hpp"
#include "jaus/components/primitive_driver.hpp"
#include "jaus/host/node_host.hpp"
#include "jaus/jss/all.hpp"
#include "jaus/jss/judp.hpp"
#include "jaus/jss_face/face.hpp"
#include "jaus/testing/memory_link.hpp"
#include "jaus/testing/virtual_time.hpp"

namespace jaus::test {

using namespace std::chrono_literals;

// Our components' JSS IDs: subsystem 1, node 1, the RA component IDs.
inline const jss::JssId kJssPrimitiveDriver{1, 1, 33};
inline const jss::JssId kJssGlobalPose{1, 1, 38};
inline const jss::JssId kJssLocalPose{1, 1, 41};
inline const jss::JssId kJssVelocityState{1, 1, 42};
inline const jss::JssId kJssWaypointDriver{1, 1, 46};
inline const Address kRaPrimitiveDriver{1, 1, 33, 1};
inline const Address kRaWaypointDriver{1, 1, 46, 1};

struct Received {
  jss::JudpHeader header;
  std::vector<std::uint8_t> contents;
};

class JssVehicle {
 public:
  explicit JssVehicle(jss::JssId client = {42, 1, 1}) : client_(client), network_(time_, time_), link_(network_.attach(1, 1)), face_link_(link_) {
    host::HostConfig c;
    c.settings.identity.subsystem_name = "jss-mobility";
    c.settings.identity.node_name = "vehicle";
    c.components = {host::ComponentSpec{"node_manager", 1, 1, 0, "", {}, 0, {}},
                    host::ComponentSpec{"primitive_driver", 33, 1, 0, "", {}, 0, {}},
                    host::ComponentSpec{"global_pose_sensor", 38, 1, 0, "", {}, 0, {}},
                    host::ComponentSpec{"local_pose_sensor", 41, 1, 0, "", {}, 0, {}},
                    host::ComponentSpec{"velocity_state_sensor", 42, 1, 0, "", {}, 0, {}},
                    host::ComponentSpec{"local_waypoint_driver", 46, 1, 1, "", {}, 0, {}}};
    auto attached = host::NodeHost::attach(std::move(c), face_link_, time_, time_);
    if (!attached) throw std::runtime_error(attached.error().message());
    host_ = std::move(*attached);
    link_.deliver_to(host_->node());
    face_ = std::make_unique<jss_face::JssFace>(
        jss_face::FaceConfig{}, host_->node(),
        [this](const jss::JssId&, std::span<const std::uint8_t> datagram) { from_face(datagram); },
        [this](rt::LogLevel, const std::string& line) { log_.push_back(line); });
    face_link_.attach(face_.get());
  }
  ~JssVehicle() {
    if (keeper_ != rt::kNoTimer) time_.cancel(keeper_);
    host_->stop("test over");
    face_link_.attach(nullptr);
    face_.reset();
    link_.on_receive({});
    link_.set_connected(false);
  }
  JssVehicle(const JssVehicle&) = delete;
  JssVehicle& operator=(const JssVehicle&) = delete;

  rt::VirtualTime& time() { return time_; }
  host::NodeHost& host() { return *host_; }
  jss_face::JssFace& face() { return *face_; }
  const std::vector<std::string>& log() const { return log_; }
  void run_for(rt::Duration d) { testing::run_for(time_, d); }
  bool run_until(const std::function<bool()>& done, rt::Duration limit) {
    return testing::run_until(time_, done, limit);
  }
  bool wait_ready(rt::Duration limit = 10s) {
    return run_until(
        [&] {
          for (const rt::Component* c : host_->node().local_components())
            if (c->state() != rt::PrimaryStatus::ready) return false;
          return true;
        },
        limit);
  }
  rt::PrimaryStatus state_of(const Address& a) { return host_->node().find(a)->state(); }
  components::LocalWaypointDriver& waypoint_driver() {
    return dynamic_cast<components::LocalWaypointDriver&>(*host_->node().find(kRaWaypointDriver));
  }
  components::PoseSample pose() {
    auto* source = host_->backends().find<components::PoseSource>();
    auto sample = source->sample();
    if (!sample) throw std::runtime_error("no pose yet");
    return *sample;
  }
  double speed_mps() {
    const auto s = pose();
    return s.velocity_mps ? std::hypot(s.velocity_mps->x, s.velocity_mps->y) : 0.0;
  }

  // The client sends `message` to `to` (one AS5669A datagram, ACK requested when asked).
  template <class M>
  void send(const jss::JssId& to, const M& message, bool ack = false) {
    send_contents(to, jss::encode_contents(message), ack);
  }
  // Any contents (message ID, then body), well formed or not.
  void send_contents(const jss::JssId& to, std::span<const std::uint8_t> contents, bool ack = false) {
    jss::JudpHeader h;
    h.destination = to;
    h.source = client_;
    h.sequence = sequence_++;
    if (ack) h.ack_nak = jss::JudpAckNak::ack_requested;
    face_->receive(jss::make_judp_datagram(h, contents), rt::SenderStanding::trusted);
  }
  // Sends and waits up to `timeout` for R from `from` (earlier replies of R dropped first).
  template <class R, class M>
  std::optional<R> ask(const jss::JssId& to, const M& message, rt::Duration timeout = 500ms) {
    drop<R>();
    send(to, message);
    std::optional<R> reply;
    run_until([&] { return (reply = take<R>(to)).has_value(); }, timeout);
    return reply;
  }
  // The oldest R received from `from`, taken out.
  template <class R>
  std::optional<R> take(const jss::JssId& from) {
    for (auto it = received_.begin(); it != received_.end(); ++it) {
      if (it->header.source != from || jss::message_id_of(it->contents) != R::code) continue;
      auto decoded = jss::decode_contents<R>(it->contents);
      received_.erase(it);
      if (!decoded) return std::nullopt;
      return *decoded;
    }
    return std::nullopt;
  }
  template <class R>
  void drop() {
    std::erase_if(received_, [](const Received& r) { return jss::message_id_of(r.contents) == R::code; });
  }
  std::size_t count(std::uint16_t id) const {
    std::size_t n = 0;
    for (const auto& r : received_) n += jss::message_id_of(r.contents) == id;
    return n;
  }
  // Request Control: the response code of Confirm Control (nullopt: none).
  // Accepted, control is kept as JSS clients keep it (AS5710): Request
  // Control again every second, well within the 3 s timeout.
  std::optional<std::uint8_t> request_control(const jss::JssId& to, std::uint8_t authority = 5) {
    auto confirm = ask<jss::msg::ConfirmControl>(to, jss::msg::RequestControl{{authority}});
    if (!confirm) return std::nullopt;
    if (confirm->response_code == jss::msg::confirm_control::kControlAccepted) {
      held_[to] = authority;
      if (keeper_ == rt::kNoTimer) keep_control();
    }
    return confirm->response_code;
  }
  // The client falls silent: no more Request Control (nor anything else the test does not send).
  void stop_keeping_control() { held_.clear(); }
  void release_control(const jss::JssId& to) {
    held_.erase(to);
    send(to, jss::msg::ReleaseControl{});
  }
  // Something from the client every `period` (it keeps control by sending within the timeout).
  void keep_alive_for(const jss::JssId& to, rt::Duration d, rt::Duration period = 500ms) {
    const auto end = time_.now() + d;
    while (time_.now() < end) {
      send(to, jss::msg::QueryStatus{});
      run_for(std::min<rt::Duration>(period, end - time_.now()));
    }
  }

 private:
  void keep_control() {
    keeper_ = time_.call_at(time_.now() + 1s, [this] {
      keeper_ = rt::kNoTimer;
      for (const auto& [to, authority] : held_) send(to, jss::msg::RequestControl{{authority}});
      if (!held_.empty()) keep_control();
    });
  }
  void from_face(std::span<const std::uint8_t> datagram) {
    auto packets = jss::decode_judp_datagram(datagram);
    if (!packets) {
      ADD_FAILURE() << "the face sent a malformed datagram: " << packets.error().message();
      return;
    }
    for (const auto& p : *packets) {
      if (p.header.ack_nak == jss::JudpAckNak::ack) continue;
      received_.push_back(Received{p.header, {p.contents.begin(), p.contents.end()}});
      // Bounded: a test reads what it waits for; old reports go.
      if (received_.size() > 4096) received_.pop_front();
    }
  }

  jss::JssId client_;
  std::uint16_t sequence_ = 1;
  rt::VirtualTime time_;
  testing::MemoryNetwork network_;
  testing::MemoryLink& link_;
  jss_face::FaceLink face_link_;
  std::unique_ptr<host::NodeHost> host_;
  std::unique_ptr<jss_face::JssFace> face_;
  std::deque<Received> received_;
  std::vector<std::string> log_;
  std::map<jss::JssId, std::uint8_t> held_;  // components the client keeps control of, at this authority
  rt::TimerId keeper_ = rt::kNoTimer;
};

}  // namespace jaus::test
