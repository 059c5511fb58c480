// A ClientCore and a SimPlatform wired together under rt::VirtualTime, with
// the faults the client's tests need: ACKs lost, bits flipped, a pulled cable,
// a platform that no longer hears (tests/clearpath: queue and probe tests).
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "jaus/base/virtual_time.hpp"
#include "jaus/clearpath/client_core.hpp"
#include "jaus/clearpath/codec.hpp"
#include "jaus/clearpath/frame.hpp"
#include "jaus/clearpath/sim/fault_injector.hpp"
#include "jaus/clearpath/sim/sim_platform.hpp"

namespace jaus::test {

namespace cp = jaus::clearpath;
namespace sim = jaus::clearpath::sim;
using namespace std::chrono_literals;

// ClientCore wired to a SimPlatform as sim::LoopbackClient wires them, but the
// platform's ACKs can be lost: at random by the seeded FaultInjector
// (drop_rate), or by a test's own rule. Frames can get a flipped bit each way
// (corrupt_rate), and the platform can go deaf (a one-way line: it hears
// nothing, its data still flows). A period of more than 1 ms with one frame
// per period makes the link slower than the application.
struct LossyOptions {
  sim::FaultConfig faults;
  cp::ClientConfig client;
  rt::Duration period = 1ms;
  std::size_t frames_per_period = 1000;
};

class LossyLink {
 public:
  using Options = LossyOptions;

  explicit LossyLink(Options options = {})
      : options_(options), platform_({}, time_.now()), client(options.client), faults_(options.faults) {
    client.reconnect_started(time_.now());
    client.on_connected(time_.now());
    time_.call_at(time_.now(), [this] { step(); });
  }

  void run_for(rt::Duration d) { time_.advance(d); }
  rt::TimePoint now() const { return time_.now(); }
  // A pulled cable: nothing crosses, reopening fails until it is plugged back.
  void set_plugged(bool plugged) { plugged_ = plugged; }
  // A one-way line: what the client writes never reaches the platform, whose
  // data (and watchdog) go on.
  void set_deaf(bool deaf) { deaf_ = deaf; }
  const sim::SimPlatform& platform() const { return platform_; }
  sim::SimPlatform& platform() { return platform_; }

  // Every frame written of `type`, decoded, in order.
  template <class M>
  std::vector<M> written_of() const {
    std::vector<M> out;
    for (const auto& f : written)
      if (f.header.type == M::kType)
        if (auto e = cp::decode(f, cp::Direction::to_platform)) out.push_back(e->message.template get<M>());
    return out;
  }

  // A test's own rule: true drops the ACK answering this frame header.
  std::function<bool(const cp::FrameHeader& acked)> drop_ack;
  std::vector<cp::Frame> written;
  std::uint64_t acks_dropped = 0;

 private:
  void step() {
    const auto now = time_.now();
    client.tick(now);
    if (client.wants_reconnect() && now >= client.reconnect_at()) {
      client.reconnect_started(now);
      if (plugged_) client.on_connected(now);
      else client.open_failed(now);
    }
    for (std::size_t n = 0; n < options_.frames_per_period; ++n) {
      const auto frame = client.take_frame(now);
      if (frame.empty()) break;
      if (auto decoded = cp::decode_frame(frame)) written.push_back(*decoded);
      if (!plugged_ || deaf_) continue;
      auto sent = frame;
      faults_.maybe_corrupt(sent);
      deliver(platform_.receive(sent, now), now);
    }
    deliver(platform_.tick(now), now);
    time_.call_at(now + options_.period, [this] { step(); });
  }

  void deliver(const std::vector<std::uint8_t>& bytes, rt::TimePoint now) {
    if (!plugged_) return;
    for (const auto frame : cp::split_frames(bytes)) {
      const auto decoded = cp::decode_frame(frame);
      if (decoded && is_ack(*decoded) && (faults_.drop() || (drop_ack && drop_ack(decoded->header)))) {
        ++acks_dropped;
        continue;
      }
      std::vector<std::uint8_t> received(frame.begin(), frame.end());
      faults_.maybe_corrupt(received);
      client.on_bytes(received, now);
    }
  }

  static bool is_ack(const cp::Frame& frame) {
    const auto e = cp::decode(frame, cp::Direction::from_platform);
    return e && e->message.get_if<cp::Ack>() != nullptr;
  }

  Options options_;
  rt::VirtualTime time_;
  sim::SimPlatform platform_;

 public:
  cp::ClientCore client;

 private:
  sim::FaultInjector faults_;
  bool plugged_ = true;
  bool deaf_ = false;
};

}  // namespace jaus::test
