#include "stop_paths.hpp"

namespace jaus::conform::detail {

namespace {

// A Reset re-initialises the component: this long in Initialize and it is
// taken as stuck there.
constexpr rt::Duration kInitialiseLimit = std::chrono::seconds(5);
constexpr rt::Duration kStatusPollPeriod = std::chrono::milliseconds(100);

// Why a stop or the way back could not be made (the path is then not judged).
Expected<void> not_made(std::string why, ErrorCode code = ErrorCode::refused) {
  return unexpected(make_error(code, std::move(why)));
}

}  // namespace

std::string path_text(StopPath path) {
  switch (path) {
    case StopPath::standby:
      return "Standby";
    case StopPath::emergency:
      return "Set Emergency";
    case StopPath::reset:
      return "Reset";
    case StopPath::release:
      return "Release Component Control";
    case StopPath::takeover:
      return "a takeover by a higher authority";
  }
  return "?";
}

std::string way_back_text(StopPath path) {
  switch (path) {
    case StopPath::standby:
      return "Resume";
    case StopPath::emergency:
      return "Clear Emergency";
    case StopPath::reset:
      return "the end of re-initialisation";
    case StopPath::release:
    case StopPath::takeover:
      return "control granted again";
  }
  return "?";
}

Expected<msg::PrimaryStatus> state_after_initialising(CaseContext& c) {
  const auto deadline = c.session.clock().now() + kInitialiseLimit;
  for (;;) {
    auto state = primary_status(c);
    if (!state || *state != msg::PrimaryStatus::initialize || c.session.clock().now() >= deadline) return state;
    c.session.run_for(kStatusPollPeriod);
  }
}

StopAlong::StopAlong(CaseContext& c, StopPath path) : c_(c), path_(path) {
  if (path_ == StopPath::takeover) {
    auto own = ask<msg::ReportComponentAuthority>(c_, msg::QueryComponentAuthority{});
    if (!own) {
      why_not_ = own.error().message();
      return;
    }
    if (own->authority >= 254) {
      why_not_ = "its authority is " + std::to_string(own->authority) + ": no two authorities above it";
      return;
    }
    authority_ = static_cast<std::uint8_t>(own->authority + 1);
  }
  control_.emplace(c_, authority_);
  if (!control_->granted()) why_not_ = "control not granted (" + control_->why() + ")";
}

Expected<void> StopAlong::stop() {
  switch (path_) {
    case StopPath::standby:
      send(c_, msg::Standby{});
      break;
    case StopPath::emergency:
      send(c_, msg::SetEmergency{{1}}, priority::kSafetyCritical);
      break;
    case StopPath::reset: {
      send(c_, msg::Reset{});
      auto state = state_after_initialising(c_);
      if (!state) return not_made("after Reset, " + state.error().message(), state.error().code);
      break;
    }
    case StopPath::release:
      control_->release();
      break;
    case StopPath::takeover: {
      auto second = c_.second();
      if (!second) return unexpected(second.error());
      taken_over_by_.emplace(c_, static_cast<std::uint8_t>(authority_ + 1), **second);
      if (!taken_over_by_->granted())
        return not_made("the second OCU's authority " + std::to_string(authority_ + 1) + " was not granted (" +
                        taken_over_by_->why() + ")");
      break;
    }
  }
  return {};
}

Expected<void> StopAlong::come_back() {
  switch (path_) {
    case StopPath::standby:
      send(c_, msg::Resume{});
      return {};
    case StopPath::emergency:
      send(c_, msg::ClearEmergency{{1}}, priority::kSafetyCritical);  // never left set
      // The RA 3.3 implementation's Clear Emergency always goes to Standby
      // (docs/wire-format.md, "Interoperability").
      if (c_.profile == Profile::openjaus) send(c_, msg::Resume{});
      return {};
    case StopPath::reset: {
      // Control may or may not outlive a re-initialisation (Part 3 does not
      // say): asked again, a controller keeps it.
      if (!control_->ask_again()) return not_made("control not granted after Reset (" + control_->why() + ")");
      auto state = primary_status(c_);
      if (!state) return not_made("after Reset, " + state.error().message(), state.error().code);
      if (*state == msg::PrimaryStatus::standby) send(c_, msg::Resume{});
      return {};
    }
    case StopPath::release:
    case StopPath::takeover:
      taken_over_by_.reset();  // the second OCU releases what it took
      if (!control_->ask_again()) return not_made("control not granted again (" + control_->why() + ")");
      return {};
  }
  return {};
}

}  // namespace jaus::conform::detail
