#include "jaus/clearpath/sim/loopback_client.hpp"

namespace jaus::clearpath::sim {

LoopbackClient::LoopbackClient(rt::Clock& clock, rt::Scheduler& scheduler, LoopbackConfig config)
    : clock_(clock),
      scheduler_(scheduler),
      period_(config.period),
      platform_(std::move(config.platform), clock.now()),
      core_(config.client),
      faults_(config.faults) {
  core_.reconnect_started(clock_.now());
  core_.on_connected(clock_.now());
  timer_ = scheduler_.call_at(clock_.now(), [this] { step(); });
}

LoopbackClient::~LoopbackClient() { scheduler_.cancel(timer_); }

void LoopbackClient::step() {
  const auto now = clock_.now();
  core_.tick(now);
  // The link's reopening, as ClearpathLink does it; a pulled cable fails to open.
  if (core_.wants_reconnect() && now >= core_.reconnect_at()) {
    core_.reconnect_started(now);
    if (plugged_) core_.on_connected(now);
    else core_.open_failed(now);
  }
  for (auto frame = core_.take_frame(now); !frame.empty(); frame = core_.take_frame(now)) {
    if (on_written_) on_written_(frame);
    if (!plugged_) continue;
    faults_.maybe_corrupt(frame);
    deliver_to_client(platform_.receive(frame, now), now);
  }
  deliver_to_client(platform_.tick(now), now);
  timer_ = scheduler_.call_at(now + period_, [this] { step(); });
}

void LoopbackClient::deliver_to_client(std::vector<std::uint8_t> bytes, rt::TimePoint now) {
  if (bytes.empty() || !plugged_) return;
  faults_.maybe_corrupt(bytes);
  core_.on_bytes(bytes, now);
}

}  // namespace jaus::clearpath::sim
