// The reference model of the RA's safety rules for one vehicle: a few sets
// and flags, no JAUS, no clock of its own, nothing from the implementation.
// The runner (model_runner.hpp) feeds it what each operator, the platform and
// the clock did, and asks it what the node must show.
//
// Where the rules leave the timing open (a controller silent for about its
// timeout, a command about its command timeout old, the platform's stop
// before jausd has heard of it, an Emergency's end before the platform
// confirms it, the vector driver taking or giving back the primitive driver)
// the model allows each outcome and the runner tells it which one happened
// (sync_*): every outcome it allows there is safe.
//
// Hooks for the rules being added (the alias subsystem refused, holds with
// their host, a driver's authority capped, a stop counter, a one-way
// platform link): at the end of the class, each with where it goes.
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "action.hpp"

namespace jaus::model {

using Ms = std::int64_t;  // virtual milliseconds
inline constexpr Ms kNever = std::numeric_limits<Ms>::max() / 4;

// Who controls the primitive driver: an operator, the vector driver, nobody.
enum class Ctl : std::uint8_t { none, a, b, j, c, driver };
const char* name(Ctl c);
Ctl ctl_of(Party p);

// The primitive driver's state as the RA's lifecycle has it.
enum class PdState : std::uint8_t { initialize, ready, standby, emergency, failure, shutdown };
const char* name(PdState s);

struct ModelTiming {
  Ms command_timeout = 500;      // the primitive driver's command_timeout_s
  Ms controller_timeout = 3000;  // control.controller_timeout_s
  Ms margin = 60;                // either side of a timeout: either outcome
  Ms stop_deadline = 50;         // a stop jausd makes: zero commanded within this
  Ms platform_deadline = 300;    // a stop the platform makes: jausd's zero within this
  Ms settle = 500;               // an Emergency's end: Ready once the platform confirms, within this
  Ms driver_settle = 600;        // the vector driver takes or gives back the primitive driver within this
  // Every platform stop, even one released before jausd's next safety
  // status would have come at 10 Hz, ends the command in effect: jausd
  // samples it at 50 Hz, so a stop of one period (20 ms, the pulse) is seen
  // (ModelRegression.APausePulseOfOneStatusPeriodEndsTheCommand). A shorter one
  // is not promised (docs/safety.md, Limits).
  bool every_platform_stop_ends_the_command = true;
};

class ReferenceModel {
 public:
  explicit ReferenceModel(ModelTiming timing = {}) : t_(timing) {}

  // A jausd (re)started at `now`: holds and the platform's inputs are kept
  // (the holds file, the hardware), everything else starts afresh.
  void start(Ms now);

  // Deadlines that are surely past by `now` take effect (controller silence,
  // command timeout). Called before every event and every check.
  void advance_to(Ms now);

  // ---- events (the runner calls advance_to(now) first) -------------------
  // `observed` is the primitive driver's state the moment the message lands:
  // used only where the model's own state is open (expected_states() has more than one).
  void request_control(Party p, std::uint8_t authority, Ms now);
  void release_control(Party p, Ms now);
  void effort(Party p, double percent, Ms now, PdState observed);
  void set_emergency(Party p, Target to, Ms now);
  void clear_emergency(Party p, Target to, Ms now);
  void standby(Party p, Ms now, PdState observed);
  void resume(Party p, Ms now, PdState observed);
  void set_authority(Party p, std::uint8_t authority, Ms now);
  void shutdown(Party p, Ms now);
  void reset(Party p, Ms now);
  void heard(Party p, Ms now);  // any message from p reached the primitive driver
  void platform_input(bool estop, bool on, Ms now);
  void local_clear(Ms now);
  // C and the vector driver.
  void c_takes_vector(Ms now);
  void c_releases_vector(Ms now);
  void c_heard_by_vector(Ms now);
  // `vector_ready`: the vector driver was Ready (observed: its own readiness is not a rule here).
  void c_drives_vector(Ms now, bool vector_ready);

  // ---- what the node must show ----------------------------------------------
  // The primitive driver's controllers the rules allow now (more than one inside a timing window).
  std::vector<Ctl> allowed_controllers(Ms now) const;
  // The runner saw `observed` (one of allowed_controllers): the model follows.
  void sync_controller(Ctl observed, Ms now);
  std::vector<bool> allowed_vector_controlled(Ms now) const;  // C controls the vector driver?
  void sync_vector_controlled(bool observed, Ms now);
  std::vector<PdState> expected_states(Ms now) const;
  // Who holds a Set Emergency (every holder's hold is kept until it clears, or the local clear).
  const std::set<Party>& holders() const { return holders_; }

  // The drive: zero required now (why, or empty when not).
  std::string zero_required(Ms now) const;
  // A non-zero drive of `percent` (linear x; the operators steer straight) is allowed now.
  bool allows_drive(double percent, Ms now) const;
  std::string describe(Ms now) const;

  // ---- hooks: rules being added in parallel (not promised yet) -------------
  // Each is false/none today; turning one on is one property to add:
  //  - accepts_ra_from_alias_subsystem(): RA datagrams whose source claims the
  //    JSS alias subsystem (250) are refused. Add a Party (an RA peer on a
  //    memory link at 250.x) whose control requests, efforts and clears the
  //    model ignores when this is false; ModelNode::party_of must then tell
  //    it from J by its link, not its subsystem.
  //  - hold_identity_includes_host(): holds persisted with the holder's host.
  //    holders_ becomes (party, host); restart() keeps it; a clear from the
  //    same ID on another host (a new action) no longer releases it.
  //  - driver_authority_cap(): a driver's authority capped (max_authority,
  //    default 1) so an operator always wins: c_drives_vector() takes
  //    min(configured, cap) as kDriverAuthority, and request_control() lets
  //    any operator's request displace the driver.
  //  - stop_counter_in_status(): every stop (disarm with a command in effect,
  //    each emergency_began, standby, a platform stop heard) counts one; the
  //    runner reads the counter from Report Component Status and checks it
  //    grew by at least the model's count (brief stops included).
  //  - one_way_platform_link_detected(): a new action drops what jausd writes
  //    to the platform (the LoopbackClient's fault injector, to_platform);
  //    expected_states() then includes Failure within the detection time,
  //    and zero_required() holds from then on.
  static constexpr bool accepts_ra_from_alias_subsystem() { return true; }
  static constexpr bool hold_identity_includes_host() { return false; }
  static constexpr std::optional<std::uint8_t> driver_authority_cap() { return std::nullopt; }
  static constexpr bool stop_counter_in_status() { return false; }
  static constexpr bool one_way_platform_link_detected() { return false; }

 private:
  struct Command {  // what the controller last commanded, in effect until a stop
    double percent = 0;
    bool certain = true;  // false: sent while the state was open (it may have been refused)
    Ms at = 0;
  };
  bool emergency() const { return !holders_.empty() || estop_ || pause_; }
  bool emergency_before_press(bool estop) const;  // held otherwise as `estop` (or the pause) is pressed
  bool certainly_ready(Ms now) const;
  PdState effective_state(Ms now, PdState observed) const;
  void disarm(Ms due);  // a stop: nothing the controller commanded is in effect from `due`
  void end_driver_motion(Ms now);
  void emergency_began(Ms now, Ms deadline);
  void emergency_may_have_ended(Ms now);
  std::optional<Party> controlling_operator() const;

  ModelTiming t_;
  // Kept across restarts.
  std::set<Party> holders_;
  bool estop_ = false, pause_ = false;
  bool estop_heard_ = false, pause_heard_ = false;  // pressed for platform_deadline: jausd surely heard
  Ms holders_since_ = kNever, estop_since_ = kNever, pause_since_ = kNever;
  // A jausd's own.
  Ctl ctl_ = Ctl::none;
  std::uint8_t ctl_authority_ = 0;
  std::uint8_t own_authority_ = 0;
  bool standby_ = false, shutdown_ = false;
  Ms standby_since_ = kNever, shutdown_since_ = kNever;
  Ms unsettled_until_ = 0;  // the state is open until then (an Emergency's end, a start)
  std::array<Ms, kParties> heard_{};
  std::optional<Command> command_;           // the operator controller's, since the last stop
  Ms zero_due_ = 0;                          // with no command in effect: zero from then on
  std::optional<double> lingering_;          // the command before the last stop or change...
  Ms lingering_until_ = 0;                   // ...may still be written until then
  bool lingering_any_ = false;               // ...it was the vector driver's (any value)
  // The vector driver.
  bool c_controls_vector_ = false;
  Ms c_heard_vector_ = 0;
  bool driver_motion_ = false;   // C's Set Local Vector since the driver's last stop
  Ms driver_settle_until_ = 0;   // taking or giving back the primitive driver
};

}  // namespace jaus::model
