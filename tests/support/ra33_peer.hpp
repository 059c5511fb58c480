// A scripted peer that behaves like the node manager of the common RA 3.3
// implementation on its subsystem interface (docs/wire-format.md,
// "Liveness and discovery" and "Interoperability"): subsystem 1, node 1, a
// plain UDP socket on loopback. It drops every message whose destination
// subsystem is neither its own nor 255 (and keeps them, so a test can say
// none came), heartbeats its subsystem (from its node manager) and every
// subsystem (from its communicator) once a second to the endpoints it is
// given, and answers Query Identification, Configuration, Subsystem List and
// Services as that node manager would. It answers to the endpoint a query
// came from (the real one answers IP:3794; the tests' nodes are on ephemeral
// ports).
#pragma once

#include <utility>  // Boost 1.74's Asio headers need it first

#include <boost/asio/io_context.hpp>
#include <chrono>
#include <map>
#include <type_traits>
#include <vector>

#include "scripted_memory_peer.hpp"
#include "scripted_udp_peer.hpp"

namespace jausctl::test {

template <class Peer>
class Ra33PeerOn final : public Peer {
 public:
  static constexpr std::uint8_t kSubsystem = 1;
  static constexpr jaus::Address kManager{kSubsystem, 1, 1, 1};
  static constexpr jaus::Address kCommunicator{kSubsystem, 1, 35, 1};
  static constexpr const char* kName = "ra33-vehicle";

  explicit Ra33PeerOn(boost::asio::io_context& io)
    requires std::is_same_v<Peer, ScriptedUdpPeer>
      : Peer(io) {}
  Ra33PeerOn(jaus::rt::VirtualTime& time, jaus::testing::MemoryNetwork& network)
    requires std::is_same_v<Peer, jaus::test_support::ScriptedMemoryPeer>
      : Peer(time, network, kSubsystem, 1) {}

  // Starts the 1 Hz heartbeats to `to` (its configured peers).
  void heartbeat_to(std::vector<jaus::transport::Ipv4Endpoint> to)
    requires std::is_same_v<Peer, ScriptedUdpPeer>
  {
    this->set_peers(std::move(to));
    heartbeat();
  }
  // On a memory network: to whoever the heartbeats' addresses reach.
  void start_heartbeats() { heartbeat(); }
  // Gone without a word (power cut): nothing in or out.
  void go_silent() { this->close(); }

  // What it accepted and what it dropped (addressed to another subsystem).
  std::vector<jaus::Header> accepted;
  std::vector<jaus::Header> dropped;

 private:
  void on_packet(const jaus::Header& h, std::span<const std::uint8_t> payload) override {
    const auto to = h.destination;
    if (to.subsystem != kSubsystem && to.subsystem != jaus::Address::kBroadcast) {
      dropped.push_back(h);
      return;
    }
    accepted.push_back(h);
    heard_[h.source.subsystem] = h.source;
    for (const jaus::Address self : {kManager, kCommunicator})
      if (to.matches(self)) answer(self, h, payload);
  }

  void answer(const jaus::Address& self, const jaus::Header& h, std::span<const std::uint8_t> payload) {
    using namespace jaus::msg;
    switch (h.command_code) {
      case QueryIdentification::code: {
        const auto q = jaus::wire::decode_payload<QueryIdentification>(payload);
        if (!q) return;
        if (self == kManager && q->query_type == identification::kSubsystem)
          return this->reply(self, h.source, ReportIdentification{{q->query_type, 0, 10001, kName}});
        if (self == kManager && q->query_type == identification::kNode)
          return this->reply(self, h.source, ReportIdentification{{q->query_type, 0, 40001, "ra33-node"}});
        if (q->query_type == identification::kComponent)
          return this->reply(self, h.source,
                       ReportIdentification{{q->query_type, 0, 0, self == kManager ? "NodeManager" : "Communicator"}});
        return;
      }
      case QueryConfiguration::code:
        if (self != kManager) return;
        return this->reply(self, h.source, ReportConfiguration{{{{1, {{1, 1}, {35, 1}}}}}});
      case QuerySubsystemList::code: {
        if (self != kManager) return;
        ReportSubsystemList list;
        list.subsystems.push_back(kManager);
        for (const auto& [subsystem, address] : heard_)
          if (subsystem != kSubsystem) list.subsystems.push_back(address);
        return this->reply(self, h.source, list);
      }
      case QueryServices::code:
        return this->reply(self, h.source, ReportServices{});
      default:
        return;
    }
  }

  void heartbeat() {
    this->send_to_peers(kManager, jaus::Address{kSubsystem, 255, 1, 1}, jaus::msg::ReportHeartbeatPulse{});
    this->send_to_peers(kCommunicator, jaus::Address{255, 255, 1, 1}, jaus::msg::ReportHeartbeatPulse{});
    this->after(std::chrono::seconds(1), [this] { heartbeat(); });
  }

  std::map<std::uint8_t, jaus::Address> heard_;  // by subsystem: who spoke for it
};

using Ra33Peer = Ra33PeerOn<ScriptedUdpPeer>;
using Ra33MemoryPeer = Ra33PeerOn<jaus::test_support::ScriptedMemoryPeer>;

}  // namespace jausctl::test
