// What every driver above the primitive driver shares (the vector, waypoint
// and path segment drivers, components 34 and 44-48; issue 30): it drives the
// vehicle the RA's way, as a JAUS client of the primitive driver.
//
//   engage()  -> Request Component Control of the primitive driver with this
//                component's own authority, never above max_authority
//                (rt::ControlClient); once granted
//                and the driver reports Ready, step() runs at command_rate_hz
//                on the pose source's latest sample and each effort goes out
//                as Set Wrench Effort (which also keeps the primitive
//                driver's command timeout from stopping it).
//   halt()    -> Set Wrench Effort zero, then Release Component Control (the
//                primitive driver's own release stop follows).
//
// Safety (where "every stop path ends commanding zero below" is kept):
//   - every stop path of this component (Standby, Emergency, Reset,
//     Shutdown, Failure, its controller releasing it, taken over or silent:
//     rt::Component::enforce_stop) reaches command_stop() -> halt();
//   - the primitive driver taken by a higher authority (Reject Component
//     Control), leaving Ready (an operator's Set Emergency or Standby on it)
//     or falling silent: the client loses control -> halt(), the loss counted
//     and logged. Nothing restarts the motion on its own after any of these:
//     the derived driver needs a new command of its controller (a new Set
//     Vector; for a route Standby and Resume, or Set Travel Speed above zero
//     in Ready: ready_start.hpp), so Clear Emergency or Resume on the
//     primitive driver never restarts a route;
//   - a pose that is missing or older than pose_stale_after halts too.
// Operators always win (issue 42): the driver's authority has a ceiling,
// max_authority (default 1, at most 254). Its controller's Set Component
// Authority above it is refused (rt::ComponentConfig::max_authority), a
// configured authority above it is a configuration error
// (mobility_driver_kind), and engage() asks with at most the ceiling; so any
// operator requesting the primitive driver above max_authority takes it from
// the driver at once (the arbiter's "higher authority takes over"), and the
// driver halts as for any loss of control.
// With emergency_scope `vehicle` the drivers are members of the vehicle's
// latch (their kinds move hardware): a Set Emergency to the primitive driver
// puts them in Emergency in the same step.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "jaus/components/guidance/loops.hpp"
#include "jaus/components/pose_source.hpp"
#include "jaus/runtime/component.hpp"
#include "jaus/runtime/component_kind.hpp"
#include "jaus/runtime/control_client.hpp"

namespace jaus::components {

// The default ceiling of a driver's authority: below every operator that
// asks with 2 or more.
inline constexpr std::uint8_t kDefaultDriverMaxAuthority = 1;
// The highest ceiling: an operator must be able to ask for more.
inline constexpr std::uint8_t kHighestDriverMaxAuthority = 254;

struct MobilityDriverOptions {
  // The primitive driver this one commands; none: this node's (ID 33, instance 1).
  std::optional<Address> primitive_driver;
  double command_rate_hz = 20;  // guidance steps, each a Set Wrench Effort
  rt::Duration pose_stale_after = std::chrono::seconds(1);
  // The ceiling of this driver's authority (see above): an operator at any
  // authority above it takes the primitive driver from this driver.
  std::uint8_t max_authority = kDefaultDriverMaxAuthority;
  rt::ControlClient::Options control;
};

// The option keys every driver kind accepts (its own come after them).
inline const std::vector<std::string_view> kMobilityDriverOptionKeys = {"primitive_driver", "command_rate_hz",
                                                                         "pose_stale_after_s", "max_authority"};
Expected<MobilityDriverOptions> mobility_driver_options(const rt::KindOptions& options);
// A configured authority above the options' max_authority is an error ("local_waypoint_driver: ...").
Expected<void> check_driver_authority(std::string_view kind, std::uint8_t authority,
                                      const MobilityDriverOptions& options);

struct MobilityDriverCounters {
  std::uint64_t engagements = 0;    // engage() that requested control
  std::uint64_t steps = 0;          // guidance steps run
  std::uint64_t efforts_sent = 0;   // Set Wrench Effort sent (zeros included)
  std::uint64_t arrivals = 0;       // motions that ended by arriving
  std::uint64_t control_losses = 0; // the primitive driver refused, took away or left Ready
  std::uint64_t halts = 0;          // every end of a motion
};

// Secondary status bits 16-31 of this component's Report Component Status.
namespace mobility_status {
inline constexpr std::uint32_t kDriving = 1u << 16;      // engaged: wants to move
inline constexpr std::uint32_t kCommanding = 1u << 17;   // holds the primitive driver, sending efforts
inline constexpr std::uint32_t kLostControl = 1u << 18;  // the last motion ended by losing the primitive driver
}  // namespace mobility_status

class MobilityDriver : public rt::Component {
 public:
  MobilityDriver(rt::ComponentConfig config, rt::Environment env, PoseSource& pose, MobilityDriverOptions options);
  ~MobilityDriver() override;

  bool driving() const { return engaged_; }
  bool commanding() const { return engaged_ && control_client_.held(); }
  const Address& primitive_driver() const { return primitive_driver_; }
  // From the primitive driver's Report Platform Specifications; none before.
  const std::optional<guidance::VehicleLimits>& limits() const { return limits_; }
  const MobilityDriverCounters& mobility_counters() const { return counters_; }
  const rt::ControlClient& control_client() const { return control_client_; }
  // Why the last motion ended ("" before the first).
  const std::string& last_halt() const { return last_halt_; }

 protected:
  // What the derived driver's guidance commands now.
  struct Step {
    enum class Kind : std::uint8_t { drive, arrived, fault };
    Kind kind = Kind::drive;
    WrenchEffort effort;  // drive
    std::string why;      // arrived, fault
    static Step drive(const WrenchEffort& effort) { return {Kind::drive, effort, {}}; }
    static Step arrived(std::string why) { return {Kind::arrived, {}, std::move(why)}; }
    static Step fault(std::string why) { return {Kind::fault, {}, std::move(why)}; }
  };
  // One guidance step: `pose` is fresh; dt_s is the time since the last step
  // of this motion (0 for the first). Only while commanding().
  virtual Step step(const PoseSample& pose, double dt_s) = 0;
  // Control of the primitive driver is held: the first step follows (reset the loops here).
  virtual void motion_started() {}
  // The motion ended, for `why` (already stopped below): the derived driver
  // forgets what would restart it.
  virtual void motion_halted(std::string_view /*why*/) {}

  // Starts a motion (only in Ready; ignored otherwise): control of the
  // primitive driver is requested, steps begin once it is held. Engaged
  // already: nothing changes.
  void engage(std::string_view why);
  // Ends the motion: zero below, control released, motion_halted(why).
  // Idempotent (does nothing when not engaged).
  void halt(std::string_view why);

  PoseSource& pose_source() { return pose_; }
  const MobilityDriverOptions& mobility_options() const { return options_; }

  bool initialize() override;
  void command_stop(std::string_view why) override;
  bool unhandled(const Header& header, std::span<const std::uint8_t> payload) override;
  std::uint32_t component_status_bits() const override;

 private:
  void on_control_held();
  void on_control_lost(const std::string& why);
  void run_step();
  void arm_step();
  void cancel_step();
  void send_effort(const WrenchEffort& effort);
  void ask_specifications();

  PoseSource& pose_;
  MobilityDriverOptions options_;
  Address primitive_driver_;
  rt::ControlClient control_client_;
  std::optional<guidance::VehicleLimits> limits_;
  MobilityDriverCounters counters_;
  bool engaged_ = false;
  bool lost_control_ = false;
  std::string last_halt_;
  rt::TimerId step_timer_ = rt::kNoTimer;
  rt::TimerId specifications_timer_ = rt::kNoTimer;
  std::optional<rt::TimePoint> last_step_;
};

}  // namespace jaus::components
