// How long to wait for an answer before sending again, from the round trip
// measured to each peer, as TCP does (RFC 6298): a smoothed round trip and
// its variation from each answered message that went out once (never from a
// retransmitted one, whose answer could be any copy's: Karn's rule), a
// retransmission timeout from them within bounds, and a timeout that doubles
// when it expires and stays doubled until the next measurement.
//
// A field radio's round trip is 100-600 ms with jitter, a LAN's under a
// millisecond: a fixed period retransmits a radio's every command several
// times before its ACK can return, or leaves a LAN's loss unrepaired for
// long. Sans-I/O: times are passed in (the ACK tracker's, ack_tracker.hpp).
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>

#include "jaus/base/time.hpp"

namespace jaus::node {

struct RoundTripOptions {
  // Before a peer's first measurement. RFC 6298 says 1 s for TCP; a stop
  // whose first copy is lost should not wait that long, and a radio's copies
  // sent before the first ACK returns cost a few small packets, once.
  rt::Duration initial_timeout = std::chrono::milliseconds(100);
  // Never sooner than this (a LAN's loss is repaired at today's pace, 50 ms)
  // nor later than this (a link back from a drop-out is found within it).
  rt::Duration min_timeout = std::chrono::milliseconds(50);
  rt::Duration max_timeout = std::chrono::seconds(2);
  // The clock's granularity (G): the least variation term.
  rt::Duration granularity = std::chrono::milliseconds(1);
};

// One peer's estimate.
class RoundTripEstimator {
 public:
  explicit RoundTripEstimator(RoundTripOptions options = {})
      : options_(options), measured_timeout_(bounded(options.initial_timeout)), timeout_(measured_timeout_) {}

  // A round trip measured: a message sent once and its answer.
  void sample(rt::Duration measured) {
    measured = std::max(measured, rt::Duration::zero());
    if (samples_ == 0) {
      smoothed_ = measured;
      variation_ = measured / 2;
    } else {
      // RFC 6298 2.3: beta 1/4, alpha 1/8; the variation first, from the old mean.
      const rt::Duration error = smoothed_ > measured ? smoothed_ - measured : measured - smoothed_;
      variation_ = (3 * variation_ + error) / 4;
      smoothed_ = (7 * smoothed_ + measured) / 8;
    }
    ++samples_;
    measured_timeout_ = bounded(smoothed_ + std::max(options_.granularity, 4 * variation_));
    timeout_ = measured_timeout_;
    expired_ = {};
  }

  // A wait of `expired` went unanswered: the timeout is at least twice that
  // (RFC 6298 5.5) until the next measurement. Several messages timing out
  // together double it once, not once each.
  void back_off(rt::Duration expired) {
    expired_ = std::max(expired_, expired);
    timeout_ = std::max(timeout_, bounded(2 * expired));
  }

  // How long to wait for an answer to a message sent now.
  rt::Duration timeout() const { return timeout_; }
  // The same without the doubling: what the measurements alone say (a stop
  // is sent again at this pace however many waits expired).
  rt::Duration measured_timeout() const { return measured_timeout_; }
  // The longest wait that expired since the last measurement (zero: none).
  rt::Duration expired() const { return expired_; }
  // The smoothed round trip and its variation; none before a measurement.
  std::optional<rt::Duration> smoothed() const { return samples_ ? std::optional(smoothed_) : std::nullopt; }
  rt::Duration variation() const { return variation_; }
  std::uint64_t samples() const { return samples_; }

 private:
  rt::Duration bounded(rt::Duration d) const { return std::clamp(d, options_.min_timeout, options_.max_timeout); }

  RoundTripOptions options_;
  rt::Duration smoothed_{};
  rt::Duration variation_{};
  rt::Duration measured_timeout_;
  rt::Duration timeout_;
  rt::Duration expired_{};
  std::uint64_t samples_ = 0;
};

// The estimates of up to `max_peers` peers; when full, the one unused the
// longest makes room (it starts again from the initial timeout).
template <class Peer>
class RoundTrips {
 public:
  explicit RoundTrips(RoundTripOptions options = {}, std::size_t max_peers = 256)
      : options_(options), unknown_(options), max_peers_(std::max<std::size_t>(max_peers, 1)) {}

  // The peer's timeout (the initial one for a peer not known).
  rt::Duration timeout(const Peer& peer) const {
    const auto it = peers_.find(peer);
    return (it == peers_.end() ? unknown_ : it->second.estimator).timeout();
  }
  void sample(const Peer& peer, rt::Duration measured, rt::TimePoint now) { entry(peer, now).sample(measured); }
  void back_off(const Peer& peer, rt::Duration expired, rt::TimePoint now) { entry(peer, now).back_off(expired); }
  // nullptr: nothing known of the peer.
  const RoundTripEstimator* find(const Peer& peer) const {
    const auto it = peers_.find(peer);
    return it == peers_.end() ? nullptr : &it->second.estimator;
  }
  std::size_t size() const { return peers_.size(); }
  const RoundTripOptions& options() const { return options_; }

 private:
  struct Entry {
    RoundTripEstimator estimator;
    rt::TimePoint used{};
  };

  RoundTripEstimator& entry(const Peer& peer, rt::TimePoint now) {
    auto it = peers_.find(peer);
    if (it == peers_.end()) {
      if (peers_.size() >= max_peers_)
        peers_.erase(std::min_element(peers_.begin(), peers_.end(),
                                      [](const auto& a, const auto& b) { return a.second.used < b.second.used; }));
      it = peers_.emplace(peer, Entry{RoundTripEstimator(options_), now}).first;
    }
    it->second.used = now;
    return it->second.estimator;
  }

  RoundTripOptions options_;
  RoundTripEstimator unknown_;  // what a peer not measured yet gets
  std::size_t max_peers_;
  std::map<Peer, Entry> peers_;
};

}  // namespace jaus::node
