#include "safety_word.hpp"

#include <cstdio>

namespace jaus::bridge::detail {

void SafetyWord::want(std::uint16_t bits) {
  bits &= config_.owned;
  if (bits == wanted_) return;
  // An owned bit that is also a stop input, going clear: held until seen clear.
  unconfirmed_clear_ |= static_cast<std::uint16_t>(wanted_ & ~bits & config_.stop_flags);
  wanted_ = bits;
  write_due_ = true;
}

void SafetyWord::status(std::uint16_t flags) {
  seen_ = flags;
  fresh_ = true;
  if (!started_) {
    // A hold restored at start: the bits an earlier run left are the ones wanted now.
    started_ = true;
    applied_ = static_cast<std::uint16_t>(applied_ | (flags & wanted_ & config_.owned));
  }
  if (in_flight_) return;  // judged once the platform has applied (ACKed) the write
  // Seen after the ACK: a bit still set is the platform's own stop now
  // (foreign_stop takes over); either way the clear is no longer in doubt.
  unconfirmed_clear_ = static_cast<std::uint16_t>(unconfirmed_clear_ & applied_);
  // The platform lost bits of ours (a restart, another client's write), or
  // carries owned bits we did not set (a stop input aside): write ours again.
  const auto lost = static_cast<std::uint16_t>(applied_ & ~flags);
  const auto extra = static_cast<std::uint16_t>(flags & ~applied_ & config_.owned & ~config_.stop_flags);
  if ((lost | extra) != 0) write_due_ = true;
}

void SafetyWord::adopt_owned_bits_seen() {
  if (!seen_) return;
  const auto adopted = static_cast<std::uint16_t>(*seen_ & config_.owned & ~applied_);
  if (adopted == 0) return;
  applied_ = static_cast<std::uint16_t>(applied_ | adopted);
  // Those not wanted go clear, and a stop input among them is confirmed as ours clears.
  unconfirmed_clear_ |= static_cast<std::uint16_t>(adopted & ~wanted_ & config_.stop_flags);
  write_due_ = true;
}

void SafetyWord::status_unavailable() {
  blind_ = true;
  write_due_ = true;
}

void SafetyWord::link_lost() {
  // The last word seen stays: a platform stop it showed is held until the
  // platform, heard again, reports it clear.
  fresh_ = false;
  if (in_flight_) applied_ = static_cast<std::uint16_t>(applied_ & *in_flight_);
  in_flight_.reset();
  write_due_ = true;
}

std::uint16_t SafetyWord::jausd_bits() const { return static_cast<std::uint16_t>(applied_ | in_flight_.value_or(0)); }

std::uint16_t SafetyWord::foreign_stop() const {
  if (!seen_) return 0;
  return static_cast<std::uint16_t>(*seen_ & config_.stop_flags & ~jausd_bits());
}

std::optional<std::uint16_t> SafetyWord::take_write() {
  if (!write_due_ || in_flight_) return std::nullopt;
  if (!fresh_ && !blind_) return std::nullopt;  // the foreign bits are not known (yet, or again)
  if (foreign_stop() != 0) return std::nullopt;  // never write over the platform's own stop
  const std::uint16_t keep = static_cast<std::uint16_t>(~(config_.owned | config_.stop_flags | config_.status_flags));
  const std::uint16_t word = static_cast<std::uint16_t>(wanted_ | (seen_.value_or(0) & keep));
  in_flight_ = wanted_;
  write_due_ = false;
  return word;
}

void SafetyWord::write_done(bool acked) {
  if (!in_flight_) return;
  // Not ACKed: the platform has the old bits or the new; only bits in both are surely ours.
  applied_ = acked ? *in_flight_ : static_cast<std::uint16_t>(applied_ & *in_flight_);
  if (!acked) write_due_ = true;
  in_flight_.reset();
}

std::optional<std::string> SafetyWord::platform_stop() const {
  if (const std::uint16_t stop = foreign_stop(); stop != 0) {
    char text[80];
    std::snprintf(text, sizeof text, "Clearpath platform e-stop or pause (safety flags 0x%04X)", stop);
    return std::string(text);
  }
  if (unconfirmed_clear_ != 0) {
    char text[96];
    std::snprintf(text, sizeof text, "waiting for the Clearpath platform to report its emergency flag 0x%04X clear",
                  unconfirmed_clear_);
    return std::string(text);
  }
  return std::nullopt;
}

}  // namespace jaus::bridge::detail
