// The platform's safety word (Set Safety System 0x0010 / Safety Status
// 0x8010), owned bit by bit. Sans-I/O: ClearpathVehicle feeds it what it
// wants and what the platform reports, and writes what it hands out.
//
// The rule (docs/bridge.md, docs/safety.md):
//   - jausd owns only `owned` (emergency_flags, discrete devices mapped to
//     safety flags). A write carries jausd's owned bits and keeps every other
//     bit as last seen in 0x8010, except the platform's stop inputs
//     (`stop_flags`) and the bits it reports about itself (`status_flags`,
//     Husky: timeout, no battery, current limit), which are never written.
//   - A platform stop is a bit of `stop_flags` set in 0x8010 that jausd did
//     not set (a bit is jausd's only once the platform ACKed a write with it;
//     while a write is in flight its bits count as jausd's). It holds until
//     the platform itself reports it clear.
//   - While a platform stop is on, nothing is written: a write could only
//     erase the platform's stop (a software stop of another client) or latch
//     it into the software word (a hardware one) — jausd never clears a stop
//     it did not set. What jausd wants then goes out once it has cleared.
//   - At start, owned bits the first 0x8010 shows that jausd wants set (an
//     emergency held across a restart) are taken as jausd's own.
//   - Until the first 0x8010 nothing is written either (the foreign bits are
//     not known yet), unless the platform refused the subscription: then only
//     jausd's own bits are written.
//   - When jausd clears one of its bits that is also a stop input (Husky:
//     emergency_flags 0x08 is the e-stop's bit), the platform's stop is held
//     until a 0x8010 after the write's ACK shows the bit clear; if it is still
//     set, the platform's own e-stop was pressed meanwhile, and that stop
//     takes over without a gap. So no flip-flop between Emergency and Ready.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

namespace jaus::bridge::detail {

struct SafetyWordConfig {
  std::uint16_t owned = 0;         // bits jausd sets and clears
  std::uint16_t stop_flags = 0;    // 0x8010 bits that mean the platform's own stop
  std::uint16_t status_flags = 0;  // 0x8010 bits the platform reports about itself, never written
};

class SafetyWord {
 public:
  explicit SafetyWord(SafetyWordConfig config) : config_(config) {}

  // The owned bits jausd wants set now.
  void want(std::uint16_t bits);
  // A Safety Status (0x8010) from the platform.
  void status(std::uint16_t flags);
  // The local command (an operator on the vehicle): owned bits the platform
  // shows now are jausd's, left there by an earlier run; what jausd does not
  // want of them is written clear. A stop input still set after that is the
  // platform's own stop again: a hardware e-stop is never undone.
  void adopt_owned_bits_seen();
  // The platform will not send 0x8010: write jausd's own bits alone.
  void status_unavailable();
  // The link went down: nothing is written until the next 0x8010, and what
  // jausd wants is written again then (a restarted platform has lost it).
  void link_lost();

  // The word to write now, if one is due; it is then in flight until write_done().
  std::optional<std::uint16_t> take_write();
  void write_done(bool acked);

  // Why the platform is stopped by itself (its stop bits) or held until it
  // confirms jausd's emergency flag clear; nullopt when neither.
  std::optional<std::string> platform_stop() const;
  std::uint16_t wanted() const { return wanted_; }
  std::optional<std::uint16_t> last_seen() const { return seen_; }

 private:
  std::uint16_t jausd_bits() const;  // bits jausd set: ACKed, or in flight
  std::uint16_t foreign_stop() const;

  SafetyWordConfig config_;
  std::uint16_t wanted_ = 0;
  std::uint16_t applied_ = 0;                // owned bits the platform ACKed
  std::optional<std::uint16_t> in_flight_;   // owned bits of the write awaiting its ACK
  std::optional<std::uint16_t> seen_;        // the last 0x8010 (kept while the link is down)
  bool fresh_ = false;                       // a 0x8010 since the link (re)started
  bool started_ = false;                     // a 0x8010 since this process started
  bool blind_ = false;                       // no 0x8010 from this platform
  bool write_due_ = false;
  std::uint16_t unconfirmed_clear_ = 0;      // owned stop bits written clear, not yet seen clear
};

}  // namespace jaus::bridge::detail
