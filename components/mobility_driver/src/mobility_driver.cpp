#include "jaus/components/mobility_driver.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "jaus/components/primitive_driver.hpp"
#include "jaus/core/component_ids.hpp"
#include "jaus/wire/message.hpp"

namespace jaus::components {

using namespace rt;

namespace {
constexpr Duration kSpecificationsRetry = std::chrono::seconds(1);
// The fields a driver above commands: speed and turn (the guidance's effort model).
constexpr std::uint16_t kCommandedFields = effort_field::kPropulsiveLinearX | effort_field::kPropulsiveRotationalZ;

bool fresh(const PoseSample& sample, TimePoint now, Duration stale_after) {
  return now - sample.taken_at <= stale_after;
}
}  // namespace

Expected<MobilityDriverOptions> mobility_driver_options(const KindOptions& options) {
  MobilityDriverOptions o;
  if (const auto it = options.values.find("primitive_driver"); it != options.values.end()) {
    const auto address = Address::parse(it->second);
    if (!address || address->is_broadcast() || address->subsystem == 0 || address->node == 0 ||
        address->component == 0 || address->instance == 0)
      return unexpected(option_error(options, "primitive_driver", "one component's address, S.N.C.I"));
    o.primitive_driver = *address;
  }
  const auto rate = number_option(options, "command_rate_hz", 1, 100, o.command_rate_hz);
  if (!rate) return unexpected(rate.error());
  o.command_rate_hz = *rate;
  const auto stale = seconds_option(options, "pose_stale_after_s", 0.05, 10, o.pose_stale_after);
  if (!stale) return unexpected(stale.error());
  o.pose_stale_after = *stale;
  // Up to 254: an operator must be able to ask for more than the ceiling.
  const std::string ceiling_range = "a whole number 0.." + std::to_string(kHighestDriverMaxAuthority) +
                                    " (an operator must be able to ask for more)";
  const auto ceiling = number_option(options, "max_authority", 0, kHighestDriverMaxAuthority, o.max_authority);
  if (!ceiling || *ceiling != std::floor(*ceiling))
    return unexpected(option_error(options, "max_authority", ceiling_range));
  o.max_authority = static_cast<std::uint8_t>(*ceiling);
  return o;
}

Expected<void> check_driver_authority(std::string_view kind, std::uint8_t authority,
                                      const MobilityDriverOptions& options) {
  if (authority <= options.max_authority) return {};
  Error error = make_error(ErrorCode::invalid_argument,
                           std::string(kind) + ": authority " + std::to_string(authority) +
                               " is above its max_authority " + std::to_string(options.max_authority) +
                               " (an operator above max_authority must always be able to take the primitive "
                               "driver from it; raise max_authority, at most " +
                               std::to_string(kHighestDriverMaxAuthority) + ", or lower authority)");
  error.field = "authority";
  return unexpected(error);
}

namespace {
ComponentConfig with_ceiling(ComponentConfig config, std::uint8_t max_authority) {
  config.max_authority = max_authority;
  return config;
}
}  // namespace

MobilityDriver::MobilityDriver(ComponentConfig config, Environment env, PoseSource& pose,
                               MobilityDriverOptions options)
    : Component(with_ceiling(std::move(config), options.max_authority), std::move(env)),
      pose_(pose),
      options_(options),
      primitive_driver_(options.primitive_driver.value_or(
          Address{address().subsystem, address().node, component_id::kPrimitiveDriver, 1})),
      control_client_(this->env(), options.control,
                      ControlClient::Io{
                          .request = [this](const Address& to, const msg::RequestComponentControl& m) { send(to, m); },
                          .release = [this](const Address& to, const msg::ReleaseComponentControl& m) { send(to, m); },
                          .query_status = [this](const Address& to,
                                                 const msg::QueryComponentStatus& m) { send(to, m); },
                      }) {}

MobilityDriver::~MobilityDriver() {
  cancel_step();
  if (specifications_timer_ != kNoTimer) env().scheduler.cancel(specifications_timer_);
}

// ---- the primitive driver's specifications: the guidance's limits -------------------

// The RA's Initialize lasts until the driver knows what it drives: the
// primitive driver's Report Platform Specifications, asked every second.
bool MobilityDriver::initialize() {
  if (limits_) return true;
  wait_for_hardware("the specifications of the primitive driver " + primitive_driver_.to_string());
  ask_specifications();
  return true;
}

void MobilityDriver::ask_specifications() {
  if (specifications_timer_ != kNoTimer) env().scheduler.cancel(specifications_timer_);
  specifications_timer_ = kNoTimer;
  if (limits_) return;
  send(primitive_driver_, msg::QueryPlatformSpecifications{{0xFFFFFFFFu}});
  specifications_timer_ = env().scheduler.call_at(env().clock.now() + kSpecificationsRetry, [this] {
    specifications_timer_ = kNoTimer;
    ask_specifications();
  });
}

bool MobilityDriver::unhandled(const Header& header, std::span<const std::uint8_t> payload) {
  if (control_client_.on_message(header, payload)) return true;
  if (header.command_code != msg::ReportPlatformSpecifications::code || header.source != primitive_driver_)
    return false;
  if (limits_) return true;  // a late answer to a repeated query
  msg::ReportPlatformSpecifications report{};
  if (auto decoded = wire::decode_payload_into(payload, report, wire::Dialect::ra, kHeaderSize); !decoded) {
    log_repeated("malformed Report Platform Specifications", LogLevel::warn, [&] {
      return "malformed Report Platform Specifications from " + header.source.to_string() + ": " +
             decoded.error().message();
    });
    return true;
  }
  auto limits = guidance::limits_from(from_specifications_body(report));
  if (!limits) {
    // Nothing to drive with: the driver stays in Initialize, asking again.
    log_repeated("unusable platform specifications", LogLevel::error, [&] {
      return "cannot drive " + primitive_driver_.to_string() + ": " + limits.error().message();
    });
    return true;
  }
  limits_ = *limits;
  log(LogLevel::info, "drives " + primitive_driver_.to_string() + " (" +
                          (limits_->steering == Steering::ackermann ? "Ackermann" : "differential") + ", " +
                          option_number_text(limits_->max_speed_mps) + " m/s)");
  if (specifications_timer_ != kNoTimer) env().scheduler.cancel(specifications_timer_);
  specifications_timer_ = kNoTimer;
  hardware_ready();
  return true;
}

// ---- motion ------------------------------------------------------------------------

void MobilityDriver::engage(std::string_view why) {
  if (engaged_) return;
  if (state() != PrimaryStatus::ready || !limits_) return;
  engaged_ = true;
  lost_control_ = false;
  ++counters_.engagements;
  last_step_.reset();
  log(LogLevel::info, "driving (" + std::string(why) + "): requesting control of " + primitive_driver_.to_string());
  // Safety: at most the ceiling, whatever the own authority (Component keeps
  // it there; this holds even if it did not), so an operator above wins.
  const auto authority = std::min(control().own_authority(), options_.max_authority);
  control_client_.acquire(
      primitive_driver_, authority, [this] { on_control_held(); },
      [this](const std::string& lost) { on_control_lost(lost); });
}

void MobilityDriver::on_control_held() {
  log(LogLevel::info, "controls " + primitive_driver_.to_string());
  motion_started();
  run_step();  // at once: the primitive driver's command timeout starts with our first effort
}

void MobilityDriver::on_control_lost(const std::string& why) {
  if (!engaged_) return;
  ++counters_.control_losses;
  lost_control_ = true;
  log(LogLevel::warn, "stopped: lost control of the primitive driver: " + why);
  halt("lost control of the primitive driver: " + why);
}

// Safety: the one place a motion ends (see the header). Zero goes below
// first, then control is given back, so the primitive driver's own release
// stop follows; after a loss nothing can be sent and the primitive driver's
// new controller (or its state) has already stopped it.
void MobilityDriver::halt(std::string_view why) {
  if (!engaged_) return;
  engaged_ = false;
  ++counters_.halts;
  cancel_step();
  if (control_client_.held()) send_effort(WrenchEffort{});
  control_client_.release();
  last_halt_ = std::string(why);
  motion_halted(why);
}

// Every stop path of the component base (Standby, Emergency, Reset,
// Shutdown, Failure, loss of its own controller) ends the motion.
void MobilityDriver::command_stop(std::string_view why) { halt(why); }

void MobilityDriver::arm_step() {
  cancel_step();
  const auto period = std::chrono::duration_cast<Duration>(std::chrono::duration<double>(1.0 / options_.command_rate_hz));
  step_timer_ = env().scheduler.call_at(env().clock.now() + period, [this] {
    step_timer_ = kNoTimer;
    run_step();
  });
}

void MobilityDriver::cancel_step() {
  if (step_timer_ == kNoTimer) return;
  env().scheduler.cancel(step_timer_);
  step_timer_ = kNoTimer;
}

void MobilityDriver::run_step() {
  if (!commanding()) return;
  const TimePoint now = env().clock.now();
  const auto sample = pose_.sample();
  if (!sample || !fresh(*sample, now, options_.pose_stale_after)) {
    log(LogLevel::warn, "stopped: no fresh pose");
    halt("no fresh pose (older than " + option_number_text(std::chrono::duration<double>(options_.pose_stale_after).count()) +
         " s)");
    return;
  }
  const double dt_s = last_step_ ? std::chrono::duration<double>(now - *last_step_).count() : 0.0;
  last_step_ = now;
  ++counters_.steps;
  const Step next = step(*sample, dt_s);
  switch (next.kind) {
    case Step::Kind::drive:
      send_effort(next.effort);
      arm_step();
      return;
    case Step::Kind::arrived:
      ++counters_.arrivals;
      log(LogLevel::info, "arrived: " + next.why);
      halt(next.why);
      return;
    case Step::Kind::fault:
      log(LogLevel::warn, "stopped: " + next.why);
      halt(next.why);
      return;
  }
}

void MobilityDriver::send_effort(const WrenchEffort& effort) {
  msg::SetWrenchEffort command;
  static_cast<msg::WrenchEffortBody&>(command) = to_wrench_effort_body(effort, kCommandedFields);
  ++counters_.efforts_sent;
  send(primitive_driver_, command);
}

std::uint32_t MobilityDriver::component_status_bits() const {
  std::uint32_t bits = 0;
  if (engaged_) bits |= mobility_status::kDriving;
  if (commanding()) bits |= mobility_status::kCommanding;
  if (lost_control_) bits |= mobility_status::kLostControl;
  return bits;
}

}  // namespace jaus::components
