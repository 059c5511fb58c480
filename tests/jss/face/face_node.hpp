// A node with its JSS face under virtual time, and JSS clients that speak
// AS5669A datagrams straight to it: a node host (node manager, primitive
// driver on the simulated vehicle, velocity state sensor) attached to a
// FaceLink around a memory link, the face made on host->node() as jausd
// makes it; every datagram the face sends is kept (ACKs included), and
// large messages are put back together. An RA peer (kRaOperator) talks to
// the node directly; what the node sends it is kept too.
#pragma once

#include <gtest/gtest.h>

#include <deque>
#include <functional>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "jaus/base/virtual_time.hpp"
#include "jaus/host/node_host.hpp"
#include "jaus/jss/all.hpp"
#include "jaus/jss/judp.hpp"
#include "jaus/jss/large_message.hpp"
#include "jaus/jss_face/face.hpp"
#include "jaus/messages/all.hpp"
#include "jaus/testing/memory_link.hpp"
#include "jaus/testing/virtual_time.hpp"

namespace jaus::test {

using namespace std::chrono_literals;

inline const jss::JssId kNodeManager{1, 1, 1};
inline const jss::JssId kDriver{1, 1, 33};
inline const jss::JssId kVelocity{1, 1, 42};
inline const jss::JssId kEveryone{jss::JssId::kAllSubsystems, jss::JssId::kAll, jss::JssId::kAll};
inline const Address kRaDriver{1, 1, 33, 1};
inline const Address kRaOperator{5, 1, 40, 1};
inline const jss::JssId kClientA{42, 1, 1};
inline const jss::JssId kClientB{43, 1, 1};
inline const jss::JssId kClientC{44, 1, 1};

struct Received {
  jss::JudpHeader header;
  std::vector<std::uint8_t> contents;
};

class FaceNode {
 public:
  explicit FaceNode(jss_face::FaceConfig config = {})
      : network_(time_, time_), link_(network_.attach(1, 1)), face_link_(link_) {
    host::HostConfig c;
    c.settings.identity.subsystem_name = "face-test";
    c.settings.identity.node_name = "vehicle";
    c.components = {host::ComponentSpec{"node_manager", 1, 1, 0, "", {}, 0, {}},
                    host::ComponentSpec{"primitive_driver", 33, 1, 0, "driver", {}, 0, {}},
                    host::ComponentSpec{"velocity_state_sensor", 42, 1, 0, "", {}, 0, {}}};
    auto attached = host::NodeHost::attach(std::move(c), face_link_, time_, time_);
    if (!attached) throw std::runtime_error(attached.error().message());
    host_ = std::move(*attached);
    link_.deliver_to(host_->node());
    link_.on_transmit([this](const Header& h, std::span<const std::uint8_t> packet) {
      if (h.destination == kRaOperator) ra_received_.push_back({h, {packet.begin() + kHeaderSize, packet.end()}});
    });
    face_ = std::make_unique<jss_face::JssFace>(
        std::move(config), host_->node(),
        [this](const jss::JssId&, std::span<const std::uint8_t> datagram) { from_face(datagram); },
        [this](rt::LogLevel, const std::string& line) { log_.push_back(line); });
    face_link_.attach(face_.get());
    wait_ready();
  }
  ~FaceNode() {
    host_->stop("test over");
    face_link_.attach(nullptr);
    face_.reset();
    link_.on_receive({});
    link_.set_connected(false);
  }
  FaceNode(const FaceNode&) = delete;
  FaceNode& operator=(const FaceNode&) = delete;

  rt::VirtualTime& time() { return time_; }
  host::NodeHost& host() { return *host_; }
  jss_face::JssFace& face() { return *face_; }
  const jss_face::FaceCounters& counters() const { return face_->counters(); }
  const std::vector<std::string>& log() const { return log_; }
  rt::Component& driver() { return *host_->node().find(kRaDriver); }
  void run_for(rt::Duration d) { testing::run_for(time_, d); }
  bool run_until(const std::function<bool()>& done, rt::Duration limit = 500ms) {
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

  // One raw datagram to the face.
  void receive(std::span<const std::uint8_t> datagram, rt::SenderStanding standing = rt::SenderStanding::trusted) {
    face_->receive(datagram, standing);
  }
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
    for (auto it = received_.begin(); it != received_.end(); ++it) {
      if (it->header.destination != client || it->header.source != from || jss::message_id_of(it->contents) != R::code)
        continue;
      auto decoded = jss::decode_contents<R>(it->contents);
      EXPECT_TRUE(decoded.has_value()) << R::name << ": " << (decoded ? "" : decoded.error().message());
      received_.erase(it);
      if (!decoded) return std::nullopt;
      return *decoded;
    }
    return std::nullopt;
  }
  // Every R to `client` (from anyone), taken out.
  template <class R>
  std::vector<std::pair<jss::JssId, R>> take_all(const jss::JssId& client) {
    std::vector<std::pair<jss::JssId, R>> out;
    for (auto it = received_.begin(); it != received_.end();) {
      if (it->header.destination != client || jss::message_id_of(it->contents) != R::code) {
        ++it;
        continue;
      }
      if (auto decoded = jss::decode_contents<R>(it->contents)) out.emplace_back(it->header.source, *decoded);
      it = received_.erase(it);
    }
    return out;
  }
  std::size_t count(const jss::JssId& client, std::uint16_t id) const {
    std::size_t n = 0;
    for (const auto& r : received_) n += r.header.destination == client && jss::message_id_of(r.contents) == id;
    return n;
  }
  void drop(const jss::JssId& client, std::uint16_t id) {
    std::erase_if(received_, [&](const Received& r) {
      return r.header.destination == client && jss::message_id_of(r.contents) == id;
    });
  }
  void clear() { received_.clear(); }
  const std::deque<Received>& received() const { return received_; }
  const std::vector<jss::JudpHeader>& acks() const { return acks_; }
  std::size_t datagrams_sent() const { return datagrams_; }

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
    host_->node().receive(PacketView{h, std::span(payload).first(*size)});
  }
  std::size_t ra_count(std::uint16_t code) const {
    std::size_t n = 0;
    for (const auto& [h, payload] : ra_received_) n += h.command_code == code;
    return n;
  }

 private:
  void from_face(std::span<const std::uint8_t> datagram) {
    ++datagrams_;
    auto packets = jss::decode_judp_datagram(datagram);
    if (!packets) {
      ADD_FAILURE() << "the face sent a malformed datagram: " << packets.error().message();
      return;
    }
    for (const auto& p : *packets) {
      if (p.header.ack_nak == jss::JudpAckNak::ack) {
        EXPECT_TRUE(p.contents.empty()) << "an ACK carries no contents";
        acks_.push_back(p.header);
        continue;
      }
      auto whole = reassembler_.add(p, time_.now());
      if (!whole) {
        ADD_FAILURE() << "a packet of the face's large message does not fit: " << whole.error().message();
        continue;
      }
      if (!whole->has_value()) continue;
      received_.push_back(Received{(*whole)->header, std::move((*whole)->contents)});
      if (received_.size() > 4096) received_.pop_front();  // bounded: a test reads what it waits for
    }
  }

  std::uint16_t sequence_ = 1;
  rt::VirtualTime time_;
  testing::MemoryNetwork network_;
  testing::MemoryLink& link_;
  jss_face::FaceLink face_link_;
  std::unique_ptr<host::NodeHost> host_;
  std::unique_ptr<jss_face::JssFace> face_;
  jss::LargeMessageReassembler reassembler_;
  std::deque<Received> received_;
  std::vector<jss::JudpHeader> acks_;
  std::size_t datagrams_ = 0;
  std::vector<std::pair<Header, std::vector<std::uint8_t>>> ra_received_;
  std::vector<std::string> log_;
};

}  // namespace jaus::test
