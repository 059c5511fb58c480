// A scripted RA 3.x node as the common open implementation behaves on the
// wire (OpenJAUS's node manager with an OCU component on it): JUDP framing,
// one socket on UDP port 3794 that also joins the LAN's group 224.1.0.1, and
// every datagram it sends goes to the group (it never unicasts). It never
// ACKs (so never answers an endpoint challenge), answers Query Component
// Status (a controller's liveness check) and nothing else it is asked, and
// heartbeats (Report Heartbeat Pulse to 255.255.1.1) every second, which is
// how its subsystem's node managers find others. It counts what arrives for
// another subsystem (neither its own nor 255): the real one logs "Message
// received on my Subsystem Interface for another subsystem ID!" for each.
//
// `unicast()` makes the same peer send to one node's address instead (an OCU
// written from the spec, behind a router the group does not cross).
//
// It runs in the calling thread's network namespace (the test's `ocu` host),
// pumped by the test (pump, request): nothing happens between calls but what
// the kernel buffers.
#pragma once

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "jaus/core/header.hpp"
#include "jaus/messages/all.hpp"
#include "jaus/transport/framing.hpp"
#include "jaus/wire/message.hpp"

namespace jaus::test::network {

struct RaReceived {
  Header header;
  std::vector<std::uint8_t> payload;
  bool from_group = false;  // unused by the checks; kept for failure messages
};

class ScriptedRaPeer {
 public:
  using Clock = std::chrono::steady_clock;
  static constexpr std::uint16_t kPort = 3794;
  static constexpr const char* kGroup = "224.1.0.1";

  // `self` is its node manager (component 1); `ocu` the OCU component on it.
  // `interface_address`: the host's address on the LAN (the group's interface).
  ScriptedRaPeer(Address ocu, const std::string& interface_address) : ScriptedRaPeer(ocu) {
    fd_ = ::socket(AF_INET, SOCK_DGRAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
    if (fd_ < 0) return;
    const int on = 1, off = 0;
    ::setsockopt(fd_, SOL_SOCKET, SO_REUSEADDR, &on, sizeof on);
    sockaddr_in any{};
    any.sin_family = AF_INET;
    any.sin_port = htons(kPort);
    any.sin_addr.s_addr = htonl(INADDR_ANY);
    if (::bind(fd_, reinterpret_cast<const sockaddr*>(&any), sizeof any) != 0) {
      close_socket();
      return;
    }
    ip_mreq join{};
    ::inet_pton(AF_INET, kGroup, &join.imr_multiaddr);
    ::inet_pton(AF_INET, interface_address.c_str(), &join.imr_interface);
    if (::setsockopt(fd_, IPPROTO_IP, IP_ADD_MEMBERSHIP, &join, sizeof join) != 0) {
      close_socket();
      return;
    }
    ::setsockopt(fd_, IPPROTO_IP, IP_MULTICAST_IF, &join.imr_interface, sizeof join.imr_interface);
    ::setsockopt(fd_, IPPROTO_IP, IP_MULTICAST_LOOP, &off, sizeof off);
    send_to_.sin_family = AF_INET;
    send_to_.sin_port = htons(kPort);
    send_to_.sin_addr = join.imr_multiaddr;
  }
  // The same peer as an OCU written from the spec that never ACKs, where the
  // group does not reach (behind a router): bound to `bind_address`:3794, it
  // sends every datagram to `node_address`:3794 and joins no group.
  static std::unique_ptr<ScriptedRaPeer> unicast(Address ocu, const std::string& bind_address,
                                                 const std::string& node_address) {
    std::unique_ptr<ScriptedRaPeer> peer(new ScriptedRaPeer(ocu));
    peer->fd_ = ::socket(AF_INET, SOCK_DGRAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
    if (peer->fd_ < 0) return peer;
    sockaddr_in here{};
    here.sin_family = AF_INET;
    here.sin_port = htons(kPort);
    ::inet_pton(AF_INET, bind_address.c_str(), &here.sin_addr);
    if (::bind(peer->fd_, reinterpret_cast<const sockaddr*>(&here), sizeof here) != 0) {
      peer->close_socket();
      return peer;
    }
    peer->send_to_.sin_family = AF_INET;
    peer->send_to_.sin_port = htons(kPort);
    ::inet_pton(AF_INET, node_address.c_str(), &peer->send_to_.sin_addr);
    return peer;
  }
  ~ScriptedRaPeer() { close_socket(); }
  ScriptedRaPeer(const ScriptedRaPeer&) = delete;
  ScriptedRaPeer& operator=(const ScriptedRaPeer&) = delete;

  bool opened() const { return fd_ >= 0; }
  const Address& ocu() const { return ocu_; }

  // One message from `from` (default: the OCU component) to `to`, JUDP-framed, to the group (a unicast peer: to the node).
  template <class M>
  void send(const Address& to, const M& message, std::optional<Address> from = std::nullopt) {
    std::vector<std::uint8_t> packet(kHeaderSize + kMaxPayloadSize);
    const auto size = wire::encode_payload(message, std::span(packet).subspan(kHeaderSize));
    if (!size) return;
    Header h;
    h.command_code = M::code;
    h.source = from.value_or(ocu_);
    h.destination = to;
    h.data_size = static_cast<std::uint16_t>(*size);
    h.sequence = sequence_++;
    encode_header_unchecked(h, std::span<std::uint8_t, kHeaderSize>(packet.data(), kHeaderSize));
    packet.resize(kHeaderSize + *size);
    const auto prefix = transport::frame_prefix(transport::Framing::judp, packet.size());
    std::vector<std::uint8_t> datagram(prefix.view().begin(), prefix.view().end());
    datagram.insert(datagram.end(), packet.begin(), packet.end());
    ::sendto(fd_, datagram.data(), datagram.size(), 0, reinterpret_cast<const sockaddr*>(&send_to_), sizeof send_to_);
    ++sent_;
  }

  // Receives for `d`: heartbeats when due, Query Component Status answered,
  // everything for us kept in `inbox`.
  void pump(std::chrono::milliseconds d) {
    const auto until = Clock::now() + d;
    for (;;) {
      heartbeat_if_due();
      const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(until - Clock::now());
      if (left.count() <= 0) return;
      pollfd p{fd_, POLLIN, 0};
      if (::poll(&p, 1, static_cast<int>(std::min<long long>(left.count(), 100))) <= 0) continue;
      std::uint8_t buffer[9000];
      for (;;) {
        const auto n = ::recv(fd_, buffer, sizeof buffer, 0);
        if (n <= 0) break;
        on_datagram(std::span<const std::uint8_t>(buffer, static_cast<std::size_t>(n)));
      }
    }
  }

  // The last message of code `code` from `from` received since `since` (an inbox index).
  const RaReceived* last_from(const Address& from, std::uint16_t code, std::size_t since = 0) const {
    for (std::size_t i = inbox.size(); i > since; --i)
      if (inbox[i - 1].header.source == from && inbox[i - 1].header.command_code == code) return &inbox[i - 1];
    return nullptr;
  }

  // Sends `query` to `to` every 500 ms until a `Reply` from it arrives, or `deadline`.
  template <class Reply, class Query>
  std::optional<Reply> request(const Address& to, const Query& query,
                                              std::chrono::milliseconds deadline = std::chrono::seconds(10)) {
    const auto until = Clock::now() + deadline;
    const std::size_t since = inbox.size();
    while (Clock::now() < until) {
      send(to, query);
      const auto resend = Clock::now() + std::chrono::milliseconds(500);
      while (Clock::now() < resend) {
        pump(std::chrono::milliseconds(20));
        if (const auto* r = last_from(to, Reply::code, since)) {
          Reply reply{};
          if (wire::decode_payload_into(r->payload, reply)) return reply;
        }
      }
    }
    return std::nullopt;
  }

  // What arrived addressed to our subsystem or broadcast, and for us (or 255).
  std::vector<RaReceived> inbox;
  // Datagrams addressed to another subsystem: the real node logs each.
  std::vector<Header> for_another_subsystem;
  std::uint64_t ack_requests_ignored = 0;  // challenges and other ACK requests: never ACKed
  std::uint64_t malformed = 0;
  std::uint64_t sent() const { return sent_; }

 private:
  explicit ScriptedRaPeer(Address ocu) : ocu_(ocu), manager_{ocu.subsystem, ocu.node, 1, 1} {}
  void close_socket() {
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
  }
  void heartbeat_if_due() {
    if (Clock::now() < next_heartbeat_) return;
    next_heartbeat_ = Clock::now() + std::chrono::seconds(1);
    send(Address{255, 255, 1, 1}, msg::ReportHeartbeatPulse{}, manager_);
  }
  void on_datagram(std::span<const std::uint8_t> datagram) {
    auto unframed = transport::unframe(datagram);
    if (!unframed) {
      ++malformed;
      return;
    }
    const Header& h = unframed->packet.header;
    if (h.source.subsystem == ocu_.subsystem && h.source.node == ocu_.node) return;  // our own, looped back
    if (h.destination.subsystem != ocu_.subsystem && h.destination.subsystem != Address::kBroadcast) {
      for_another_subsystem.push_back(h);
      return;
    }
    if (h.ack_nak == AckNak::ack_requested) ++ack_requests_ignored;  // never ACKed
    const auto& payload = unframed->packet.payload;
    if (h.command_code == msg::QueryComponentStatus::code && h.destination.matches(ocu_))
      send(h.source, msg::ReportComponentStatus{{static_cast<std::uint8_t>(msg::PrimaryStatus::ready), 0}});
    inbox.push_back(RaReceived{h, std::vector<std::uint8_t>(payload.begin(), payload.end())});
  }

  Address ocu_;
  Address manager_;
  int fd_ = -1;
  sockaddr_in send_to_{};  // the group, or the node for a unicast peer
  std::uint16_t sequence_ = 0;
  std::uint64_t sent_ = 0;
  Clock::time_point next_heartbeat_{};
};

}  // namespace jaus::test::network
