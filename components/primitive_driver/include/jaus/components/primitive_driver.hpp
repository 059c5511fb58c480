// The primitive driver (component 33, RA 3.x Part 3 platform subgroup): the
// controller's Set Wrench Effort and Set Discrete Devices reach the Drive, in
// Ready only; anyone may ask what the drive applies (Report Wrench Effort, the
// effort actually applied, with the fields this platform has), its devices,
// its specifications and its operational data.
//
// Safety: the drive is told to stop (zero propulsive effort, with the
// configured brake) in command_stop(), which the component base calls on
// Standby, Emergency, Failure, Reset, Shutdown, control release or takeover,
// controller silence and the command service connection's deadman
// (rt::Component::enforce_stop); and here, when no Set Wrench Effort has
// arrived within the command timeout. A fault of the drive (Drive::on_fault:
// a lost link to the platform) is a Failure, so it stops the drive too, and
// the driver is Ready again only once the fault has cleared (or back in
// Standby, when a fault interrupted Standby). Until the drive's first data it
// stays in Initialize. The driver keeps no effort to resume:
// after Resume or Clear Emergency the drive stays stopped until the
// controller sends a new Set Wrench Effort.
#pragma once

#include "jaus/components/drive.hpp"
#include "jaus/messages/platform_messages.hpp"
#include "jaus/runtime/component.hpp"

namespace jaus::components {

struct PrimitiveDriverOptions {
  // A moving drive with no new Set Wrench Effort for this long is stopped
  // (0 disables; the deadman of a command service connection still applies).
  rt::Duration command_timeout = std::chrono::milliseconds(500);
  // Resistive linear effort applied with every stop, percent (0 coasts).
  double stop_brake_percent = 100;
};

struct PrimitiveDriverCounters {
  std::uint64_t efforts_applied = 0;
  std::uint64_t devices_set = 0;
  std::uint64_t command_timeouts = 0;
};

class PrimitiveDriver final : public rt::Component {
 public:
  PrimitiveDriver(rt::ComponentConfig config, rt::Environment env, Drive& drive, PrimitiveDriverOptions options = {});
  ~PrimitiveDriver() override;

  const PrimitiveDriverOptions& options() const { return options_; }
  const PrimitiveDriverCounters& driver_counters() const { return driver_counters_; }

  // The reports, for all fields this platform has (queries and service
  // connections mask them with the requested presence vector).
  msg::ReportWrenchEffort wrench_effort_report() const;
  msg::ReportDiscreteDevices discrete_devices_report() const;
  msg::ReportPlatformSpecifications specifications_report() const;
  msg::ReportPlatformOperationalData operational_data_report();

 protected:
  bool initialize() override;
  void command_stop(std::string_view why) override;
  void state_changed(rt::PrimaryStatus before, rt::PrimaryStatus after) override;

 private:
  void on_set_wrench_effort(const Header& h, const msg::SetWrenchEffort& m);
  void on_set_discrete_devices(const Header& h, const msg::SetDiscreteDevices& m);
  void arm_command_timeout();
  void cancel_command_timeout();
  void wait_for_command_deadline();
  std::uint8_t discrete_devices_presence() const;

  Drive& drive_;
  PrimitiveDriverOptions options_;
  PrimitiveDriverCounters driver_counters_;
  rt::TimerId command_timer_ = rt::kNoTimer;
  rt::TimePoint command_deadline_{};
  std::optional<std::string> drive_fault_;  // as the drive last reported it
  bool propelling_ = false;  // the last effort applied moves the platform (until a stop)
};

// The conversions between Part 3's message bodies and the Drive's terms
// (driver_reports.cpp), one place for each field's meaning.
WrenchEffort to_wrench_effort(const msg::WrenchEffortBody& body);
msg::WrenchEffortBody to_wrench_effort_body(const WrenchEffort& effort, std::uint16_t fields);
DiscreteDevices to_discrete_devices(const msg::DiscreteDevicesBody& body, const DeviceSet& has);
msg::DiscreteDevicesBody to_discrete_devices_body(const DiscreteDevices& devices, const DeviceSet& has);
msg::PlatformSpecificationsBody to_specifications_body(const PlatformSpecifications& specs);
// What a client of a primitive driver reads back (the drivers above it): the fields the Drive's terms have.
PlatformSpecifications from_specifications_body(const msg::PlatformSpecificationsBody& body);
msg::PlatformOperationalDataBody to_operational_data_body(const OperationalData& data);

}  // namespace jaus::components
