#include "jaus/components/primitive_driver.hpp"

#include <chrono>

#include "jaus/wire/describe.hpp"

namespace jaus::components {

using namespace rt;

namespace {
std::string seconds_text(Duration d) {
  return std::to_string(std::chrono::duration<double>(d).count()).substr(0, 5) + " s";
}
bool propels(const WrenchEffort& e) {
  return e.propulsive_linear != Axes{} || e.propulsive_rotational != Axes{};
}
}  // namespace

PrimitiveDriver::PrimitiveDriver(ComponentConfig config, Environment env, Drive& drive, PrimitiveDriverOptions options)
    : Component(std::move(config), std::move(env)), drive_(drive), options_(options) {
  using namespace msg;
  // Commands that move the platform: the controller's, in Ready only (the
  // base refuses the rest and counts them; they never reach the drive).
  handle<SetWrenchEffort>(Access::controller, /*ready_only=*/true,
                          [this](const Header& h, const SetWrenchEffort& m) { on_set_wrench_effort(h, m); });
  handle<SetDiscreteDevices>(Access::controller, /*ready_only=*/true,
                             [this](const Header& h, const SetDiscreteDevices& m) { on_set_discrete_devices(h, m); });

  // Queries: anyone; the report carries the requested fields this platform has.
  handle<QueryWrenchEffort>(Access::anyone, false, [this](const Header& h, const QueryWrenchEffort& q) {
    auto report = wrench_effort_report();
    wire::mask_presence(report, q.presence_vector);
    send(h.source, report);
  });
  handle<QueryDiscreteDevices>(Access::anyone, false, [this](const Header& h, const QueryDiscreteDevices& q) {
    auto report = discrete_devices_report();
    wire::mask_presence(report, q.presence_vector);
    send(h.source, report);
  });
  handle<QueryPlatformSpecifications>(Access::anyone, false,
                                      [this](const Header& h, const QueryPlatformSpecifications& q) {
                                        auto report = specifications_report();
                                        wire::mask_presence(report, q.presence_vector);
                                        send(h.source, report);
                                      });
  handle<QueryPlatformOperationalData>(Access::anyone, false,
                                       [this](const Header& h, const QueryPlatformOperationalData& q) {
                                         auto report = operational_data_report();
                                         wire::mask_presence(report, q.presence_vector);
                                         send(h.source, report);
                                       });

  // The same reports on service connections, with what this platform has.
  provide<ReportWrenchEffort>(drive_.effort_fields(), [this] { return wrench_effort_report(); });
  provide<ReportDiscreteDevices>(discrete_devices_presence(), [this] { return discrete_devices_report(); });
  provide<ReportPlatformSpecifications>(wire::presence_of(specifications_report()),
                                        [this] { return specifications_report(); });
  provide<ReportPlatformOperationalData>(wire::presence_of(operational_data_report()),
                                         [this] { return operational_data_report(); });

  // A drive fault is a Failure of the driver (the drive stops), and its end a recovery.
  // Before the drive's first data (a platform not heard from yet), the
  // driver waits in Initialize (initialize()); its end is the first clear.
  drive_.on_fault([this](const std::optional<std::string>& fault) {
    drive_fault_ = fault;
    if (fault) {
      declare_failure("drive fault: " + *fault);
      return;
    }
    hardware_ready();
    clear_failure("drive fault cleared");
  });

  // Report Services: the fields each command acts on and each query can get.
  declare_input_presence(SetWrenchEffort::code, drive_.effort_fields());
  declare_input_presence(QueryWrenchEffort::code, drive_.effort_fields());
  declare_input_presence(SetDiscreteDevices::code, discrete_devices_presence());
  declare_input_presence(QueryDiscreteDevices::code, discrete_devices_presence());
  declare_input_presence(QueryPlatformSpecifications::code, wire::presence_of(specifications_report()));
  declare_input_presence(QueryPlatformOperationalData::code, wire::presence_of(operational_data_report()));
}

PrimitiveDriver::~PrimitiveDriver() {
  drive_.on_fault({});
  cancel_command_timeout();
}

// The RA's Initialize lasts until the drive can be commanded: a platform not
// heard from yet is not a Ready driver that fails a moment later.
bool PrimitiveDriver::initialize() {
  if (drive_fault_) wait_for_hardware("the drive (" + *drive_fault_ + ")");
  return true;
}

// A fault that arrived while the driver could not enter Failure (in
// Emergency, or initialising) takes effect as soon as it is Ready or in
// Standby again: never Ready on a faulted drive.
// Likewise a fault that cleared during an Emergency that interrupted the
// Failure: back in Failure, the driver recovers at once.
void PrimitiveDriver::state_changed(rt::PrimaryStatus, rt::PrimaryStatus after) {
  if (drive_fault_ && (after == rt::PrimaryStatus::ready || after == rt::PrimaryStatus::standby))
    declare_failure("drive fault: " + *drive_fault_);
  else if (!drive_fault_ && after == rt::PrimaryStatus::failure && failure_declared())
    clear_failure("drive fault cleared");
}

msg::ReportWrenchEffort PrimitiveDriver::wrench_effort_report() const {
  msg::ReportWrenchEffort report;
  static_cast<msg::WrenchEffortBody&>(report) = to_wrench_effort_body(drive_.applied_effort(), drive_.effort_fields());
  return report;
}

msg::ReportDiscreteDevices PrimitiveDriver::discrete_devices_report() const {
  msg::ReportDiscreteDevices report;
  static_cast<msg::DiscreteDevicesBody&>(report) = to_discrete_devices_body(drive_.device_state(), drive_.devices());
  return report;
}

msg::ReportPlatformSpecifications PrimitiveDriver::specifications_report() const {
  msg::ReportPlatformSpecifications report;
  static_cast<msg::PlatformSpecificationsBody&>(report) = to_specifications_body(drive_.specifications());
  return report;
}

msg::ReportPlatformOperationalData PrimitiveDriver::operational_data_report() {
  msg::ReportPlatformOperationalData report;
  static_cast<msg::PlatformOperationalDataBody&>(report) = to_operational_data_body(drive_.operational_data());
  return report;
}

std::uint8_t PrimitiveDriver::discrete_devices_presence() const {
  const DeviceSet has = drive_.devices();
  std::uint8_t presence = 0;
  if (has.main_power) presence |= 0x01;
  if (has.parking_brake || has.horn) presence |= 0x02;
  if (has.gear) presence |= 0x04;
  return presence;
}

void PrimitiveDriver::on_set_wrench_effort(const Header& h, const msg::SetWrenchEffort& m) {
  const WrenchEffort asked = to_wrench_effort(m);
  const WrenchEffort applied = drive_.apply_effort(asked);
  ++driver_counters_.efforts_applied;
  propelling_ = propels(applied);
  if (applied != asked)
    log_repeated("Set Wrench Effort limited by the drive", LogLevel::debug,
                 [&] { return "Set Wrench Effort from " + h.source.to_string() + " limited by the drive"; });
  arm_command_timeout();
}

void PrimitiveDriver::on_set_discrete_devices(const Header& h, const msg::SetDiscreteDevices& m) {
  const DeviceSet has = drive_.devices();
  const DiscreteDevices asked = to_discrete_devices(m, has);
  if (asked == DiscreteDevices{}) {
    log_repeated("Set Discrete Devices naming no device ignored", LogLevel::warn, [&] {
      return "Set Discrete Devices from " + h.source.to_string() + " names no device this platform has";
    });
    return;
  }
  drive_.set_devices(asked);
  ++driver_counters_.devices_set;
  log_repeated({"discrete devices set", kNoteworthyBurst}, LogLevel::info,
               [&] { return "discrete devices set by " + h.source.to_string(); });
}

// Safety: each Set Wrench Effort restarts the command timeout; when it runs
// out, the drive stops, as if the controller had gone (a lost link that the
// controller's liveness would notice only after seconds). A command only
// moves the deadline; the one timer, set for the deadline, looks again when
// it fires (no timer armed per command).
void PrimitiveDriver::arm_command_timeout() {
  if (options_.command_timeout <= Duration::zero()) return;
  command_deadline_ = env().clock.now() + options_.command_timeout;
  if (command_timer_ == kNoTimer) wait_for_command_deadline();
}

void PrimitiveDriver::wait_for_command_deadline() {
  command_timer_ = env().scheduler.call_at(command_deadline_, [this] {
    command_timer_ = kNoTimer;
    if (env().clock.now() < command_deadline_) return wait_for_command_deadline();  // a newer command
    // The driver's own record, not the drive's report: a backend may already
    // report zero for a setpoint it stopped renewing (the Clearpath bridge
    // after setpoint_max_age) while the platform still acts on it.
    if (!propelling_) return;  // the last command asked for no motion: nothing to stop
    ++driver_counters_.command_timeouts;
    stop_platform("no Set Wrench Effort for " + seconds_text(options_.command_timeout));
  });
}

void PrimitiveDriver::cancel_command_timeout() {
  if (command_timer_ == kNoTimer) return;
  env().scheduler.cancel(command_timer_);
  command_timer_ = kNoTimer;
}

// Safety: the one place the drive is told to stop (see the header). Nothing
// of the last effort is kept, so nothing resumes it.
void PrimitiveDriver::command_stop(std::string_view why) {
  cancel_command_timeout();
  propelling_ = false;
  drive_.stop(options_.stop_brake_percent);
  // Every Standby, Emergency, release or takeover stops the drive: a peer looping them is
  // one line per stop up to the burst, then a count (the stop itself is never limited).
  log_repeated({"drive stops", kNoteworthyBurst}, LogLevel::info, [&] { return "drive stopped: " + std::string(why); });
}

}  // namespace jaus::components
