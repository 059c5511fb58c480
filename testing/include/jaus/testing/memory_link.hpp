// Nodes in one process, joined as a network would join them, for tests and
// examples under virtual time (or any injected scheduler): each node
// transmits on its own MemoryLink of one MemoryNetwork, and a packet reaches
// the links of the JAUS nodes its destination names (255: every one but the
// sender's) `latency` later, through the scheduler, never during transmit().
//
//   rt::VirtualTime time;
//   testing::MemoryNetwork network(time, time);
//   auto& link = network.attach(1, 1);
//   node::Node node(config, time, time, link);   // config: subsystem 1, node 1
//   link.deliver_to(node);
//
// The network outlives its links, and the nodes and sessions they deliver to
// disconnect (on_receive({})) or outlive the packets still in flight.
//
// A lossy radio link: link.set_loss(0.1, 0.1, seed) drops 10 % of what the
// link sends and 10 % of what reaches it, at random but the same for a seed;
// link.set_burst_loss(...) drops in bursts, as a radio does; and
// network.set_jitter(extra, seed) delays each packet by up to `extra` more
// than the latency, so packets overtake each other; link.set_rate(...) makes
// the link a radio of that many bits a second, with a buffer of its own.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "jaus/base/time.hpp"
#include "jaus/core/header.hpp"
#include "jaus/node/node.hpp"

namespace jaus::testing {

class MemoryNetwork;

class MemoryLink final : public node::Link {
 public:
  using Receiver = std::function<void(std::span<const std::uint8_t> packet)>;

  // Where the packets that reach this link go: the node's receive_bytes(),
  // or whatever stands in front of a node (an OCU session that watches every
  // packet). Empty: they are dropped.
  void deliver_to(node::Node& node) {
    receiver_ = [&node](std::span<const std::uint8_t> packet) { node.receive_bytes(packet); };
  }
  void on_receive(Receiver receiver) { receiver_ = std::move(receiver); }
  // Sees every packet the node hands this link, the header it wrote with it,
  // whether or not the link is connected: a test reads what its node sent.
  using Tap = std::function<void(const Header& header, std::span<const std::uint8_t> packet)>;
  void on_transmit(Tap tap) { tap_ = std::move(tap); }

  // The cable pulled (false): nothing leaves or arrives, in flight included.
  void set_connected(bool connected) { connected_ = connected; }
  bool connected() const { return connected_; }

  // Random loss, reproducible: each packet this link transmits is lost with
  // probability `outbound`, each that reaches it with `inbound` (clamped to
  // 0..1), drawn from a std::mt19937 seeded with `seed` (its raw output,
  // which the standard fixes: the same drops with every compiler). A packet
  // lost outbound reaches no link (the tap still sees it: the node sent it).
  void set_loss(double outbound, double inbound, std::uint32_t seed) {
    outbound_loss_ = std::clamp(outbound, 0.0, 1.0);
    inbound_loss_ = std::clamp(inbound, 0.0, 1.0);
    outbound_burst_ = inbound_burst_ = Burst{};
    random_.seed(seed);
  }
  // Loss in bursts, as a radio fades: each way alternates good and bad
  // periods, their lengths drawn at random (exponentially distributed) with
  // these means, and what is sent or arrives in a bad period is lost. The
  // mean loss is mean_bad / (mean_good + mean_bad), whatever the traffic.
  // Replaces set_loss's random loss (and the reverse); the same periods for
  // a seed.
  void set_burst_loss(rt::Duration mean_good, rt::Duration mean_bad, std::uint32_t seed);
  // Packets dropped by set_loss or set_burst_loss, both ways (not those of a pulled cable).
  std::uint64_t packets_lost() const { return lost_; }

  // A radio of `bits_per_second` (0: none, the default): what this link
  // transmits leaves one packet after another, each taking its size plus
  // `overhead_bytes` (IP and UDP headers, framing) at that rate, first in
  // first out; a packet that finds `buffer_bytes` already waiting is dropped
  // (counted in packets_overflowed), as a radio's full buffer drops it.
  void set_rate(std::uint64_t bits_per_second, std::size_t buffer_bytes, std::size_t overhead_bytes = 36) {
    bits_per_second_ = bits_per_second;
    buffer_bytes_ = buffer_bytes;
    overhead_bytes_ = overhead_bytes;
  }
  std::uint64_t packets_overflowed() const { return overflowed_; }
  // How long what the radio holds now takes to leave.
  rt::Duration radio_backlog() const;

  std::uint8_t subsystem() const { return subsystem_; }
  std::uint8_t node() const { return node_; }
  std::uint64_t packets_sent() const { return sent_; }
  std::uint64_t packets_received() const { return received_; }

  // node::Link.
  void transmit(const Header& header, std::span<const std::uint8_t> packet) override;
  // What a UDP node's static peers get: the packet reaches every other link,
  // whatever its destination names (a node sending its own subsystem's
  // heartbeats to each endpoint it is configured with).
  void transmit_to_every_link(const Header& header, std::span<const std::uint8_t> packet);

 private:
  friend class MemoryNetwork;
  MemoryLink(MemoryNetwork& network, std::uint8_t subsystem, std::uint8_t node)
      : network_(network), subsystem_(subsystem), node_(node) {}
  void arrive(std::span<const std::uint8_t> packet);
  bool reached_by(const Address& destination) const {
    return (destination.subsystem == subsystem_ || destination.subsystem == Address::kBroadcast) &&
           (destination.node == node_ || destination.node == Address::kBroadcast);
  }

  bool lost(double probability) {
    if (probability <= 0) return false;
    const bool dropped = draw(probability);
    lost_ += dropped;
    return dropped;
  }
  // mt19937 draws 32-bit values: true when below probability * 2^32.
  bool draw(double probability) { return static_cast<double>(random_()) < probability * 4294967296.0; }

  struct Burst {
    rt::Duration mean_good{};
    rt::Duration mean_bad{};  // zero: no bursts
    bool bad = false;
    rt::TimePoint until{};    // when the period under way ends
  };
  // Whether what is on the air at `at` is lost (`at` never goes back for one burst).
  bool lost_in_burst(Burst& burst, rt::TimePoint at);
  // How long the packet waits in the radio before its last bit has left
  // (set_rate); nullopt: the radio's buffer is full.
  std::optional<rt::Duration> radio_delay(std::size_t packet_size);
  // A period's length: exponentially distributed with this mean (1 ns at least).
  rt::Duration period_of(rt::Duration mean) {
    const double u = (static_cast<double>(random_()) + 0.5) / 4294967296.0;
    return std::max(rt::Duration(1), rt::Duration(static_cast<rt::Duration::rep>(
                                         -std::log(u) * static_cast<double>(mean.count()))));
  }

  MemoryNetwork& network_;
  std::uint8_t subsystem_;
  std::uint8_t node_;
  bool connected_ = true;
  double outbound_loss_ = 0;
  double inbound_loss_ = 0;
  Burst outbound_burst_;
  Burst inbound_burst_;
  std::mt19937 random_;
  std::uint64_t lost_ = 0;
  std::uint64_t bits_per_second_ = 0;
  std::size_t buffer_bytes_ = 0;
  std::size_t overhead_bytes_ = 0;
  rt::TimePoint radio_free_at_{};  // when the radio has sent all it holds
  std::uint64_t overflowed_ = 0;
  Receiver receiver_;
  Tap tap_;
  std::uint64_t sent_ = 0;
  std::uint64_t received_ = 0;
};

class MemoryNetwork {
 public:
  // latency 0: a packet arrives once the current handler has returned.
  MemoryNetwork(rt::Clock& clock, rt::Scheduler& scheduler, rt::Duration latency = {})
      : clock_(clock), scheduler_(scheduler), latency_(latency) {}
  MemoryNetwork(const MemoryNetwork&) = delete;
  MemoryNetwork& operator=(const MemoryNetwork&) = delete;

  // The link of JAUS node `subsystem`.`node`, valid as long as the network.
  MemoryLink& attach(std::uint8_t subsystem, std::uint8_t node) {
    links_.push_back(std::unique_ptr<MemoryLink>(new MemoryLink(*this, subsystem, node)));
    return *links_.back();
  }

  rt::Duration latency() const { return latency_; }
  void set_latency(rt::Duration latency) { latency_ = latency; }
  // Each packet (each copy of a broadcast) takes the latency plus up to
  // `extra` more, uniformly (the same delays for a seed, with every
  // compiler): packets sent closer together than `extra` may overtake each
  // other, as on a radio.
  void set_jitter(rt::Duration extra, std::uint32_t seed) {
    jitter_ = std::max(extra, rt::Duration::zero());
    jitter_random_.seed(seed);
  }

 private:
  friend class MemoryLink;

  void carry(const MemoryLink& from, const Header& header, std::span<const std::uint8_t> packet,
             bool to_every_link = false, rt::Duration queued = {}) {
    std::shared_ptr<const std::vector<std::uint8_t>> bytes;
    for (const auto& link : links_) {
      if (link.get() == &from || (!to_every_link && !link->reached_by(header.destination))) continue;
      if (!bytes) bytes = std::make_shared<const std::vector<std::uint8_t>>(packet.begin(), packet.end());
      // Packets already in flight when the network goes are dropped.
      std::weak_ptr<const char> alive = alive_;
      scheduler_.call_at(clock_.now() + queued + latency_ + jitter(), [alive, to = link.get(), bytes] {
        if (!alive.expired()) to->arrive(*bytes);
      });
    }
  }

  // The extra delay of one packet (set_jitter).
  rt::Duration jitter() {
    if (jitter_ <= rt::Duration::zero()) return {};
    // A 32-bit draw scaled onto [0, jitter_].
    return rt::Duration(static_cast<rt::Duration::rep>(static_cast<double>(jitter_random_()) / 4294967295.0 *
                                                       static_cast<double>(jitter_.count())));
  }

  rt::Clock& clock_;
  rt::Scheduler& scheduler_;
  rt::Duration latency_;
  rt::Duration jitter_{};
  std::mt19937 jitter_random_;
  std::vector<std::unique_ptr<MemoryLink>> links_;
  std::shared_ptr<const char> alive_ = std::make_shared<const char>(0);
};

inline void MemoryLink::set_burst_loss(rt::Duration mean_good, rt::Duration mean_bad, std::uint32_t seed) {
  outbound_loss_ = inbound_loss_ = 0;
  random_.seed(seed);
  const rt::TimePoint now = network_.clock_.now();
  for (Burst* burst : {&outbound_burst_, &inbound_burst_}) {
    *burst = Burst{mean_good, std::max(mean_bad, rt::Duration::zero()), false, {}};
    burst->until = now + period_of(mean_good);
  }
}

inline bool MemoryLink::lost_in_burst(Burst& burst, rt::TimePoint at) {
  if (burst.mean_bad <= rt::Duration::zero()) return false;
  while (at >= burst.until) {
    burst.bad = !burst.bad;
    burst.until += period_of(burst.bad ? burst.mean_bad : burst.mean_good);
  }
  lost_ += burst.bad;
  return burst.bad;
}

inline void MemoryLink::arrive(std::span<const std::uint8_t> packet) {
  if (!connected_ || !receiver_) return;
  if (lost(inbound_loss_) || lost_in_burst(inbound_burst_, network_.clock_.now())) return;
  ++received_;
  receiver_(packet);
}

inline rt::Duration MemoryLink::radio_backlog() const {
  return std::max(rt::Duration::zero(), radio_free_at_ - network_.clock_.now());
}

inline std::optional<rt::Duration> MemoryLink::radio_delay(std::size_t packet_size) {
  if (bits_per_second_ == 0) return rt::Duration::zero();
  const rt::TimePoint now = network_.clock_.now();
  const rt::Duration backlog = radio_backlog();
  const double held_bytes = std::chrono::duration<double>(backlog).count() * static_cast<double>(bits_per_second_) / 8;
  const std::size_t cost = packet_size + overhead_bytes_;
  if (held_bytes + static_cast<double>(cost) > static_cast<double>(buffer_bytes_)) {
    ++overflowed_;
    return std::nullopt;
  }
  const auto airtime = std::chrono::duration_cast<rt::Duration>(
      std::chrono::duration<double>(static_cast<double>(cost) * 8 / static_cast<double>(bits_per_second_)));
  radio_free_at_ = now + backlog + airtime;
  return backlog + airtime;
}

inline void MemoryLink::transmit(const Header& header, std::span<const std::uint8_t> packet) {
  if (tap_) tap_(header, packet);
  if (!connected_) return;
  ++sent_;
  const auto queued = radio_delay(packet.size());
  if (!queued) return;
  // A fade takes what is on the air then: the packet's last bit leaves at now + queued.
  if (lost(outbound_loss_) || lost_in_burst(outbound_burst_, network_.clock_.now() + *queued)) return;
  network_.carry(*this, header, packet, false, *queued);
}

inline void MemoryLink::transmit_to_every_link(const Header& header, std::span<const std::uint8_t> packet) {
  if (tap_) tap_(header, packet);
  if (!connected_) return;
  ++sent_;
  const auto queued = radio_delay(packet.size());
  if (!queued) return;
  // A fade takes what is on the air then: the packet's last bit leaves at now + queued.
  if (lost(outbound_loss_) || lost_in_burst(outbound_burst_, network_.clock_.now() + *queued)) return;
  network_.carry(*this, header, packet, true, *queued);
}

}  // namespace jaus::testing
