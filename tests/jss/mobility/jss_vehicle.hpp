// A whole simulated vehicle with its JSS face under virtual time
// (jss_face_host.hpp: node manager, primitive driver, the pose and velocity
// sensors, the local waypoint driver), and a JSS client that speaks AS5669A
// datagrams straight to the face.
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

#include "jaus/components/local_waypoint_driver.hpp"
#include "jaus/components/primitive_driver.hpp"
#include "jaus/jss/all.hpp"
#include "jaus/jss/judp.hpp"
#include "jss_face_host.hpp"

namespace jaus::test {

// Our components' JSS IDs: subsystem 1, node 1, the RA component IDs.
inline const jss::JssId kJssPrimitiveDriver{1, 1, 33};
inline const jss::JssId kJssGlobalPose{1, 1, 38};
inline const jss::JssId kJssLocalPose{1, 1, 41};
inline const jss::JssId kJssVelocityState{1, 1, 42};
inline const jss::JssId kJssWaypointDriver{1, 1, 46};
inline const Address kRaPrimitiveDriver{1, 1, 33, 1};
inline const Address kRaWaypointDriver{1, 1, 46, 1};

class JssVehicle : public JssFaceHost {
 public:
  explicit JssVehicle(jss::JssId client = {42, 1, 1})
      : JssFaceHost({host::ComponentSpec{"node_manager", 1, 1, 0, "", {}, 0, {}},
                     host::ComponentSpec{"primitive_driver", 33, 1, 0, "", {}, 0, {}},
                     host::ComponentSpec{"global_pose_sensor", 38, 1, 0, "", {}, 0, {}},
                     host::ComponentSpec{"local_pose_sensor", 41, 1, 0, "", {}, 0, {}},
                     host::ComponentSpec{"velocity_state_sensor", 42, 1, 0, "", {}, 0, {}},
                     host::ComponentSpec{"local_waypoint_driver", 46, 1, 1, "", {}, 0, {}}},
                    "jss-mobility"),
        client_(client) {}
  ~JssVehicle() {
    if (keeper_ != rt::kNoTimer) time().cancel(keeper_);
  }

  rt::PrimaryStatus state_of(const Address& a) { return host().node().find(a)->state(); }
  components::LocalWaypointDriver& waypoint_driver() {
    return dynamic_cast<components::LocalWaypointDriver&>(*host().node().find(kRaWaypointDriver));
  }
  components::PoseSample pose() {
    auto* source = host().backends().find<components::PoseSource>();
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
    receive(jss::make_judp_datagram(h, contents));
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
    for (auto it = kept().begin(); it != kept().end(); ++it) {
      if (it->header.source != from || jss::message_id_of(it->contents) != R::code) continue;
      auto decoded = jss::decode_contents<R>(it->contents);
      kept().erase(it);
      if (!decoded) return std::nullopt;
      return *decoded;
    }
    return std::nullopt;
  }
  template <class R>
  void drop() {
    std::erase_if(kept(), [](const Received& r) { return jss::message_id_of(r.contents) == R::code; });
  }
  std::size_t count(std::uint16_t id) const {
    std::size_t n = 0;
    for (const auto& r : received()) n += jss::message_id_of(r.contents) == id;
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
    const auto end = time().now() + d;
    while (time().now() < end) {
      send(to, jss::msg::QueryStatus{});
      run_for(std::min<rt::Duration>(period, end - time().now()));
    }
  }

 private:
  void keep_control() {
    keeper_ = time().call_at(time().now() + 1s, [this] {
      keeper_ = rt::kNoTimer;
      for (const auto& [to, authority] : held_) send(to, jss::msg::RequestControl{{authority}});
      if (!held_.empty()) keep_control();
    });
  }
  jss::JssId client_;
  std::uint16_t sequence_ = 1;
  std::map<jss::JssId, std::uint8_t> held_;  // components the client keeps control of, at this authority
  rt::TimerId keeper_ = rt::kNoTimer;
};

}  // namespace jaus::test
