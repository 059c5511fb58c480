#include "jaus/clearpath/sim/sim_platform.hpp"

#include <algorithm>
#include <cmath>
#include <type_traits>

namespace jaus::clearpath::sim {
namespace {

constexpr auto kPhysicsStep = std::chrono::milliseconds(5);

template <class M, class T>
constexpr bool is = std::is_same_v<M, T>;

bool differential_only(std::uint16_t type) {
  switch (type & 0x3FFF) {  // command, request and data share the low bits
    case 0x0200: case 0x0201: case 0x0202: return true;
    default: return false;
  }
}
bool ackermann_only(std::uint16_t type) {
  switch (type & 0x3FFF) {
    case 0x0203: case 0x0206: case 0x0212: return true;
    default: return false;
  }
}

// nullopt: not a motion command; else whether it asks for motion.
std::optional<bool> asks_for_motion(const AnyMessage& m) {
  if (const auto* c = m.get_if<SetDifferentialSpeeds>()) return c->left_speed != 0 || c->right_speed != 0;
  if (const auto* c = m.get_if<SetDifferentialOutput>()) return c->left != 0 || c->right != 0;
  if (const auto* c = m.get_if<SetAckermannOutput>()) return c->throttle != 0 && c->brake < 100;
  if (const auto* c = m.get_if<SetVelocity>()) return c->translational != 0 || c->rotational != 0;
  if (const auto* c = m.get_if<SetTurn>()) return c->translational != 0;
  return std::nullopt;
}

// Yaw of the left-handed messages (0x8600/0x8601): positive towards east / right turn.
double left_handed(double right_handed) { return -right_handed; }

}  // namespace

SimPlatform::SimPlatform(PlatformConfig config, rt::TimePoint start)
    : config_(std::move(config)), start_(start), simulated_until_(start), vehicle_(config_.vehicle),
      name_(config_.name) {
  diff_left_ = diff_right_ = ack_speed_ = ack_heading_ = MotorControlConstants{1.0, 0.1, 0, 0.5, 2.0, 20.0};
  factory_ = current_settings();
  stored_ = factory_;
  reported_safety_ = vehicle_.safety_flags();
}

void SimPlatform::emit(PlatformEvent event) const {
  if (on_event_) on_event_(event);
}

void SimPlatform::note_motion_command(const AnyMessage& command, rt::TimePoint now) {
  const auto motion = asks_for_motion(command);
  if (!motion) return;
  if (!*motion && last_motion_nonzero_) emit({PlatformEvent::Kind::zero_command, now});
  last_motion_nonzero_ = *motion;
}

// Events from the vehicle's state: the safety word and the wheels coming to rest.
void SimPlatform::note_state(rt::TimePoint at) {
  if (const auto flags = vehicle_.safety_flags(); flags != reported_safety_) {
    reported_safety_ = flags;
    emit({PlatformEvent::Kind::safety, at, flags});
  }
  if (vehicle_.left().speed != 0 || vehicle_.right().speed != 0) {
    wheels_moving_ = true;
  } else if (wheels_moving_) {
    wheels_moving_ = false;
    emit({PlatformEvent::Kind::wheels_stopped, at});
  }
}

void SimPlatform::press(HardwareInput input, bool on, rt::TimePoint now) {
  advance(now);
  vehicle_.set_hardware_input(input, on);
  emit({PlatformEvent::Kind::input, now, 0, input, on});
  note_state(now);
}

double SimPlatform::seconds(rt::TimePoint now) const {
  return std::chrono::duration<double>(now - start_).count();
}

std::uint32_t SimPlatform::clock_ms(rt::TimePoint now) const {
  const auto ms = std::chrono::duration_cast<std::chrono::milliseconds>(now - start_).count();
  return static_cast<std::uint32_t>(ms + clock_offset_ms_);
}

bool SimPlatform::supports(std::uint16_t type) const {
  if (!find_message(type)) return false;
  if (config_.vehicle.drive == Drive::differential && ackermann_only(type)) return false;
  if (config_.vehicle.drive == Drive::ackermann && differential_only(type)) return false;
  return true;
}

void SimPlatform::append(std::vector<std::uint8_t>& out, std::uint16_t type, std::uint32_t timestamp,
                         const AnyMessage& message) {
  // Our own messages always fit; a failure here would be a bug in the model.
  if (append_encoded(out, Envelope{{kDefaultVersion, timestamp, 0, type}, message})) {
    if (message.holds<Ack>()) ++counters_.acks_out;
    else ++counters_.data_out;
  }
}

std::vector<std::uint8_t> SimPlatform::receive(std::span<const std::uint8_t> bytes, rt::TimePoint now) {
  advance(now);
  std::vector<std::uint8_t> out;
  parser_.feed(bytes);
  while (auto event = parser_.poll()) {
    if (const auto* frame = std::get_if<Frame>(&*event)) {
      handle(*frame, now, out);
      continue;
    }
    const auto& rejected = std::get<RejectedBytes>(*event);
    if (rejected.reason == RejectReason::garbage) continue;
    ++counters_.parse_errors;
    // The header survived, only the CRC failed: tell the host to resend.
    if (rejected.reason == RejectReason::bad_crc && rejected.header && (rejected.header->flags & kFlagSuppressAck) == 0 &&
        kind_of(rejected.header->type) != MessageKind::data &&
        kind_of(rejected.header->type) != MessageKind::unassigned) {
      ++counters_.refused;
      append(out, rejected.header->type, rejected.header->timestamp, Ack{kAckBadChecksum});
    }
  }
  return out;
}

void SimPlatform::handle(const Frame& frame, rt::TimePoint now, std::vector<std::uint8_t>& out) {
  ++counters_.frames_in;
  const std::uint16_t type = frame.header.type;
  const MessageKind kind = kind_of(type);
  if (kind == MessageKind::data || kind == MessageKind::unassigned) return;  // nothing to acknowledge
  const bool ack_wanted = (frame.header.flags & kFlagSuppressAck) == 0;
  const auto acknowledge = [&](std::uint16_t result) {
    if (result != 0) ++counters_.refused;
    if (ack_wanted) append(out, type, frame.header.timestamp, Ack{result});
  };

  if (!supports(type)) return acknowledge(kAckTypeNotSupported);
  const auto decoded = decode_payload(type, frame.payload, Direction::to_platform);
  if (!decoded) return acknowledge(kAckBadFormat);
  if (!check_ranges(*decoded)) return acknowledge(kAckOutOfRange);

  if (kind == MessageKind::command) {
    const std::uint16_t result = apply_command(*decoded, now);
    acknowledge(result);
    if (result == 0) note_motion_command(*decoded, now);
    if (result == 0 && decoded->holds<ResetProcessor>()) {
      // A reset loses subscriptions and restarts the platform clock; a button
      // still pressed stays pressed.
      subscriptions_.clear();
      const auto inputs = vehicle_.hardware_inputs();
      vehicle_ = VehicleModel(config_.vehicle);
      for (const auto input : {HardwareInput::estop, HardwareInput::pause})
        vehicle_.set_hardware_input(input, (inputs & static_cast<std::uint16_t>(input)) != 0);
      start_ = now;
      simulated_until_ = now;
      clock_offset_ms_ = 0;
      last_motion_nonzero_ = false;
    }
    note_state(now);
    return;
  }
  bool reply_now = false;
  const std::uint16_t result = handle_request(*decoded, now, reply_now);
  acknowledge(result);
  if (result == 0 && reply_now) {
    if (const auto reply = reply_to(*decoded, now)) append(out, reply_type_of(type), clock_ms(now), *reply);
  }
}

std::uint16_t SimPlatform::handle_request(const AnyMessage& request, rt::TimePoint now, bool& reply_now) {
  std::uint16_t subscription = 0;
  std::uint8_t selector = 0;
  visit(
      [&](const auto& m) {
        if constexpr (requires { m.subscription; }) subscription = m.subscription;
        if constexpr (requires { m.mount; }) selector = m.mount;
        if constexpr (requires { m.joint; }) selector = m.joint;
      },
      request);
  if (request.holds<RequestPanTiltZoom>() && selector >= config_.vehicle.mounts) return kAckOutOfRange;
  if (request.holds<RequestJointControl>() && selector >= config_.vehicle.joints) return kAckOutOfRange;

  const SubscriptionKey key{*type_of(request), selector};
  if (subscription == kReplyOnce) {
    reply_now = true;
    return 0;
  }
  if (subscription == kCancelSubscription) {
    subscriptions_.erase(key);
    return 0;
  }
  std::uint16_t result = 0;
  if (subscription > config_.max_frequency_hz) result |= kAckFrequencyTooHigh;
  const bool is_new = !subscriptions_.contains(key);
  if (is_new && subscriptions_.size() >= config_.max_subscriptions) result |= kAckTooManyTypes;

  const auto reply = reply_to(request, now);
  const std::size_t frame_bytes = reply ? encode_payload(*reply)->size() + kFrameOverhead : kFrameOverhead;
  if (config_.bandwidth_bytes_per_second > 0) {
    double load = static_cast<double>(frame_bytes) * subscription;
    for (const auto& [k, s] : subscriptions_)
      if (!(k == key)) load += static_cast<double>(s.frame_bytes) * s.rate_hz;
    if (load > config_.bandwidth_share * static_cast<double>(config_.bandwidth_bytes_per_second)) result |= kAckNoBandwidth;
  }
  if (result != 0) return result;
  // Reply now; later replies are timed from this one.
  const auto period = std::chrono::duration_cast<rt::Duration>(std::chrono::duration<double>(1.0 / subscription));
  subscriptions_[key] = Subscription{request, subscription, frame_bytes, now + period};
  reply_now = true;
  return 0;
}

std::uint16_t SimPlatform::apply_command(const AnyMessage& command, rt::TimePoint now) {
  const double t = seconds(now);
  std::uint16_t result = 0;
  visit(
      [&](const auto& m) {
        using M = std::remove_cvref_t<decltype(m)>;
        if constexpr (is<M, SetPlatformName>) {
          name_ = m.name;
        } else if constexpr (is<M, SetPlatformTime>) {
          clock_offset_ms_ = static_cast<std::int64_t>(m.time_ms) -
                             std::chrono::duration_cast<std::chrono::milliseconds>(now - start_).count();
        } else if constexpr (is<M, SetSafetySystem>) {
          vehicle_.set_safety(m.flags);
        } else if constexpr (is<M, SetDifferentialSpeeds>) {
          vehicle_.command_differential_speeds(m.left_speed, m.right_speed, m.left_accel, m.right_accel, t);
        } else if constexpr (is<M, SetDifferentialControl>) {
          diff_left_ = m.left;
          diff_right_ = m.right;
        } else if constexpr (is<M, SetDifferentialOutput>) {
          vehicle_.command_differential_output(m.left, m.right, t);
        } else if constexpr (is<M, SetAckermannOutput>) {
          vehicle_.command_ackermann_output(m.steering, m.throttle, m.brake, t);
        } else if constexpr (is<M, SetVelocity>) {
          vehicle_.command_velocity(m.translational, m.rotational, m.acceleration, t);
        } else if constexpr (is<M, SetTurn>) {
          vehicle_.command_turn(m.translational, m.radius, m.acceleration, t);
        } else if constexpr (is<M, SetAckermannControl>) {
          ack_speed_ = m.speed;
          ack_heading_ = m.heading;
        } else if constexpr (is<M, SetMaxSpeed>) {
          vehicle_.set_max_speed(m.forward, m.reverse);
        } else if constexpr (is<M, SetMaxAccel>) {
          vehicle_.set_max_accel(m.forward, m.reverse);
        } else if constexpr (is<M, ChangeGear>) {
          vehicle_.set_gear(m.gear);
        } else if constexpr (is<M, SetAnalogOutputs>) {
          for (const auto& c : m.channels)
            if (c.channel >= config_.vehicle.analog_outputs) result = kAckOutOfRange;
          if (result == 0)
            for (const auto& c : m.channels) vehicle_.set_analog_output(c.channel, c.value);
        } else if constexpr (is<M, SetGpioDirection>) {
          vehicle_.set_gpio_direction(m.mask, m.direction);
        } else if constexpr (is<M, SetGpioOutput>) {
          vehicle_.set_gpio_output(m.mask, m.value);
        } else if constexpr (is<M, SetPanTiltZoom>) {
          if (m.mount >= config_.vehicle.mounts) result = kAckOutOfRange;
          else vehicle_.set_pan_tilt_zoom(m.mount, m.pan, m.tilt, m.zoom);
        } else if constexpr (is<M, ConfigureEncoders>) {
          if (!vehicle_.configure_encoders(m.encoders)) result = kAckOutOfRange;
        } else if constexpr (is<M, SetAbsoluteJoints> || is<M, SetRelativeJoints>) {
          for (const auto& j : m.joints)
            if (j.joint >= config_.vehicle.joints) result = kAckOutOfRange;
          if (result == 0)
            for (const auto& j : m.joints) {
              if constexpr (is<M, SetAbsoluteJoints>) vehicle_.set_joint_absolute(j.joint, j.angle);
              else vehicle_.set_joint_relative(j.joint, j.angle);
            }
        } else if constexpr (is<M, SetJointControl>) {
          if (m.joint >= config_.vehicle.joints) result = kAckOutOfRange;
          else vehicle_.set_joint_constants(m.joint, m.constants);
        } else if constexpr (is<M, HomeJoint>) {
          if (m.joint >= config_.vehicle.joints) result = kAckOutOfRange;
          else vehicle_.home_joint(m.joint);
        } else if constexpr (is<M, SetEndEffectorPosition> || is<M, SetEndEffectorPose>) {
          // Accepted and reported back; the simulated arm has no inverse kinematics.
        } else if constexpr (is<M, RestoreSettings>) {
          apply_settings(m.source == RestoreSettings::kFactoryDefaults ? factory_ : stored_);
        } else if constexpr (is<M, StoreSettings>) {
          stored_ = current_settings();
        } else if constexpr (is<M, ResetProcessor>) {
          // Handled by the caller once the ACK is out.
        } else {
          result = kAckTypeNotSupported;
        }
      },
      command);
  if (result == 0) ++counters_.commands_applied;
  return result;
}

SimPlatform::Settings SimPlatform::current_settings() const {
  return {name_,
          vehicle_.max_speed_forward(),
          vehicle_.max_speed_reverse(),
          vehicle_.max_accel_forward(),
          vehicle_.max_accel_reverse(),
          diff_left_,
          diff_right_,
          ack_speed_,
          ack_heading_};
}

void SimPlatform::apply_settings(const Settings& s) {
  name_ = s.name;
  vehicle_.set_max_speed(s.max_speed_fwd, s.max_speed_rev);
  vehicle_.set_max_accel(s.max_accel_fwd, s.max_accel_rev);
  diff_left_ = s.diff_left;
  diff_right_ = s.diff_right;
  ack_speed_ = s.ack_speed;
  ack_heading_ = s.ack_heading;
}

void SimPlatform::advance(rt::TimePoint now) {
  while (simulated_until_ + kPhysicsStep <= now) {
    simulated_until_ += kPhysicsStep;
    vehicle_.step(std::chrono::duration<double>(kPhysicsStep).count(), seconds(simulated_until_));
    note_state(simulated_until_);
  }
}

std::vector<std::uint8_t> SimPlatform::tick(rt::TimePoint now) {
  advance(now);
  std::vector<std::uint8_t> out;
  for (auto& [key, sub] : subscriptions_) {
    if (sub.next_due > now) continue;
    if (const auto reply = reply_to(sub.request, now)) append(out, reply_type_of(key.type), clock_ms(now), *reply);
    const auto period = std::chrono::duration_cast<rt::Duration>(std::chrono::duration<double>(1.0 / sub.rate_hz));
    sub.next_due += period;
    if (sub.next_due <= now) sub.next_due = now + period;  // fell behind: skip, do not burst
  }
  return out;
}

std::optional<AnyMessage> SimPlatform::reply_to(const AnyMessage& request, rt::TimePoint now) const {
  const auto& v = vehicle_;
  const auto clamp = [](double x, double lo, double hi) { return std::clamp(x, lo, hi); };
  std::optional<AnyMessage> reply;
  visit(
      [&](const auto& m) {
        using M = std::remove_cvref_t<decltype(m)>;
        if constexpr (is<M, RequestEcho>) {
          reply = EchoData{};
        } else if constexpr (is<M, RequestPlatformInfo>) {
          reply = PlatformInfo{config_.model, 1, config_.serial};
        } else if constexpr (is<M, RequestPlatformName>) {
          reply = PlatformName{name_, false};
        } else if constexpr (is<M, RequestFirmwareInfo>) {
          // 2024-06-05 12:30: minute | hour << 6 | day << 11 | month << 17 | (year - 2000) << 21
          reply = FirmwareInfo{1, 2, 1, 1, 30u | (12u << 6) | (5u << 11) | (6u << 17) | (24u << 21)};
        } else if constexpr (is<M, RequestSystemStatus>) {
          reply = SystemStatus{clock_ms(now), {v.battery_voltage(), 12.0, 5.0}, {v.battery_current()}, {35.0, 30.0 + v.battery_current()}};
        } else if constexpr (is<M, RequestPowerStatus>) {
          reply = PowerStatus{{Battery{v.battery_charge(), 400, 0xC1}}};
        } else if constexpr (is<M, RequestProcessorStatus>) {
          reply = ProcessorStatus{{0, 0, 0}};
        } else if constexpr (is<M, RequestSafetyStatus>) {
          reply = SafetyStatus{v.safety_flags()};
        } else if constexpr (is<M, RequestDifferentialSpeeds>) {
          const auto s = v.differential_speeds_setpoint();
          DifferentialSpeedsData d;
          d.left_speed = s[0]; d.right_speed = s[1]; d.left_accel = s[2]; d.right_accel = s[3];
          reply = d;
        } else if constexpr (is<M, RequestDifferentialControl>) {
          DifferentialControlData d;
          d.left = diff_left_; d.right = diff_right_;
          reply = d;
        } else if constexpr (is<M, RequestDifferentialOutput>) {
          DifferentialOutputData d;
          // Report what the motors get: the speed each side runs at, as % of max.
          d.left = clamp(v.left().speed / v.max_speed_forward() * 100, -100, 100);
          d.right = clamp(v.right().speed / v.max_speed_forward() * 100, -100, 100);
          reply = d;
        } else if constexpr (is<M, RequestAckermannOutput>) {
          const auto s = v.ackermann_output();
          AckermannOutputData d;
          d.steering = s[0]; d.throttle = s[1]; d.brake = s[2];
          reply = d;
        } else if constexpr (is<M, RequestVelocity>) {
          const auto s = v.velocity_setpoint();
          VelocityData d;
          d.translational = s[0]; d.rotational = s[1]; d.acceleration = s[2];
          reply = d;
        } else if constexpr (is<M, RequestTurn>) {
          const auto s = v.turn_setpoint();
          TurnData d;
          d.translational = s[0]; d.radius = s[1]; d.acceleration = s[2];
          reply = d;
        } else if constexpr (is<M, RequestAckermannControl>) {
          AckermannControlData d;
          d.speed = ack_speed_; d.heading = ack_heading_;
          reply = d;
        } else if constexpr (is<M, RequestMaxSpeed>) {
          MaxSpeedData d;
          d.forward = v.max_speed_forward(); d.reverse = v.max_speed_reverse();
          reply = d;
        } else if constexpr (is<M, RequestMaxAccel>) {
          MaxAccelData d;
          d.forward = v.max_accel_forward(); d.reverse = v.max_accel_reverse();
          reply = d;
        } else if constexpr (is<M, RequestGear>) {
          reply = GearData{v.gear_flags(), v.gear()};
        } else if constexpr (is<M, RequestAnalogOutputs>) {
          reply = AnalogOutputsData{v.analog_outputs()};
        } else if constexpr (is<M, RequestGpio>) {
          reply = GpioData{v.gpio_direction(), v.gpio_value()};
        } else if constexpr (is<M, RequestAnalogInputs>) {
          reply = AnalogInputsData{v.analog_inputs()};
        } else if constexpr (is<M, RequestPanTiltZoom>) {
          const auto& mount = v.mounts().at(m.mount);
          PanTiltZoomData d;
          d.mount = m.mount; d.pan = mount.pan; d.tilt = mount.tilt; d.zoom = mount.zoom;
          reply = d;
        } else if constexpr (is<M, RequestRangefinders>) {
          reply = RangefinderData{v.ranges()};
        } else if constexpr (is<M, RequestRangefinderTiming>) {
          RangefinderTimingData d;
          for (const double r : v.ranges()) d.ranges.push_back({r, clock_ms(now)});
          reply = d;
        } else if constexpr (is<M, RequestOrientation>) {
          reply = OrientationData{0, 0, left_handed(v.yaw())};
        } else if constexpr (is<M, RequestRotationalRates>) {
          reply = RotationalRateData{0, 0, clamp(left_handed(v.yaw_rate()), -31.4, 31.4)};
        } else if constexpr (is<M, RequestAcceleration>) {
          reply = AccelerationData{clamp(v.longitudinal_accel(), -32, 32), clamp(v.linear_speed() * v.yaw_rate(), -32, 32), 9.81};
        } else if constexpr (is<M, RequestSixAxis>) {
          reply = SixAxisData{clamp(v.longitudinal_accel(), -32, 32), clamp(v.linear_speed() * v.yaw_rate(), -32, 32), 9.81,
                              0, 0, clamp(v.yaw_rate(), -31.4, 31.4)};
        } else if constexpr (is<M, RequestSixAxisOrientation>) {
          reply = SixAxisOrientationData{0, 0, v.yaw(),
                                         clamp(v.longitudinal_accel(), -32, 32), clamp(v.linear_speed() * v.yaw_rate(), -32, 32), 9.81,
                                         0, 0, clamp(v.yaw_rate(), -31.4, 31.4)};
        } else if constexpr (is<M, RequestMagnetometer>) {
          // Horizontal field towards magnetic north, seen from the body frame.
          reply = MagnetometerData{0.2 * std::cos(v.yaw()), -0.2 * std::sin(v.yaw()), -0.4};
        } else if constexpr (is<M, RequestEncoders>) {
          reply = EncoderData{{EncoderReading{v.left().travel, v.left().speed}, EncoderReading{v.right().travel, v.right().speed}}};
        } else if constexpr (is<M, RequestRawEncoders>) {
          reply = RawEncoderData{{v.ticks(0), v.ticks(1)}};
        } else if constexpr (is<M, RequestEncoderConfig>) {
          reply = EncoderConfigData{v.encoder_settings()};
        } else if constexpr (is<M, RequestAbsoluteJoints>) {
          AbsoluteJointsData d;
          for (const auto& j : v.joints()) d.angles.push_back(j.target);
          reply = d;
        } else if constexpr (is<M, RequestRelativeJoints>) {
          RelativeJointsData d;
          for (const auto& j : v.joints()) d.angles.push_back(j.relative_target);
          reply = d;
        } else if constexpr (is<M, RequestJointControl>) {
          JointControlData d;
          d.joint = m.joint;
          d.constants = v.joints().at(m.joint).constants;
          reply = d;
        } else if constexpr (is<M, RequestJointHoming>) {
          JointHomingData d;
          for (const auto& j : v.joints()) d.status.push_back(j.homing);
          reply = d;
        } else if constexpr (is<M, RequestJointTorques>) {
          JointTorqueData d;
          for (const auto& j : v.joints()) d.torques.push_back(j.torque);
          reply = d;
        } else if constexpr (is<M, RequestEndEffectorPosition>) {
          const auto p = v.end_effector_pose();
          EndEffectorPositionData d;
          d.x = p[0]; d.y = p[1]; d.z = p[2];
          reply = d;
        } else if constexpr (is<M, RequestEndEffectorPoseSetpoint> || is<M, RequestEndEffectorPose>) {
          const auto p = v.end_effector_pose();
          std::conditional_t<is<M, RequestEndEffectorPose>, EndEffectorPoseData, EndEffectorPoseSetpointData> d;
          d.x = p[0]; d.y = p[1]; d.z = p[2]; d.roll = p[3]; d.pitch = p[4]; d.yaw = p[5];
          reply = d;
        }
      },
      request);
  return reply;
}

}  // namespace jaus::clearpath::sim
