#include "jaus/clearpath/client_core.hpp"

#include <algorithm>
#include <cstdio>

namespace jaus::clearpath {

std::string_view to_string(ConnectionState state) {
  switch (state) {
    case ConnectionState::down: return "down";
    case ConnectionState::connecting: return "connecting";
    case ConnectionState::connected: return "connected";
    case ConnectionState::retrying: return "retrying";
  }
  return "unknown";
}

ClientCore::ClientCore(ClientConfig config) : config_(config), backoff_(config.backoff_initial) {}

std::uint32_t ClientCore::next_timestamp(rt::TimePoint now) {
  if (!epoch_set_) {
    epoch_ = now;
    epoch_set_ = true;
  }
  // Milliseconds since start, but strictly increasing and unique so every
  // ACK matches exactly one message.
  const auto ms = static_cast<std::uint32_t>(
      std::chrono::duration_cast<std::chrono::milliseconds>(now - epoch_).count());
  last_timestamp_ = std::max(ms, last_timestamp_ + 1);
  return last_timestamp_;
}

namespace {

// A request's subscription field: 0 a single reply, kCancelSubscription a
// cancel, else a rate; nullopt for a message without one.
std::optional<std::uint16_t> subscription_field(const AnyMessage& message) {
  std::optional<std::uint16_t> field;
  visit([&](const auto& m) { if constexpr (requires { m.subscription; }) field = m.subscription; }, message);
  return field;
}

bool is_subscription_setting(const AnyMessage& message) {
  const auto field = subscription_field(message);
  return field && *field != 0 && *field != kCancelSubscription;
}

// Every id of `older` is among those of `newer` (channels, joints).
template <class Record, class Id>
bool ids_covered(const std::vector<Record>& newer, const std::vector<Record>& older, Id Record::*id) {
  return std::all_of(older.begin(), older.end(), [&](const Record& o) {
    return std::any_of(newer.begin(), newer.end(), [&](const Record& n) { return n.*id == o.*id; });
  });
}

// Whether `newer` makes `older` (same type and selector) pointless to write:
// everything `older` would set, `newer` sets too.
bool covers(const AnyMessage& newer, const AnyMessage& older) {
  if (const auto* n = newer.get_if<SetGpioOutput>()) return (older.get<SetGpioOutput>().mask & ~n->mask) == 0;
  if (const auto* n = newer.get_if<SetGpioDirection>()) return (older.get<SetGpioDirection>().mask & ~n->mask) == 0;
  if (const auto* n = newer.get_if<SetAnalogOutputs>())
    return ids_covered(n->channels, older.get<SetAnalogOutputs>().channels, &AnalogOutputChannel::channel);
  if (const auto* n = newer.get_if<SetAbsoluteJoints>())
    return ids_covered(n->joints, older.get<SetAbsoluteJoints>().joints, &AbsoluteJointTarget::joint);
  if (newer.get_if<SetRelativeJoints>() != nullptr) return false;  // deltas add up: each one counts
  // Requests: a single reply (0) leaves the subscription alone (spec,
  // "Subscriptions"), so it neither replaces a rate or cancel nor is
  // answered by one.
  const auto newer_field = subscription_field(newer), older_field = subscription_field(older);
  const auto once = [](const std::optional<std::uint16_t>& field) {
    return field ? std::optional<bool>(*field == 0) : std::nullopt;
  };
  return once(newer_field) == once(older_field);
}

}  // namespace

ClientCore::Kind ClientCore::kind_of_message(std::uint16_t type, const AnyMessage& message) {
  Kind kind{type, 0};
  visit(
      [&](const auto& m) {
        if constexpr (requires { m.mount; }) kind.selector = m.mount;
        if constexpr (requires { m.joint; }) kind.selector = m.joint;
      },
      message);
  return kind;
}

void ClientCore::send(AnyMessage message, CommandCallback done) {
  const auto type = type_of(message);
  if (!type || kind_of(*type) == MessageKind::data) {
    if (done) done(CommandOutcome{CommandError::not_encodable, 0, 0});
    return;
  }
  const Kind kind = kind_of_message(*type, message);
  // Safety: the safety word is never refused; it replaces its own waiting
  // one, so it cannot grow the queue.
  enqueue(Pending(std::move(message), kind, std::move(done)), *type != SetSafetySystem::kType);
}

bool ClientCore::enqueue(Pending pending, bool bounded) {
  const auto replaces = [&](const Pending& waiting) {
    return waiting.kind == pending.kind && covers(pending.message, waiting.message);
  };
  const auto replaced = static_cast<std::size_t>(std::count_if(queue_.begin(), queue_.end(), replaces));
  if (bounded && waiting_commands() - replaced >= config_.max_waiting_commands) {
    ++counters_.commands_refused_full;
    finish(pending, CommandOutcome{CommandError::queue_full, 0, 0});
    return false;
  }
  // Latest wins; the newer one goes to the back, keeping the order in which
  // commands were sent. Callbacks run last, on a consistent queue (one may send).
  std::vector<Pending> older;
  for (auto it = queue_.begin(); it != queue_.end();) {
    if (!replaces(*it)) {
      ++it;
      continue;
    }
    older.push_back(std::move(*it));
    it = queue_.erase(it);
  }
  queue_.push_back(std::move(pending));
  for (auto& o : older) supersede(o);
  return true;
}

void ClientCore::supersede(Pending& pending) {
  ++counters_.commands_superseded;
  finish(pending, CommandOutcome{CommandError::superseded, 0, pending.attempts});
}

void ClientCore::supersede_for_setpoint(const AnyMessage& setpoint, std::uint16_t type) {
  const Kind kind = kind_of_message(type, setpoint);
  // Safety: a setpoint is written before any waiting command, so an older
  // command of its kind sent with ACK would land after it (a stale motion
  // after a zero). Waiting ones are dropped; one in flight was written
  // before the setpoint, so it may be answered, but it is never retried.
  for (auto& [key, pending] : in_flight_)
    if (pending.kind == kind && covers(setpoint, pending.message)) pending.stale = true;
  std::vector<Pending> older;
  for (auto it = queue_.begin(); it != queue_.end();) {
    if (it->kind != kind || !covers(setpoint, it->message)) {
      ++it;
      continue;
    }
    older.push_back(std::move(*it));
    it = queue_.erase(it);
  }
  for (auto& o : older) supersede(o);
}

void ClientCore::subscribe(AnyMessage request, CommandCallback done) {
  const auto type = type_of(request);
  if (!type || kind_of(*type) != MessageKind::request) {
    if (done) done(CommandOutcome{CommandError::not_encodable, 0, 0});
    return;
  }
  const Kind kind = kind_of_message(*type, request);
  AnyMessage kept = request;
  // Refused when full: then it is not kept either, or a reconnect would
  // subscribe to what the application was told failed.
  if (enqueue(Pending(std::move(request), kind, std::move(done)), true)) {
    subscriptions_[{kind.type, kind.selector}] = std::move(kept);
    resubscribe_at_.erase(kind);  // the application's own request stands instead
  }
}

void ClientCore::unsubscribe(std::uint16_t request_type, std::uint8_t selector) {
  const auto it = subscriptions_.find({request_type, selector});
  if (it == subscriptions_.end()) return;
  AnyMessage cancel = it->second;
  visit(
      [](auto& m) {
        if constexpr (requires { m.subscription; }) m.subscription = kCancelSubscription;
      },
      cancel);
  subscriptions_.erase(it);
  resubscribe_at_.erase(Kind{request_type, selector});
  // Never refused: a subscription the application gave up must end, and the
  // cancel replaces any waiting request of its kind.
  enqueue(Pending(std::move(cancel), Kind{request_type, selector}), false);
}

void ClientCore::set_setpoint(AnyMessage command, rt::TimePoint now) {
  const auto type = type_of(command);
  if (!type || kind_of(*type) != MessageKind::command) return;
  supersede_for_setpoint(command, *type);
  auto [it, inserted] = setpoints_.try_emplace(*type, Setpoint{command, now});
  if (!inserted) {
    if (it->second.fresh) ++counters_.setpoints_replaced;  // the older one never went out
    it->second = Setpoint{std::move(command), now};
  }
}

void ClientCore::stop_setpoint(AnyMessage stop, rt::TimePoint now) {
  const auto type = type_of(stop);
  if (!type || kind_of(*type) != MessageKind::command) return;
  supersede_for_setpoint(stop, *type);
  Setpoint setpoint{std::move(stop), now};
  setpoint.stop_once = true;
  setpoints_.insert_or_assign(*type, std::move(setpoint));
}

void ClientCore::clear_setpoint(std::uint16_t type) { setpoints_.erase(type); }

std::vector<std::uint8_t> ClientCore::take_frame(rt::TimePoint now) {
  std::vector<std::uint8_t> frame;
  if (state_ != ConnectionState::connected && state_ != ConnectionState::retrying) return frame;

  // Setpoints first: a fresh one at once, the current one again every period.
  // Safety: a setpoint older than setpoint_max_age is never written again
  // (its stream ends and the platform's watchdog stops the platform), and a
  // stop is written once and ends its stream.
  for (auto it = setpoints_.begin(); it != setpoints_.end();) {
    auto& [type, setpoint] = *it;
    if (!setpoint.stop_once && config_.setpoint_max_age.count() > 0 && now - setpoint.set_at > config_.setpoint_max_age) {
      ++counters_.setpoints_expired;
      it = setpoints_.erase(it);
      continue;
    }
    if (!setpoint.fresh && now - setpoint.last_sent < config_.setpoint_period) {
      ++it;
      continue;
    }
    // Suppress the ACK: the stream itself is the retry mechanism.
    const Envelope e{{config_.version, next_timestamp(now), kFlagSuppressAck, type}, setpoint.message};
    const bool encoded = append_encoded(frame, e).has_value();
    if (!encoded || setpoint.stop_once) {
      setpoints_.erase(it);  // a stop goes once; one that cannot be encoded is dropped rather than looped on
      if (!encoded) return {};
    } else {
      setpoint.fresh = false;
      setpoint.last_sent = now;
    }
    ++counters_.setpoints_sent;
    ++counters_.frames_sent;
    return frame;
  }
  // The safety word before the cancels of a reconnect and every other command.
  auto next = next_waiting();
  if (!raw_.empty() && (next == queue_.end() || next->kind.type != SetSafetySystem::kType)) {
    frame = std::move(raw_.front());
    raw_.pop_front();
    ++counters_.frames_sent;
    return frame;
  }
  for (; next != queue_.end(); next = next_waiting()) {
    Pending pending = std::move(*next);
    queue_.erase(next);
    const std::uint32_t ts = next_timestamp(now);
    if (!append_encoded(frame, Envelope{{config_.version, ts, 0, pending.kind.type}, pending.message})) {
      finish(pending, CommandOutcome{CommandError::not_encodable, 0, pending.attempts});
      frame.clear();
      continue;
    }
    if (!pending.first_sent) pending.first_sent = now;
    ++pending.attempts;
    pending.deadline = now + config_.ack_timeout;
    in_flight_.emplace(AckKey{pending.kind.type, ts}, std::move(pending));
    ++counters_.frames_sent;
    return frame;
  }
  // Safety: the probe goes last, only when nothing else is to be written now,
  // so it never delays a stop, the safety word or a command (on a serial line
  // a stop that comes while a probe is being written waits for its 16 bytes,
  // about 1.4 ms at 115200 baud, as behind any frame). It is not a queued
  // command: it takes no kind's turn (one in flight per kind) and replaces
  // nothing; its ACK is matched by its own key.
  if (probe_due(now)) return take_probe(now);
  return frame;
}

bool ClientCore::probe_due(rt::TimePoint now) const {
  if (config_.probe_period.count() <= 0) return false;
  // Since the connection, the last ACK or the last probe, whichever is newest:
  // while commands are being acknowledged, no probe goes.
  rt::TimePoint since = connected_at_;
  if (last_ack_ && *last_ack_ > since) since = *last_ack_;
  if (last_probe_ && *last_probe_ > since) since = *last_probe_;
  return now - since >= config_.probe_period;
}

std::vector<std::uint8_t> ClientCore::take_probe(rt::TimePoint now) {
  std::vector<std::uint8_t> frame;
  const std::uint32_t ts = next_timestamp(now);
  // A single reply (subscription 0): it leaves every subscription alone.
  if (!append_encoded(frame, Envelope{{config_.version, ts, 0, RequestEcho::kType}, RequestEcho{}})) return {};
  probe_key_ = AckKey{RequestEcho::kType, ts};
  last_probe_ = now;
  if (!unanswered_probe_) {
    unanswered_probe_ = now;
    probes_sent_at_unanswered_ = counters_.probes_sent;
  }
  ++counters_.probes_sent;
  ++counters_.frames_sent;
  return frame;
}

bool ClientCore::in_flight(const Kind& kind) const {
  return std::any_of(in_flight_.begin(), in_flight_.end(), [&](const auto& entry) { return entry.second.kind == kind; });
}

std::deque<ClientCore::Pending>::iterator ClientCore::next_waiting() {
  // Safety: Set Safety System first (retries too); otherwise the oldest whose
  // kind has nothing in flight.
  const auto safety = std::find_if(queue_.begin(), queue_.end(), [&](const Pending& p) {
    return p.kind.type == SetSafetySystem::kType && !in_flight(p.kind);
  });
  if (safety != queue_.end()) return safety;
  return std::find_if(queue_.begin(), queue_.end(), [&](const Pending& p) { return !in_flight(p.kind); });
}

bool ClientCore::answered_since_first_send(const Pending& pending) const {
  return last_ack_ && pending.first_sent && *last_ack_ >= *pending.first_sent;
}

// False when the command used its attempts and no ACK to anything came back
// since its first send: the platform does not hear us, and the caller takes
// the link down. Otherwise the platform answers other commands (only this
// one's frames or ACKs were lost, as on a noisy line): it finishes no_ack and
// the link stays up, so one unlucky request does not fail a working platform;
// a subscription, being wanted state, is asked again after resubscribe_delay.
bool ClientCore::retry_or_finish(Pending pending, std::uint16_t result, rt::TimePoint now) {
  // A newer command of its kind waits (or a setpoint of its kind went out):
  // resending the older one would land after it, so it ends here.
  const bool newer = std::any_of(queue_.begin(), queue_.end(), [&](const Pending& waiting) {
    return waiting.kind == pending.kind && covers(waiting.message, pending.message);
  });
  if (pending.stale || newer) {
    supersede(pending);
    return true;
  }
  if (pending.attempts >= config_.max_attempts) {
    ++counters_.commands_unanswered;
    const bool heard = answered_since_first_send(pending);
    if (heard && is_subscription_setting(pending.message) &&
        subscriptions_.contains({pending.kind.type, pending.kind.selector}))
      resubscribe_at_[pending.kind] = now + config_.resubscribe_delay;
    finish(pending, CommandOutcome{CommandError::no_ack, result, pending.attempts});
    return heard;
  }
  ++counters_.retries;
  set_state(ConnectionState::retrying);
  pending.deadline.reset();
  // At the front: it is older than everything waiting, and a newer one of its
  // kind that does not cover it waits behind it (one in flight per kind).
  queue_.push_front(std::move(pending));  // goes out again with a new timestamp
  return true;
}

void ClientCore::finish(Pending& pending, CommandOutcome outcome) {
  outcome.attempts = pending.attempts;
  if (pending.done) {
    auto done = std::move(pending.done);
    pending.done = nullptr;
    done(outcome);
  }
}

void ClientCore::tick(rt::TimePoint now) {
  if (state_ != ConnectionState::connected && state_ != ConnectionState::retrying) return;
  // Taken out first: the callbacks that retry_or_finish runs may send.
  std::vector<Pending> expired;
  for (auto it = in_flight_.begin(); it != in_flight_.end();) {
    if (!it->second.deadline || *it->second.deadline > now) {
      ++it;
      continue;
    }
    expired.push_back(std::move(it->second));
    it = in_flight_.erase(it);
  }
  bool unheard = false;
  for (auto& pending : expired) {
    ++counters_.timeouts;
    if (!retry_or_finish(std::move(pending), 0, now)) unheard = true;
  }
  if (unheard) {
    // Nothing got through: reconnect.
    mark_unheard(now, "a command went unanswered after " + std::to_string(config_.max_attempts) +
                          " attempts and nothing was acknowledged since its first send");
    return;
  }
  // Safety: a platform that no longer hears us (a one-way line: its data may
  // still flow) takes the link down, so the owner stops relying on it (the
  // bridge's driver goes to Failure) even while only setpoints, which are
  // never acknowledged, are being written.
  if (unanswered_probe_ && now - *unanswered_probe_ >= config_.probe_timeout) {
    const bool data_flows = last_rx_ > *unanswered_probe_;
    mark_unheard(now, "no ACK to anything for " + std::to_string(config_.probe_timeout.count()) + " ms (" +
                          std::to_string(counters_.probes_sent - probes_sent_at_unanswered_) + " probes)" +
                          (data_flows ? " while its data still arrives" : ""));
    return;
  }
  rerequest_due_subscriptions(now);
  // Data expected but none for too long: the link is dead.
  if (!subscriptions_.empty() && now - last_rx_ > config_.data_silence)
    mark_down(now, "no frame from the platform for " + std::to_string(config_.data_silence.count()) + " ms; link down");
}

void ClientCore::rerequest_due_subscriptions(rt::TimePoint now) {
  for (auto it = resubscribe_at_.begin(); it != resubscribe_at_.end();) {
    if (it->second > now) {
      ++it;
      continue;
    }
    const Kind kind = it->first;
    it = resubscribe_at_.erase(it);
    // subscribe(), unsubscribe() and a reconnect drop the entry, so the
    // subscription is still wanted and nothing asks for it now.
    const auto wanted = subscriptions_.find({kind.type, kind.selector});
    if (wanted == subscriptions_.end()) continue;
    ++counters_.subscriptions_rerequested;
    // Never refused, like the re-requests of a reconnect: one per kind at most.
    enqueue(Pending(wanted->second, kind), false);
  }
}

void ClientCore::on_bytes(std::span<const std::uint8_t> bytes, rt::TimePoint now) {
  parser_.feed(bytes);
  while (auto event = parser_.poll()) {
    if (const auto* frame = std::get_if<Frame>(&*event))
      handle_frame(*frame, now);
    else if (on_problem_)
      on_problem_(std::get<RejectedBytes>(*event).to_error());
  }
}

void ClientCore::handle_frame(const Frame& frame, rt::TimePoint now) {
  ++counters_.frames_received;
  last_rx_ = now;
  auto envelope = decode(frame, Direction::from_platform);
  if (!envelope) {
    ++counters_.decode_errors;  // e.g. a type the document lacks: ignore it, never fail
    if (on_problem_) {
      Error error = envelope.error();
      char type[40];
      std::snprintf(type, sizeof type, "frame of type 0x%04X", frame.header.type);
      error.detail = error.detail.empty() ? std::string(type) : type + (": " + error.detail);
      on_problem_(error);
    }
    return;
  }
  const auto* ack = envelope->message.get_if<Ack>();
  if (ack == nullptr) {
    if (hearing_unconfirmed_) {
      ++counters_.data_withheld;  // talks, but may not listen: not taken for a live platform yet
      return;
    }
    ++counters_.data_received;
    if (on_data_) on_data_(*envelope);
    return;
  }
  // Any ACK, even "bad checksum" or one we cannot match: the platform hears us.
  last_ack_ = now;
  unanswered_probe_.reset();
  hearing_unconfirmed_ = false;
  const AckKey key{frame.header.type, frame.header.timestamp};
  if (probe_key_ && *probe_key_ == key) {
    ++counters_.probes_answered;
    probe_key_.reset();
    return;
  }
  const auto it = in_flight_.find(key);
  if (it == in_flight_.end()) {
    ++counters_.acks_unmatched;
    return;
  }
  Pending pending = std::move(it->second);
  in_flight_.erase(it);
  if (ack->result == 0) {
    ++counters_.acks_ok;
    if (state_ == ConnectionState::retrying && in_flight_.empty()) set_state(ConnectionState::connected);
    finish(pending, CommandOutcome{});
    return;
  }
  if ((ack->result & kAckBadChecksum) != 0) {
    // The platform did not get it: resend with a new timestamp.
    ++counters_.bad_checksum_acks;
    retry_or_finish(std::move(pending), ack->result, now);  // this ACK shows the platform hears us
    return;
  }
  ++counters_.acks_refused;  // a definite refusal: report, do not retry
  finish(pending, CommandOutcome{CommandError::refused, ack->result, pending.attempts});
}

void ClientCore::fail_all(CommandError error) {
  // Moved out before any callback runs: a callback may send again.
  auto in_flight = std::move(in_flight_);
  auto queue = std::move(queue_);
  in_flight_.clear();
  queue_.clear();
  raw_.clear();
  for (auto& [key, pending] : in_flight) finish(pending, CommandOutcome{error, 0, pending.attempts});
  for (auto& pending : queue) finish(pending, CommandOutcome{error, 0, pending.attempts});
}

void ClientCore::resubscribe() {
  // Cancel whatever the platform may still send from an earlier session, then
  // ask again for what is wanted. Cancels go without ACK.
  for (const auto& info : message_catalogue()) {
    if (info.kind != MessageKind::request) continue;
    auto cancel = make_message(info.type);
    visit(
        [](auto& m) {
          if constexpr (requires { m.subscription; }) m.subscription = kCancelSubscription;
        },
        *cancel);
    std::vector<std::uint8_t> frame;
    // The timestamp is assigned now; cancels never need matching.
    if (append_encoded(frame, Envelope{{config_.version, next_timestamp(last_rx_), kFlagSuppressAck, info.type}, *cancel}))
      raw_.push_back(std::move(frame));
  }
  // Never refused (the queue is empty after a disconnection). A request of
  // its kind already waiting (the application's own, sent before the link
  // came up) asks for it already: it is not replaced.
  for (const auto& [key, request] : subscriptions_) {
    const Kind kind{key.first, key.second};
    const bool waiting = std::any_of(queue_.begin(), queue_.end(), [&](const Pending& p) { return p.kind == kind; });
    if (!waiting) enqueue(Pending(request, kind), false);
  }
}

void ClientCore::on_connected(rt::TimePoint now) {
  if (counters_.frames_received > 0 || counters_.frames_sent > 0) ++counters_.reconnects;
  parser_.reset();
  last_rx_ = now;
  connected_at_ = now;
  last_probe_.reset();
  probe_key_.reset();
  unanswered_probe_.reset();
  wants_reconnect_ = false;
  backoff_ = config_.backoff_initial;
  resubscribe();
  // No setpoint survives a disconnection (mark_down): a reconnect re-arms nothing.
  set_state(ConnectionState::connected);
}

void ClientCore::mark_unheard(rt::TimePoint now, std::string why) {
  ++counters_.unheard_downs;
  hearing_unconfirmed_ = true;  // until an ACK shows otherwise (handle_frame)
  mark_down(now, "the platform no longer hears us: " + why + "; link down");
}

void ClientCore::mark_down(rt::TimePoint now, std::string reason) {
  down_reason_ = std::move(reason);
  unanswered_probe_.reset();
  fail_all(CommandError::link_down);
  // Safety: a reconnect never re-arms an old setpoint; the application sets a
  // new one when it wants motion again.
  counters_.setpoints_dropped += setpoints_.size();
  setpoints_.clear();
  resubscribe_at_.clear();  // a reconnect asks for every subscription again
  wants_reconnect_ = true;
  reconnect_at_ = now + backoff_;
  backoff_ = std::min(backoff_ * 2, config_.backoff_max);
  set_state(ConnectionState::down);
}

void ClientCore::set_state(ConnectionState state) {
  if (state == state_) return;
  state_ = state;
  if (on_state_) on_state_(state);
}

void ClientCore::on_disconnected(rt::TimePoint now) {
  if (state_ == ConnectionState::down) return;
  mark_down(now, "the connection closed or failed; link down");
}

void ClientCore::reconnect_started(rt::TimePoint) {
  wants_reconnect_ = false;
  set_state(ConnectionState::connecting);
}

void ClientCore::open_failed(rt::TimePoint now) { mark_down(now, "the link could not be opened"); }

}  // namespace jaus::clearpath
