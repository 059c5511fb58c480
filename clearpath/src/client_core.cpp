#include "jaus/clearpath/client_core.hpp"

#include <algorithm>

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

void ClientCore::send(AnyMessage message, CommandCallback done) {
  const auto type = type_of(message);
  if (!type || kind_of(*type) == MessageKind::data) {
    if (done) done(CommandOutcome{CommandError::not_encodable, 0, 0});
    return;
  }
  queue_.push_back(Pending{std::move(message), *type, std::move(done), 0, std::nullopt});
}

void ClientCore::subscribe(AnyMessage request, CommandCallback done) {
  const auto type = type_of(request);
  if (!type || kind_of(*type) != MessageKind::request) {
    if (done) done(CommandOutcome{CommandError::not_encodable, 0, 0});
    return;
  }
  std::uint8_t selector = 0;
  visit(
      [&](const auto& m) {
        if constexpr (requires { m.mount; }) selector = m.mount;
        if constexpr (requires { m.joint; }) selector = m.joint;
      },
      request);
  subscriptions_[{*type, selector}] = request;
  send(std::move(request), std::move(done));
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
  send(std::move(cancel));
}

void ClientCore::set_setpoint(AnyMessage command, rt::TimePoint now) {
  const auto type = type_of(command);
  if (!type || kind_of(*type) != MessageKind::command) return;
  auto [it, inserted] = setpoints_.try_emplace(*type, Setpoint{command, now});
  if (!inserted) {
    if (it->second.fresh) ++counters_.setpoints_replaced;  // the older one never went out
    it->second = Setpoint{std::move(command), now};
  }
}

void ClientCore::stop_setpoint(AnyMessage stop, rt::TimePoint now) {
  const auto type = type_of(stop);
  if (!type || kind_of(*type) != MessageKind::command) return;
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
  if (!raw_.empty()) {
    frame = std::move(raw_.front());
    raw_.pop_front();
    ++counters_.frames_sent;
    return frame;
  }
  while (!queue_.empty()) {
    Pending pending = std::move(queue_.front());
    queue_.pop_front();
    const std::uint32_t ts = next_timestamp(now);
    if (!append_encoded(frame, Envelope{{config_.version, ts, 0, pending.type}, pending.message})) {
      finish(pending, CommandOutcome{CommandError::not_encodable, 0, pending.attempts});
      frame.clear();
      continue;
    }
    ++pending.attempts;
    pending.deadline = now + config_.ack_timeout;
    in_flight_.emplace(Key{pending.type, ts}, std::move(pending));
    ++counters_.frames_sent;
    return frame;
  }
  return frame;
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
  for (auto it = in_flight_.begin(); it != in_flight_.end();) {
    if (!it->second.deadline || *it->second.deadline > now) {
      ++it;
      continue;
    }
    Pending pending = std::move(it->second);
    it = in_flight_.erase(it);
    ++counters_.timeouts;
    if (pending.attempts < config_.max_attempts) {
      ++counters_.retries;
      set_state(ConnectionState::retrying);
      queue_.push_front(std::move(pending));  // goes out again with a new timestamp
    } else {
      finish(pending, CommandOutcome{CommandError::no_ack, 0, pending.attempts});
      mark_down(now);  // nothing got through: reconnect
      return;
    }
  }
  // Data expected but none for too long: the link is dead.
  if (!subscriptions_.empty() && now - last_rx_ > config_.data_silence) mark_down(now);
}

void ClientCore::on_bytes(std::span<const std::uint8_t> bytes, rt::TimePoint now) {
  parser_.feed(bytes);
  while (auto event = parser_.poll()) {
    if (const auto* frame = std::get_if<Frame>(&*event)) handle_frame(*frame, now);
  }
}

void ClientCore::handle_frame(const Frame& frame, rt::TimePoint now) {
  ++counters_.frames_received;
  last_rx_ = now;
  auto envelope = decode(frame, Direction::from_platform);
  if (!envelope) {
    ++counters_.decode_errors;  // e.g. a type the document lacks: ignore it, never fail
    return;
  }
  const auto* ack = envelope->message.get_if<Ack>();
  if (ack == nullptr) {
    ++counters_.data_received;
    if (on_data_) on_data_(*envelope);
    return;
  }
  const auto it = in_flight_.find(Key{frame.header.type, frame.header.timestamp});
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
    if (pending.attempts < config_.max_attempts) {
      ++counters_.retries;
      set_state(ConnectionState::retrying);
      pending.deadline.reset();
      queue_.push_front(std::move(pending));
    } else {
      finish(pending, CommandOutcome{CommandError::no_ack, ack->result, pending.attempts});
    }
    return;
  }
  ++counters_.acks_refused;  // a definite refusal: report, do not retry
  finish(pending, CommandOutcome{CommandError::refused, ack->result, pending.attempts});
}

void ClientCore::fail_all(CommandError error) {
  for (auto& [key, pending] : in_flight_) finish(pending, CommandOutcome{error, 0, pending.attempts});
  in_flight_.clear();
  for (auto& pending : queue_) finish(pending, CommandOutcome{error, 0, pending.attempts});
  queue_.clear();
  raw_.clear();
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
  for (const auto& [key, request] : subscriptions_)
    queue_.push_back(Pending{request, key.first, nullptr, 0, std::nullopt});
}

void ClientCore::on_connected(rt::TimePoint now) {
  if (counters_.frames_received > 0 || counters_.frames_sent > 0) ++counters_.reconnects;
  parser_.reset();
  last_rx_ = now;
  wants_reconnect_ = false;
  backoff_ = config_.backoff_initial;
  resubscribe();
  // No setpoint survives a disconnection (mark_down): a reconnect re-arms nothing.
  set_state(ConnectionState::connected);
}

void ClientCore::mark_down(rt::TimePoint now) {
  fail_all(CommandError::link_down);
  // Safety: a reconnect never re-arms an old setpoint; the application sets a
  // new one when it wants motion again.
  counters_.setpoints_dropped += setpoints_.size();
  setpoints_.clear();
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
  mark_down(now);
}

void ClientCore::reconnect_started(rt::TimePoint) {
  wants_reconnect_ = false;
  set_state(ConnectionState::connecting);
}

void ClientCore::open_failed(rt::TimePoint now) { mark_down(now); }

}  // namespace jaus::clearpath
