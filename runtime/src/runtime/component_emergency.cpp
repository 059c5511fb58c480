// Emergency: the latch a component follows (its own or one shared by the
// moving components), Set and Clear Emergency from JAUS and holds from the
// hardware. Safety: entering Emergency always stops (Component::transition).
#include "jaus/runtime/component.hpp"

namespace jaus::rt {

// Safety: the one place a component enters or leaves Emergency, following its
// latch. Idempotent: a shared latch calls every member on every change.
void Component::follow_emergency() {
  const PrimaryStatus state = lifecycle_.state();
  if (state == PrimaryStatus::shutdown) return;
  // A Set or Clear Emergency names its sender; anything else (a local hold,
  // a restored or shared latch) says who holds it.
  const Address& sender = emergency_->last_changed_by();
  const Address by = sender.is_valid() ? sender : config_.address;
  const std::string cause = sender.is_valid() ? std::string()
                            : emergency_->active() ? "held by " + emergency_->describe_holders()
                                                   : std::string("no longer held");
  if (emergency_->active() && state != PrimaryStatus::emergency) {
    transition(LifecycleEvent::emergency_set, by, cause);
  } else if (!emergency_->active() && state == PrimaryStatus::emergency) {
    transition(LifecycleEvent::emergency_cleared, by, cause);
    // The hardware spoke while the emergency interrupted the wait for it.
    if (lifecycle_.state() == PrimaryStatus::initialize && !waiting_for_hardware_)
      transition(LifecycleEvent::init_succeeded, config_.address);
  }
}

void Component::hold_hardware_emergency(std::string_view cause) {
  // A hardware stop can flap (or be toggled through a platform a peer reaches): limited like remote input.
  if (emergency_->hold_local(cause))
    log_repeated({"emergency Stops from the hardware", kNoteworthyBurst}, LogLevel::warn,
                 [&] { return "emergency Stop from the hardware: " + std::string(cause); });
}

void Component::release_hardware_emergency(std::string_view cause) {
  switch (emergency_->release_local(cause)) {
    case EmergencyLatch::ClearResult::not_a_holder:
    case EmergencyLatch::ClearResult::refused:  // (only JAUS clears are refused)
      return;
    case EmergencyLatch::ClearResult::still_held:
      log_repeated({"hardware emergencies cleared", kNoteworthyBurst}, LogLevel::info, [&] {
        return "hardware emergency cleared (" + std::string(cause) + "); still held by " +
               emergency_->describe_holders();
      });
      return;
    case EmergencyLatch::ClearResult::released_last:
      log_repeated({"hardware emergencies cleared", kNoteworthyBurst}, LogLevel::info,
                   [&] { return "hardware emergency cleared: " + std::string(cause); });
      return;
  }
}

void Component::on_set_emergency(const Header& h, const msg::SetEmergency& m) {
  if ((m.emergency_code & 0x1) == 0) {
    log_repeated("Set Emergency without the Stop bit ignored", LogLevel::warn,
                 [&] { return "Set Emergency from " + h.source.to_string() + " without the Stop bit ignored"; });
    return;
  }
  if (standing_ == SenderStanding::unrecorded) {
    // Obeyed, fail safe: the node cannot tie this ID to a sender, so the hold
    // is the latch's unnamed one (as its overflow), released only locally.
    ++counters_.unrecorded_emergencies;
    const bool first = emergency_->hold_unrecorded();
    log_repeated(first ? Repeated{"emergency Stop set", kNoteworthyBurst} : Repeated{"repeated Set Emergency"},
                 LogLevel::warn, [&] {
                   return "emergency Stop set by " + h.source.to_string() + ", " +
                          std::string(to_string(standing_)) + ": held until cleared locally";
                 });
    return;
  }
  const bool first = emergency_->set(h.source);  // every member follows (follow_emergency)
  if (first) {
    log_repeated({"emergency Stop set", kNoteworthyBurst}, LogLevel::warn,
                 [&] { return "emergency Stop set by " + h.source.to_string(); });
    return;
  }
  // Already held: the platform is already stopped; nothing changes, and a
  // flood of repeats is one line and a count per window.
  log_repeated("repeated Set Emergency", LogLevel::warn, [&] {
    return "emergency Stop set by " + h.source.to_string() + " (already in Emergency" +
           (emergency_->overflowed() ? "; holders beyond the recorded ones hold it until cleared locally" : "") + ")";
  });
}

void Component::on_clear_emergency(const Header& h, const msg::ClearEmergency& m) {
  if ((m.emergency_code & 0x1) == 0) {
    log_repeated("Clear Emergency without the Stop bit ignored", LogLevel::warn,
                 [&] { return "Clear Emergency from " + h.source.to_string() + " without the Stop bit ignored"; });
    return;
  }
  if (standing_ == SenderStanding::unrecorded) {
    // Not trusted to be the holder it names: the hold stays (its own, if it
    // set one, is unnamed and released only locally).
    ++counters_.refused_clears;
    return refuse_for_standing(h, "Clear Emergency");
  }
  switch (emergency_->clear(h.source)) {  // on the last one, every member follows
    case EmergencyLatch::ClearResult::not_a_holder:
      ++counters_.refused_clears;
      log_repeated("Clear Emergency from a non-holder refused", LogLevel::warn,
                   [&] { return "Clear Emergency from " + h.source.to_string() + " refused: it holds no emergency"; });
      return;
    case EmergencyLatch::ClearResult::still_held: {
      ++counters_.refused_clears;
      log_repeated("Clear Emergency while others hold it", LogLevel::warn, [&] {
        return "emergency cleared by " + h.source.to_string() + "; still held by " + emergency_->describe_holders();
      });
      return;
    }
    case EmergencyLatch::ClearResult::refused:
      // Its Report Component Status still says Emergency: the OCU sees its clear not taken.
      ++counters_.refused_clears;
      log_repeated("Clear Emergency refused while holds cannot be persisted", LogLevel::error, [&] {
        return "Clear Emergency from " + h.source.to_string() +
               " refused: the emergency holds cannot be persisted (state directory); held until they can be, "
               "or until the local clear";
      });
      return;
    case EmergencyLatch::ClearResult::released_last:
      return;
  }
}

}  // namespace jaus::rt
