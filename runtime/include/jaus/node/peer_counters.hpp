// What a node exchanged with each other node (issue 45, step 4): packets
// each way, the fate of its ACK-requested messages, copies filtered. The
// node keeps one entry per peer node (subsystem.node: its components share
// the path), for up to max_peers of them; what comes from or goes to more
// is counted together in others(), so the totals stay whole. Broadcasts are
// nobody's in particular and are not counted per peer. Read by the node's
// metrics (jaus/host/metrics.hpp) beside the round trip measured to each.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <utility>

#include "jaus/core/address.hpp"

namespace jaus::node {

struct PeerCounts {
  std::uint64_t packets_received = 0;  // from any of its components, before any filtering
  std::uint64_t packets_sent = 0;      // to one of its components (large data sets: each packet)
  std::uint64_t retransmissions = 0;   // copies of ACK-requested messages sent again
  std::uint64_t acknowledged = 0;      // ACK-requested messages it ACKed...
  std::uint64_t refused = 0;           // ... NAKed ...
  std::uint64_t unacknowledged = 0;    // ... or never answered
  std::uint64_t duplicates = 0;        // copies from it already handled, filtered (ACKed again)
};

class PeerCounters {
 public:
  using PeerKey = std::pair<std::uint8_t, std::uint8_t>;  // subsystem, node

  explicit PeerCounters(std::size_t max_peers = 256) : max_peers_(max_peers) {}

  // The entry of `a`'s node: its own, or others() when max_peers are kept.
  // Broadcast subsystem or node: nullptr (nobody's in particular).
  PeerCounts* of(const Address& a) {
    if (a.subsystem == Address::kBroadcast || a.node == Address::kBroadcast) return nullptr;
    const PeerKey key{a.subsystem, a.node};
    if (const auto it = peers_.find(key); it != peers_.end()) return &it->second;
    if (peers_.size() >= max_peers_) return &others_;
    return &peers_[key];
  }

  const std::map<PeerKey, PeerCounts>& peers() const { return peers_; }
  const PeerCounts& others() const { return others_; }

 private:
  std::size_t max_peers_;
  std::map<PeerKey, PeerCounts> peers_;
  PeerCounts others_;
};

}  // namespace jaus::node
