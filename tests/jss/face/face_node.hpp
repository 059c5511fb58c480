// A node with its JSS face under virtual time (jss_face_host.hpp: node
// manager, primitive driver on the simulated vehicle, velocity state
// sensor), and JSS clients that speak AS5669A datagrams straight to it. An
// RA peer (kRaOperator) talks to the node directly; what the node sends it
// is kept too.
#pragma once

#include <gtest/gtest.h>

#include <deque>
#include <functional>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "jaus/jss/all.hpp"
#include "jaus/jss/judp.hpp"
#include "jaus/messages/all.hpp"
#include "jss_face_host.hpp"

namespace jaus::test {

inline const jss::JssId kNodeManager{1, 1, 1};
inline const jss::JssId kDriver{1, 1, 33};
inline const jss::JssId kVelocity{1, 1, 42};
inline const jss::JssId kEveryone{jss::JssId::kAllSubsystems, jss::JssId::kAll, jss::JssId::kAll};
inline const Address kRaDriver{1, 1, 33, 1};
inline const Address kRaOperator{5, 1, 40, 1};
inline const jss::JssId kClientA{42, 1, 1};
inline const jss::JssId kClientB{43, 1, 1};
inline const jss::JssId kClientC{44, 1, 1};

class FaceNode : public JssFaceHost {
 public:
  explicit FaceNode(jss_face::FaceConfig config = {})
      : JssFaceHost({host::ComponentSpec{"node_manager", 1, 1, 0, "", {}, 0, {}},
                     host::ComponentSpec{"primitive_driver", 33, 1, 0, "driver", {}, 0, {}},
                     host::ComponentSpec{"velocity_state_sensor", 42, 1, 0, "", {}, 0, {}}},
                    "face-test", std::move(config)) {
    link().on_transmit([this](const Header& h, std::span<const std::uint8_t> packet) {
      if (h.destination == kRaOperator) ra_received_.push_back({h, {packet.begin() + kHeaderSize, packet.end()}});
    });
    wait_ready();
  }
  // The host stops after this class's members are gone: no more taps into them.
  ~FaceNode() { link().on_transmit({}); }

  rt::Component& driver() { return *host().node().find(kRaDriver); }

  // `from` sends `message` to `to` in one datagram; returns its sequence number.
  template <class M>
  std::uint16_t send(const jss::JssId& from, const jss::JssId& to, const M& message, bool ack = false,
                     std::optional<std::uint16_t> sequence = std::nullopt) {
    jss::JudpHeader h;
    h.destination = to;
    h.source = from;
    h.sequence = sequence.value_or(sequence_++);
    if (ack) h.ack_nak = jss::JudpAckNak::ack_requested;
    const auto contents = jss::encode_contents(message);
    EXPECT_FALSE(contents.empty()) << M::name << " does not encode";
    receive(jss::make_judp_datagram(h, contents));
    return h.sequence;
  }
  // Sends, then waits for R from `from_component` to `client` (older Rs dropped first).
  template <class R, class M>
  std::optional<R> ask(const jss::JssId& client, const jss::JssId& to, const M& message, rt::Duration timeout = 500ms) {
    drop(client, R::code);
    send(client, to, message);
    std::optional<R> reply;
    run_until([&] { return (reply = take<R>(client, to)).has_value(); }, timeout);
    return reply;
  }
  // The oldest R to `client` from `from`, taken out.
  template <class R>
  std::optional<R> take(const jss::JssId& client, const jss::JssId& from) {
    for (auto it = kept().begin(); it != kept().end(); ++it) {
      if (it->header.destination != client || it->header.source != from || jss::message_id_of(it->contents) != R::code)
        continue;
      auto decoded = jss::decode_contents<R>(it->contents);
      EXPECT_TRUE(decoded.has_value()) << R::name << ": " << (decoded ? "" : decoded.error().message());
      kept().erase(it);
      if (!decoded) return std::nullopt;
      return *decoded;
    }
    return std::nullopt;
  }
  // Every R to `client` (from anyone), taken out.
  template <class R>
  std::vector<std::pair<jss::JssId, R>> take_all(const jss::JssId& client) {
    std::vector<std::pair<jss::JssId, R>> out;
    for (auto it = kept().begin(); it != kept().end();) {
      if (it->header.destination != client || jss::message_id_of(it->contents) != R::code) {
        ++it;
        continue;
      }
      if (auto decoded = jss::decode_contents<R>(it->contents)) out.emplace_back(it->header.source, *decoded);
      it = kept().erase(it);
    }
    return out;
  }
  std::size_t count(const jss::JssId& client, std::uint16_t id) const {
    std::size_t n = 0;
    for (const auto& r : received()) n += r.header.destination == client && jss::message_id_of(r.contents) == id;
    return n;
  }
  void drop(const jss::JssId& client, std::uint16_t id) {
    std::erase_if(kept(), [&](const Received& r) {
      return r.header.destination == client && jss::message_id_of(r.contents) == id;
    });
  }
  void clear() { kept().clear(); }

  // Request Control: the Confirm Control response code (nullopt: none came).
  std::optional<std::uint8_t> request_control(const jss::JssId& client, const jss::JssId& to, std::uint8_t authority) {
    auto confirm = ask<jss::msg::ConfirmControl>(client, to, jss::msg::RequestControl{{authority}});
    if (!confirm) return std::nullopt;
    return confirm->response_code;
  }
  std::optional<std::uint8_t> status_of(const jss::JssId& client, const jss::JssId& to) {
    auto report = ask<jss::msg::ReportStatus>(client, to, jss::msg::QueryStatus{});
    if (!report) return std::nullopt;
    return report->status;
  }

  // The RA peer kRaOperator sends an RA message to one of our components.
  template <class M>
  void send_ra(const Address& to, const M& message) {
    std::vector<std::uint8_t> payload(kMaxPayloadSize);
    auto size = wire::encode_payload(message, payload);
    ASSERT_TRUE(size.has_value());
    Header h;
    h.command_code = M::code;
    h.source = kRaOperator;
    h.destination = to;
    h.data_size = static_cast<std::uint16_t>(*size);
    host().node().receive(PacketView{h, std::span(payload).first(*size)});
  }
  std::size_t ra_count(std::uint16_t code) const {
    std::size_t n = 0;
    for (const auto& [h, payload] : ra_received_) n += h.command_code == code;
    return n;
  }

 private:
  std::uint16_t sequence_ = 1;
  std::vector<std::pair<Header, std::vector<std::uint8_t>>> ra_received_;
};

}  // namespace jaus::test
