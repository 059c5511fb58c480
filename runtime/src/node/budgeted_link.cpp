#include "jaus/node/budgeted_link.hpp"

#include <algorithm>
#include <chrono>

#include "jaus/core/stop_commands.hpp"

namespace jaus::node {

namespace {

// What travels with the stops so that none overtakes another (core_messages.hpp).
constexpr std::uint16_t kResumeCode = 0x0004;
constexpr std::uint16_t kClearEmergencyCode = 0x0007;

bool is_command(std::uint16_t code) { return (code >> 12) == 0x0; }

// A command that stops what it reaches (a request, not an ACK or NAK of one).
bool halts(const Header& h) {
  if (h.ack_nak == AckNak::ack || h.ack_nak == AckNak::nak) return false;
  return is_stop_command(h.command_code);
}

bool same_stream(const Header& a, const Header& b) {
  return a.source == b.source && a.destination == b.destination && a.command_code == b.command_code;
}

std::size_t fifo_index(SendClass c) { return static_cast<std::size_t>(c) - 1; }

}  // namespace

std::string_view to_string(SendClass send_class) {
  switch (send_class) {
    case SendClass::stop: return "stop";
    case SendClass::command: return "command";
    case SendClass::status: return "status";
    case SendClass::connection: return "connection";
    case SendClass::bulk: return "bulk";
  }
  return "?";
}

std::size_t piece_size_for(const SendBudgetOptions& options) {
  if (!options.enabled()) return kMaxPayloadSize;
  const auto in_50_ms = options.bits_per_second / 8 / 20;
  return static_cast<std::size_t>(std::clamp<std::uint64_t>(in_50_ms, 512, kMaxPayloadSize));
}

SendClass send_class_of(const Header& h, std::size_t packet_size, const SendBudgetOptions& options) {
  const std::uint16_t code = h.command_code;
  if (h.priority >= priority::kSafetyCritical || is_stop_command(code) || code == kClearEmergencyCode ||
      code == kResumeCode)
    return SendClass::stop;
  // A command is never dropped for a newer one: however large, it keeps its
  // place among the commands.
  if (is_command(code)) return SendClass::command;
  if (h.data_flag != DataFlag::single || packet_size > options.bulk_threshold) return SendClass::bulk;
  if (h.service_connection) return SendClass::connection;
  return SendClass::status;
}

BudgetedLink::BudgetedLink(Link& inner, rt::Clock& clock, rt::Scheduler& scheduler, SendBudgetOptions options)
    : inner_(inner),
      clock_(clock),
      scheduler_(scheduler),
      options_(options),
      bytes_per_second_(static_cast<double>(options.bits_per_second) / 8.0),
      burst_(options.burst_bytes > 0 ? static_cast<double>(options.burst_bytes)
                                     : std::max(512.0, bytes_per_second_ * 0.020)),
      tokens_(burst_),
      refilled_at_(clock.now()) {}

BudgetedLink::~BudgetedLink() {
  if (wake_ != rt::kNoTimer) scheduler_.cancel(wake_);
}

void BudgetedLink::transmit(const Header& header, std::span<const std::uint8_t> packet) {
  if (!options_.enabled()) return inner_.transmit(header, packet);
  const rt::TimePoint now = clock_.now();
  refill(now);
  const SendClass send_class = send_class_of(header, packet.size(), options_);
  if (send_class == SendClass::stop) {
    // Safety: a stop never waits behind anything here (docs/safety.md).
    if (halts(header)) drop_commands_to(header.destination);
    send(header, packet, send_class);
    return;
  }
  // Nothing ahead of it and the budget allows: straight through, no copy.
  if (send_class != SendClass::bulk && tokens_ >= 0 && !anything_waiting()) {
    send(header, packet, send_class);
    return;
  }
  offer(send_class, header, packet, now);
  drain();
}

void BudgetedLink::offer(SendClass send_class, const Header& header, std::span<const std::uint8_t> packet,
                         rt::TimePoint now) {
  if (send_class == SendClass::bulk) return offer_bulk(header, packet, now);
  auto& per_class = counters_.classes[static_cast<std::size_t>(send_class)];
  auto& queue = fifo_[fifo_index(send_class)];
  if (send_class == SendClass::connection) {
    // Only the newest report of a connection waits: it takes the older one's
    // place in the queue (so a fast connection does not go to the back).
    const auto older = std::find_if(queue.begin(), queue.end(),
                                    [&](const Waiting& w) { return same_stream(w.header, header); });
    if (older != queue.end()) {
      const std::size_t old_size = older->packet.size();
      if (queued_bytes_[static_cast<std::size_t>(send_class)] - old_size + packet.size() > options_.queue_bytes) {
        ++per_class.dropped;
        return;
      }
      older->header = header;
      older->packet.assign(packet.begin(), packet.end());
      queued_bytes_[static_cast<std::size_t>(send_class)] += packet.size() - old_size;
      counters_.queued_bytes += packet.size() - old_size;
      ++per_class.superseded;
      return;
    }
  }
  if (!fits(send_class, packet.size())) {
    ++per_class.dropped;
    return;
  }
  queue.push_back(Waiting{header, {packet.begin(), packet.end()}, now});
}

void BudgetedLink::offer_bulk(const Header& header, std::span<const std::uint8_t> packet, rt::TimePoint now) {
  auto& per_class = counters_.classes[static_cast<std::size_t>(SendClass::bulk)];
  if (header.data_flag == DataFlag::retransmitted) {
    // One packet of a set sent again on request: it replaces nothing.
    if (!fits(SendClass::bulk, packet.size())) {
      ++per_class.dropped;
      return;
    }
    BulkUnit unit{header, {}, true, true};
    unit.packets.push_back(Waiting{header, {packet.begin(), packet.end()}, now});
    bulk_.push_back(std::move(unit));
    return;
  }
  const bool opens = header.data_flag == DataFlag::first || header.data_flag == DataFlag::single;
  if (!opens) {
    // The rest of a set: after its first packet (dropped with it if that was).
    const auto unit = std::find_if(bulk_.rbegin(), bulk_.rend(), [&](const BulkUnit& u) {
      return !u.complete && same_stream(u.first, header);
    });
    if (unit == bulk_.rend()) {
      ++per_class.dropped;
      return;
    }
    if (!fits(SendClass::bulk, packet.size())) {
      // A set without one of its packets is lost: what waits of it goes too.
      per_class.dropped += 1 + unit->packets.size();
      for (const auto& w : unit->packets) forget(SendClass::bulk, w.packet.size());
      bulk_.erase(std::next(unit).base());
      return;
    }
    unit->packets.push_back(Waiting{header, {packet.begin(), packet.end()}, now});
    unit->complete = header.data_flag == DataFlag::last;
    return;
  }
  // A new set (or big single packet): it replaces the one of its stream that
  // has not started yet; one already on its way is finished first.
  const auto waiting = std::find_if(bulk_.begin(), bulk_.end(), [&](const BulkUnit& u) {
    return !u.started && same_stream(u.first, header);
  });
  if (waiting != bulk_.end()) {
    for (const auto& w : waiting->packets) forget(SendClass::bulk, w.packet.size());
    per_class.superseded += waiting->packets.size();
    bulk_.erase(waiting);
  }
  if (!fits(SendClass::bulk, packet.size())) {
    ++per_class.dropped;
    return;
  }
  BulkUnit unit{header, {}, false, header.data_flag != DataFlag::first};
  unit.packets.push_back(Waiting{header, {packet.begin(), packet.end()}, now});
  bulk_.push_back(std::move(unit));
}

// Safety: a command issued before a stop must not arrive after it and undo
// it (docs/safety.md): the stop went at once, the commands still waiting go.
void BudgetedLink::drop_commands_to(const Address& destination) {
  auto& queue = fifo_[fifo_index(SendClass::command)];
  auto& per_class = counters_.classes[static_cast<std::size_t>(SendClass::command)];
  std::erase_if(queue, [&](const Waiting& w) {
    if (!destination.matches(w.header.destination)) return false;
    forget(SendClass::command, w.packet.size());
    ++per_class.superseded;
    return true;
  });
}

bool BudgetedLink::fits(SendClass send_class, std::size_t bytes) {
  auto& queued = queued_bytes_[static_cast<std::size_t>(send_class)];
  if (queued + bytes > options_.queue_bytes) return false;
  queued += bytes;
  ++counters_.queued_packets;
  counters_.queued_bytes += bytes;
  counters_.most_queued_bytes = std::max(counters_.most_queued_bytes, counters_.queued_bytes);
  return true;
}

void BudgetedLink::forget(SendClass send_class, std::size_t bytes) {
  queued_bytes_[static_cast<std::size_t>(send_class)] -= bytes;
  --counters_.queued_packets;
  counters_.queued_bytes -= bytes;
}

void BudgetedLink::refill(rt::TimePoint now) {
  if (now <= refilled_at_) return;
  const double seconds = std::chrono::duration<double>(now - refilled_at_).count();
  tokens_ = std::min(burst_, tokens_ + seconds * bytes_per_second_);
  refilled_at_ = now;
}

bool BudgetedLink::anything_waiting() const { return counters_.queued_packets > 0; }

void BudgetedLink::send(const Header& header, std::span<const std::uint8_t> packet, SendClass send_class) {
  tokens_ -= static_cast<double>(packet.size() + options_.overhead_bytes);
  auto& per_class = counters_.classes[static_cast<std::size_t>(send_class)];
  ++per_class.sent;
  per_class.bytes_sent += packet.size();
  inner_.transmit(header, packet);
}

void BudgetedLink::sent_after_wait(const Waiting& w, SendClass send_class, rt::TimePoint now) {
  ++counters_.classes[static_cast<std::size_t>(send_class)].waited;
  counters_.longest_wait = std::max(counters_.longest_wait, now - w.since);
  forget(send_class, w.packet.size());
}

std::string BudgetedLink::summary() const {
  std::uint64_t sent = 0, waited = 0, superseded = 0, dropped = 0;
  for (const auto& c : counters_.classes) {
    sent += c.sent;
    waited += c.waited;
    superseded += c.superseded;
    dropped += c.dropped;
  }
  const auto longest = std::chrono::duration_cast<std::chrono::milliseconds>(counters_.longest_wait).count();
  return "send budget " + std::to_string(options_.bits_per_second / 1000) + " kbit/s: " + std::to_string(waited) +
         " of " + std::to_string(sent) + " packets waited (longest " + std::to_string(longest) + " ms), " +
         std::to_string(superseded) + " replaced by newer, " + std::to_string(dropped) + " dropped";
}

void BudgetedLink::flush() {
  if (wake_ != rt::kNoTimer) scheduler_.cancel(wake_);
  wake_ = rt::kNoTimer;
  drain(true);
}

void BudgetedLink::drain(bool whatever_the_budget) {
  const rt::TimePoint now = clock_.now();
  refill(now);
  while (tokens_ >= 0 || whatever_the_budget) {
    // Strictly by class: command, status, connection, then bulk.
    std::deque<Waiting>* queue = nullptr;
    SendClass send_class = SendClass::bulk;
    for (SendClass c : {SendClass::command, SendClass::status, SendClass::connection}) {
      if (!fifo_[fifo_index(c)].empty()) {
        queue = &fifo_[fifo_index(c)];
        send_class = c;
        break;
      }
    }
    if (queue) {
      // The link may send again (e.g. an ACK tracker): take it off the queue first.
      Waiting w = std::move(queue->front());
      queue->pop_front();
      sent_after_wait(w, send_class, now);
      send(w.header, w.packet, send_class);
      continue;
    }
    // The oldest set with a packet here (one whose next packets are still
    // being handed over has none for the moment).
    const auto unit = std::find_if(bulk_.begin(), bulk_.end(), [](const BulkUnit& u) { return !u.packets.empty(); });
    if (unit == bulk_.end()) break;
    unit->started = true;
    Waiting w = std::move(unit->packets.front());
    unit->packets.pop_front();
    if (unit->packets.empty() && unit->complete) bulk_.erase(unit);
    sent_after_wait(w, SendClass::bulk, now);
    send(w.header, w.packet, SendClass::bulk);
  }
  if (whatever_the_budget || tokens_ >= 0 || !anything_waiting() || wake_ != rt::kNoTimer) return;
  // In debt: wake when the debt is paid (at least a microsecond on).
  const double seconds = -tokens_ / bytes_per_second_;
  const auto wait = std::max<rt::Duration>(std::chrono::microseconds(1),
                                           std::chrono::duration_cast<rt::Duration>(
                                               std::chrono::duration<double>(seconds)));
  wake_ = scheduler_.call_at(now + wait, [this] {
    wake_ = rt::kNoTimer;
    drain();
  });
}

}  // namespace jaus::node
