#include "jaus/components/primitive_manipulator.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

#include "jaus/components/manipulator_reports.hpp"

namespace jaus::components {

using namespace rt;

namespace {

std::string seconds_text(Duration d) {
  return std::to_string(std::chrono::duration<double>(d).count()).substr(0, 5) + " s";
}

double control_period_s(const PrimitiveManipulatorOptions& o) {
  const double rate = std::isfinite(o.control_rate_hz) ? std::clamp(o.control_rate_hz, 1.0, 1000.0) : 50.0;
  return 1.0 / rate;
}

const char* position_unit(const JointConfig& j) { return j.prismatic ? "m" : "rad"; }
const char* velocity_unit(const JointConfig& j) { return j.prismatic ? "m/s" : "rad/s"; }

// Values within the wire's slack of a limit, on the limit.
void clamp_to(std::vector<double>& values, const ArmConfig& config, bool velocities) {
  for (std::size_t i = 0; i < values.size() && i < config.joints.size(); ++i) {
    const JointConfig& j = config.joints[i];
    values[i] = velocities ? std::clamp(values[i], -j.max_velocity, j.max_velocity)
                           : std::clamp(values[i], j.min_position, j.max_position);
  }
}

}  // namespace

PrimitiveManipulator::PrimitiveManipulator(ComponentConfig config, Environment env, ManipulatorArm& arm,
                                           PrimitiveManipulatorOptions options)
    : Component(std::move(config), std::move(env)),
      arm_(arm),
      options_(options),
      kinematics_(std::make_unique<kinematics::ArmKinematics>(arm.geometry())),
      tool_point_(options.tool_point),
      commanded_efforts_(arm.geometry().joints.size(), 0.0) {
  using namespace msg;
  // Commands that move the arm: the controller's, in Ready only (the base
  // refuses the rest and counts them; they never reach the arm).
  handle<SetJointEfforts>(Access::controller, /*ready_only=*/true,
                          [this](const Header& h, const SetJointEfforts& m) { on_set_joint_efforts(h, m); });
  handle<SetJointPositions>(Access::controller, true,
                            [this](const Header& h, const SetJointPositions& m) { on_set_joint_positions(h, m); });
  handle<SetJointVelocities>(Access::controller, true,
                             [this](const Header& h, const SetJointVelocities& m) { on_set_joint_velocities(h, m); });
  handle<SetToolPoint>(Access::controller, true,
                       [this](const Header& h, const SetToolPoint& m) { on_set_tool_point(h, m); });
  handle<SetEndEffectorPose>(Access::controller, true,
                             [this](const Header& h, const SetEndEffectorPose& m) { on_set_end_effector_pose(h, m); });
  handle<SetEndEffectorVelocityState>(
      Access::controller, true,
      [this](const Header& h, const SetEndEffectorVelocityState& m) { on_set_end_effector_velocity(h, m); });
  handle<SetJointMotion>(Access::controller, true,
                         [this](const Header& h, const SetJointMotion& m) { on_set_joint_motion(h, m); });
  handle<SetEndEffectorPathMotion>(
      Access::controller, true,
      [this](const Header& h, const SetEndEffectorPathMotion& m) { on_set_path_motion(h, m); });

  // Queries: anyone.
  handle<QueryManipulatorSpecifications>(Access::anyone, false, [this](const Header& h, const auto&) {
    send(h.source, specifications_report());
  });
  handle<QueryJointEfforts>(Access::anyone, false,
                            [this](const Header& h, const auto&) { send(h.source, joint_efforts_report()); });
  handle<QueryJointPositions>(Access::anyone, false,
                              [this](const Header& h, const auto&) { send(h.source, joint_positions_report()); });
  handle<QueryJointVelocities>(Access::anyone, false,
                               [this](const Header& h, const auto&) { send(h.source, joint_velocities_report()); });
  handle<QueryToolPoint>(Access::anyone, false,
                         [this](const Header& h, const auto&) { send(h.source, tool_point_report()); });
  handle<QueryJointForceTorques>(Access::anyone, false, [this](const Header& h, const auto&) {
    send(h.source, joint_force_torques_report());
  });

  // The same reports on service connections (no presence vectors: 0).
  provide<ReportManipulatorSpecifications>(0, [this] { return specifications_report(); });
  provide<ReportJointEfforts>(0, [this] { return joint_efforts_report(); });
  provide<ReportJointPositions>(0, [this] { return joint_positions_report(); });
  provide<ReportJointVelocities>(0, [this] { return joint_velocities_report(); });
  provide<ReportToolPoint>(0, [this] { return tool_point_report(); });
  provide<ReportJointForceTorques>(0, [this] { return joint_force_torques_report(); });
}

PrimitiveManipulator::~PrimitiveManipulator() {
  cancel_timer(control_timer_);
  cancel_timer(command_timer_);
}

bool PrimitiveManipulator::initialize() {
  const ArmConfig& geometry = arm_.geometry();
  if (auto ok = check_arm_config(geometry); !ok) {
    // A controller's Reset runs this again: limited like the rest of what a Reset repeats.
    log_repeated({"arm configurations refused", kNoteworthyBurst}, LogLevel::error,
                 [&] { return "cannot run the arm: " + ok.error().message(); });
    return false;
  }
  if (!losses_written_)
    for (const std::string& loss : specification_losses(geometry)) log(LogLevel::warn, loss);
  losses_written_ = true;
  return true;
}

void PrimitiveManipulator::state_changed(PrimaryStatus before, PrimaryStatus after) {
  // Only a Reset enters Initialize from another state; the base has already
  // stopped the arm (command_stop). Homing moves it: never under an emergency.
  if (after != PrimaryStatus::initialize || before == PrimaryStatus::initialize) return;
  if (emergency().active()) {
    log_repeated({"resets of the arm", kNoteworthyBurst}, LogLevel::info,
                 [] { return std::string("reset: arm not homed (emergency latched)"); });
    return;
  }
  arm_.home();
  log_repeated({"resets of the arm", kNoteworthyBurst}, LogLevel::info,
               [] { return std::string("reset: arm homing"); });
}

// ---- Reports ----------------------------------------------------------------

std::optional<kinematics::Pose> PrimitiveManipulator::end_effector_pose() const {
  auto q = current_positions();
  if (!q) return std::nullopt;
  return kinematics_->tool_pose(*q, tool_point_);
}

msg::ReportManipulatorSpecifications PrimitiveManipulator::specifications_report() const {
  msg::ReportManipulatorSpecifications report;
  static_cast<msg::ManipulatorSpecificationsBody&>(report) = to_specifications_body(arm_.geometry());
  return report;
}

namespace {
// A sample's per-joint values, or zeros when the arm has none of that kind.
std::vector<double> per_joint(const std::optional<JointSample>& s, std::vector<double> JointSample::*field,
                              std::size_t n) {
  if (s && ((*s).*field).size() == n) return (*s).*field;
  return std::vector<double>(n, 0.0);
}
}  // namespace

msg::ReportJointEfforts PrimitiveManipulator::joint_efforts_report() const {
  msg::ReportJointEfforts report;
  const auto s = arm_.sample();
  const std::size_t n = arm_.geometry().joints.size();
  report.efforts_percent = s && s->efforts_percent.size() == n ? s->efforts_percent : commanded_efforts_;
  for (double& e : report.efforts_percent) e = std::isfinite(e) ? std::clamp(e, -100.0, 100.0) : 0.0;
  return report;
}

msg::ReportJointPositions PrimitiveManipulator::joint_positions_report() const {
  msg::ReportJointPositions report;
  const ArmConfig& g = arm_.geometry();
  report.positions_rad =
      joint_values_to_wire(g, per_joint(arm_.sample(), &JointSample::positions, g.joints.size()), JointQuantity::position);
  return report;
}

msg::ReportJointVelocities PrimitiveManipulator::joint_velocities_report() const {
  msg::ReportJointVelocities report;
  const ArmConfig& g = arm_.geometry();
  report.velocities_rps = joint_values_to_wire(g, per_joint(arm_.sample(), &JointSample::velocities, g.joints.size()),
                                               JointQuantity::velocity);
  return report;
}

msg::ReportToolPoint PrimitiveManipulator::tool_point_report() const {
  msg::ReportToolPoint report;
  report.x_m = tool_point_.x;
  report.y_m = tool_point_.y;
  report.z_m = tool_point_.z;
  return report;
}

msg::ReportJointForceTorques PrimitiveManipulator::joint_force_torques_report() const {
  msg::ReportJointForceTorques report;
  const ArmConfig& g = arm_.geometry();
  report.force_torques_nm = joint_values_to_wire(
      g, per_joint(arm_.sample(), &JointSample::force_torques, g.joints.size()), JointQuantity::force_torque);
  return report;
}

// ---- Checks -----------------------------------------------------------------

std::optional<PrimitiveManipulator::Problem> PrimitiveManipulator::check_count(std::size_t count) const {
  const std::size_t n = arm_.geometry().joints.size();
  if (count == n) return std::nullopt;
  return Problem{Refusal::joint_count,
                 std::to_string(count) + " joint values for an arm of " + std::to_string(n) + " joints"};
}

std::optional<PrimitiveManipulator::Problem> PrimitiveManipulator::check_positions(
    const std::vector<double>& positions) const {
  const ArmConfig& g = arm_.geometry();
  for (std::size_t i = 0; i < positions.size() && i < g.joints.size(); ++i) {
    const JointConfig& j = g.joints[i];
    const double v = positions[i];
    if (std::isfinite(v) && v >= j.min_position - kJointLimitSlack && v <= j.max_position + kJointLimitSlack)
      continue;
    std::ostringstream why;
    why << joint_label(g, i) << ": position " << v << " " << position_unit(j) << " outside its limits ["
        << j.min_position << ", " << j.max_position << "]";
    return Problem{Refusal::out_of_limits, why.str()};
  }
  return std::nullopt;
}

std::optional<PrimitiveManipulator::Problem> PrimitiveManipulator::check_velocities(
    const std::vector<double>& velocities) const {
  const ArmConfig& g = arm_.geometry();
  for (std::size_t i = 0; i < velocities.size() && i < g.joints.size(); ++i) {
    const JointConfig& j = g.joints[i];
    const double v = velocities[i];
    if (std::isfinite(v) && std::abs(v) <= j.max_velocity + kJointLimitSlack) continue;
    std::ostringstream why;
    why << joint_label(g, i) << ": velocity " << v << " " << velocity_unit(j) << " beyond its speed limit "
        << j.max_velocity;
    return Problem{Refusal::out_of_limits, why.str()};
  }
  return std::nullopt;
}

Expected<std::vector<double>> PrimitiveManipulator::current_positions() const {
  const auto s = arm_.sample();
  if (!s) return unexpected(make_error(ErrorCode::refused, "the arm has not reported its position yet"));
  if (s->positions.size() != arm_.geometry().joints.size())
    return unexpected(make_error(ErrorCode::refused, "the arm reports " + std::to_string(s->positions.size()) +
                                                         " joints, its geometry has " +
                                                         std::to_string(arm_.geometry().joints.size())));
  return s->positions;
}

// The joint rates for an end-effector velocity from where the arm is now.
// Strict (a new command): a twist the joints miss, or rates beyond a speed
// limit, are errors. Otherwise (streaming it): rates beyond the limits are
// scaled down together, which keeps the direction of the motion.
Expected<std::vector<double>> PrimitiveManipulator::twist_rates(const msg::EndEffectorVelocityStateBody& body,
                                                                bool strict) const {
  auto q = current_positions();
  if (!q) return unexpected(q.error());
  const kinematics::Transform effector = kinematics_->end_effector_frame(*q);
  auto twist = to_tool_twist(body, effector, effector * tool_point_);
  if (!twist) return unexpected(twist.error());
  const kinematics::JointRates rates = kinematics_->joint_rates(*q, tool_point_, twist->linear, twist->angular);
  const ArmConfig& g = arm_.geometry();
  if (strict) {
    const double size = kinematics::norm(twist->linear) + kinematics::norm(twist->angular);
    if (!(rates.residual <= 1e-3 + options_.twist_tolerance * size)) {
      std::ostringstream why;
      why << "the joints cannot give this end-effector velocity here (missed by " << rates.residual << ")";
      return unexpected(make_error(ErrorCode::out_of_range, why.str()));
    }
    if (auto problem = check_velocities(rates.rates))
      return unexpected(make_error(ErrorCode::invalid_argument, "it needs " + problem->why));
  }
  double over = 1;
  for (std::size_t i = 0; i < rates.rates.size(); ++i)
    over = std::max(over, std::abs(rates.rates[i]) / g.joints[i].max_velocity);
  std::vector<double> out = rates.rates;
  for (double& r : out) r /= over;
  clamp_to(out, g, /*velocities=*/true);
  return out;
}

void PrimitiveManipulator::refuse(const Header& h, std::string_view what, const Problem& problem) {
  // A controller can repeat any refusal at will: one kind per reason, so that
  // a flood of one reason leaves the others (and the arm's holds) written.
  Repeated kind{"arm commands refused by the arm", kNoteworthyBurst};
  switch (problem.kind) {
    case Refusal::joint_count:
      ++counters_.refused_joint_count;
      kind = {"arm commands with a wrong joint count refused", kNoteworthyBurst};
      break;
    case Refusal::out_of_limits:
      ++counters_.refused_out_of_limits;
      kind = {"arm commands beyond the joint limits refused", kNoteworthyBurst};
      break;
    case Refusal::unreachable:
      ++counters_.refused_unreachable;
      kind = {"arm commands out of reach refused", kNoteworthyBurst};
      break;
    case Refusal::arm:
      ++counters_.refused_by_arm;
      break;
  }
  log_repeated(kind, LogLevel::warn, [&] {
    return std::string(what) + " from " + h.source.to_string() + " refused (nothing moved): " + problem.why;
  });
}

// ---- Commands ---------------------------------------------------------------

void PrimitiveManipulator::end_motion() {
  cancel_timer(control_timer_);
  cancel_timer(command_timer_);
  trajectory_.reset();
  twist_.reset();
}

bool PrimitiveManipulator::command_arm(const Header& h, std::string_view what, const Expected<void>& result,
                                       Motion motion) {
  if (!result) {
    refuse(h, what, {Refusal::arm, "the arm: " + result.error().message()});
    arm_.hold();  // the previous command has been ended: hold rather than leave it running
    ++counters_.holds;
    motion_ = Motion::holding;
    return false;
  }
  motion_ = motion;
  ++counters_.commands_applied;
  if (motion != Motion::efforts) std::fill(commanded_efforts_.begin(), commanded_efforts_.end(), 0.0);
  return true;
}

void PrimitiveManipulator::on_set_joint_efforts(const Header& h, const msg::SetJointEfforts& m) {
  const ArmConfig& g = arm_.geometry();
  std::vector<double> efforts = m.efforts_percent;
  if (auto p = check_count(efforts.size())) return refuse(h, msg::SetJointEfforts::name, *p);
  for (std::size_t i = 0; i < efforts.size(); ++i) {
    if (std::isfinite(efforts[i]) && std::abs(efforts[i]) <= 100 + kJointLimitSlack) {
      efforts[i] = std::clamp(efforts[i], -100.0, 100.0);
      continue;
    }
    std::ostringstream why;
    why << joint_label(g, i) << ": effort " << efforts[i] << " % beyond +-100 %";
    return refuse(h, msg::SetJointEfforts::name, {Refusal::out_of_limits, why.str()});
  }
  end_motion();
  if (!command_arm(h, msg::SetJointEfforts::name, arm_.apply_efforts(efforts), Motion::efforts)) return;
  commanded_efforts_ = efforts;
  arm_command_timeout();
}

void PrimitiveManipulator::on_set_joint_positions(const Header& h, const msg::SetJointPositions& m) {
  const ArmConfig& g = arm_.geometry();
  if (auto p = check_count(m.positions_rad.size())) return refuse(h, msg::SetJointPositions::name, *p);
  std::vector<double> positions = joint_values_from_wire(g, m.positions_rad, JointQuantity::position);
  if (auto p = check_positions(positions)) return refuse(h, msg::SetJointPositions::name, *p);
  clamp_to(positions, g, false);
  end_motion();  // a position target needs no renewal: no command timeout
  command_arm(h, msg::SetJointPositions::name, arm_.move_to_positions(positions), Motion::positions);
}

void PrimitiveManipulator::on_set_joint_velocities(const Header& h, const msg::SetJointVelocities& m) {
  const ArmConfig& g = arm_.geometry();
  if (auto p = check_count(m.velocities_rps.size())) return refuse(h, msg::SetJointVelocities::name, *p);
  std::vector<double> velocities = joint_values_from_wire(g, m.velocities_rps, JointQuantity::velocity);
  if (auto p = check_velocities(velocities)) return refuse(h, msg::SetJointVelocities::name, *p);
  clamp_to(velocities, g, true);
  end_motion();
  if (command_arm(h, msg::SetJointVelocities::name, arm_.move_at_velocities(velocities), Motion::velocities))
    arm_command_timeout();
}

// The tool point moves nothing by itself: it changes which point the
// end-effector commands and the end-effector pose are about.
void PrimitiveManipulator::on_set_tool_point(const Header& h, const msg::SetToolPoint& m) {
  tool_point_ = {m.x_m, m.y_m, m.z_m};
  ++counters_.commands_applied;
  std::ostringstream text;
  text << "tool point set to (" << m.x_m << ", " << m.y_m << ", " << m.z_m << ") m by " << h.source.to_string();
  log_repeated({"tool points set", kNoteworthyBurst}, LogLevel::info, [&] { return text.str(); });
}

void PrimitiveManipulator::on_set_end_effector_pose(const Header& h, const msg::SetEndEffectorPose& m) {
  constexpr std::string_view what = msg::SetEndEffectorPose::name;
  const double qn = std::sqrt(m.quaternion_d * m.quaternion_d + m.quaternion_a * m.quaternion_a +
                              m.quaternion_b * m.quaternion_b + m.quaternion_c * m.quaternion_c);
  if (!(qn > 0.5)) return refuse(h, what, {Refusal::out_of_limits, "the orientation is not a unit quaternion"});
  auto q = current_positions();
  if (!q) return refuse(h, what, {Refusal::arm, q.error().message()});
  auto solution = kinematics_->inverse(to_pose(m), tool_point_, *q, options_.ik);
  if (!solution) return refuse(h, what, {Refusal::unreachable, "pose unreachable: " + solution.error().message()});
  end_motion();
  command_arm(h, what, arm_.move_to_positions(*solution), Motion::positions);
}

void PrimitiveManipulator::on_set_end_effector_velocity(const Header& h, const msg::SetEndEffectorVelocityState& m) {
  constexpr std::string_view what = msg::SetEndEffectorVelocityState::name;
  auto rates = twist_rates(m, /*strict=*/true);
  if (!rates) {
    // refused: no sample; invalid_argument: a bad field or a speed limit; out_of_range: the kinematics.
    const ErrorCode code = rates.error().code;
    const Refusal kind = code == ErrorCode::refused            ? Refusal::arm
                         : code == ErrorCode::invalid_argument ? Refusal::out_of_limits
                                                               : Refusal::unreachable;
    return refuse(h, what, {kind, rates.error().message()});
  }
  end_motion();
  if (!command_arm(h, what, arm_.move_at_velocities(*rates), Motion::end_effector_velocity)) return;
  twist_ = static_cast<const msg::EndEffectorVelocityStateBody&>(m);
  schedule_control_tick();
  arm_command_timeout();
}

void PrimitiveManipulator::on_set_joint_motion(const Header& h, const msg::SetJointMotion& m) {
  constexpr std::string_view what = msg::SetJointMotion::name;
  const ArmConfig& g = arm_.geometry();
  if (auto p = check_count(m.joint_count)) return refuse(h, what, *p);
  std::vector<TimedJointPose> poses;
  for (std::size_t k = 0; k < m.poses.size(); ++k) {
    const msg::JointMotionPose& in = m.poses[k];
    const std::string where = "pose " + std::to_string(k + 1) + ": ";
    if (auto p = check_count(in.joints.size())) return refuse(h, what, {p->kind, where + p->why});
    TimedJointPose pose;
    pose.time_s = in.time_s;
    for (std::size_t i = 0; i < in.joints.size(); ++i) {
      const JointConfig& j = g.joints[i];
      const msg::JointMotionPoint& point = in.joints[i];
      pose.positions.push_back(joint_value_from_wire(point.position_rad, j.prismatic, JointQuantity::position));
      const double velocity = joint_value_from_wire(point.max_velocity_rps, j.prismatic, JointQuantity::velocity);
      // A max velocity of 0 means the joint's own speed limit; accelerations of 0 are not limited.
      pose.limits.push_back(
          {velocity == 0 ? j.max_velocity : std::abs(velocity),
           joint_value_from_wire(point.max_acceleration_rps2, j.prismatic, JointQuantity::acceleration),
           joint_value_from_wire(point.max_deceleration_rps2, j.prismatic, JointQuantity::acceleration)});
    }
    if (auto p = check_positions(pose.positions)) return refuse(h, what, {p->kind, where + p->why});
    std::vector<double> speeds;
    for (const auto& l : pose.limits) speeds.push_back(l.max_velocity);
    if (auto p = check_velocities(speeds))
      return refuse(h, what, {p->kind, "pose " + std::to_string(k + 1) + " max velocity: " + p->why});
    clamp_to(pose.positions, g, false);
    for (std::size_t i = 0; i < pose.limits.size(); ++i)
      pose.limits[i].max_velocity = std::min(pose.limits[i].max_velocity, g.joints[i].max_velocity);
    poses.push_back(std::move(pose));
  }
  auto q = current_positions();
  if (!q) return refuse(h, what, {Refusal::arm, q.error().message()});
  auto trajectory = JointTrajectory::plan(g, *q, poses);
  if (!trajectory) return refuse(h, what, {Refusal::unreachable, trajectory.error().message()});
  end_motion();
  ++counters_.commands_applied;
  start_trajectory(std::move(*trajectory), Motion::joint_motion);
}

// Each pose through the inverse kinematics (seeded with the previous pose's
// joints, so the arm takes the nearest solution), then in joint space from
// pose to pose at constant joint speeds: the tool passes through every pose
// at its time; between poses its path is not a straight line.
void PrimitiveManipulator::on_set_path_motion(const Header& h, const msg::SetEndEffectorPathMotion& m) {
  constexpr std::string_view what = msg::SetEndEffectorPathMotion::name;
  const ArmConfig& g = arm_.geometry();
  auto q = current_positions();
  if (!q) return refuse(h, what, {Refusal::arm, q.error().message()});
  std::vector<TimedJointPose> poses;
  std::vector<double> seed = *q;
  for (std::size_t k = 0; k < m.poses.size(); ++k) {
    const msg::EndEffectorPathPose& in = m.poses[k];
    const std::string where = "pose " + std::to_string(k + 1) + ": ";
    const double qn = std::sqrt(in.quaternion_d * in.quaternion_d + in.quaternion_a * in.quaternion_a +
                                in.quaternion_b * in.quaternion_b + in.quaternion_c * in.quaternion_c);
    if (!(qn > 0.5))
      return refuse(h, what, {Refusal::out_of_limits, where + "the orientation is not a unit quaternion"});
    auto solution = kinematics_->inverse(to_pose(in), tool_point_, seed, options_.ik);
    if (!solution) return refuse(h, what, {Refusal::unreachable, where + "unreachable: " + solution.error().message()});
    TimedJointPose pose;
    pose.time_s = in.time_s;
    pose.positions = *solution;
    for (const JointConfig& j : g.joints) pose.limits.push_back({j.max_velocity, 0, 0});
    seed = *solution;
    poses.push_back(std::move(pose));
  }
  auto trajectory = JointTrajectory::plan(g, *q, poses);
  if (!trajectory) return refuse(h, what, {Refusal::unreachable, trajectory.error().message()});
  end_motion();
  ++counters_.commands_applied;
  start_trajectory(std::move(*trajectory), Motion::path_motion);
}

// ---- Streaming: timed motions and end-effector velocity ---------------------

void PrimitiveManipulator::start_trajectory(JointTrajectory trajectory, Motion motion) {
  std::fill(commanded_efforts_.begin(), commanded_efforts_.end(), 0.0);
  trajectory_ = std::move(trajectory);
  trajectory_started_ = env().clock.now();
  motion_ = motion;
  control_tick();
}

void PrimitiveManipulator::schedule_control_tick() {
  cancel_timer(control_timer_);
  const auto period = std::chrono::duration_cast<Duration>(std::chrono::duration<double>(control_period_s(options_)));
  control_timer_ = env().scheduler.call_at(env().clock.now() + period, [this] {
    control_timer_ = kNoTimer;
    control_tick();
  });
}

// A timed motion: the arm is sent the setpoint one period ahead, which it
// reaches (moving at its speed limits, at least the profile's speed) by the
// next tick. An end-effector velocity: joint rates again from where the arm is now.
void PrimitiveManipulator::control_tick() {
  if (trajectory_) {
    const double period = control_period_s(options_);
    const double lead = std::chrono::duration<double>(env().clock.now() - trajectory_started_).count() + period;
    const bool last = lead >= trajectory_->duration_s();
    auto moved = arm_.move_to_positions(trajectory_->at(lead));
    if (!moved) {
      // A controller can start timed motions in a loop: these lines are limited.
      log_repeated({"timed motions ended by the arm", kNoteworthyBurst}, LogLevel::error,
                   [&] { return "timed motion ended: the arm refused a setpoint: " + moved.error().message(); });
      ++counters_.refused_by_arm;
      stop_platform("timed motion refused by the arm");
      return;
    }
    if (last) {
      trajectory_.reset();
      ++counters_.motions_completed;
      motion_ = Motion::positions;  // holding the last pose: a position target
      log_repeated({"timed motions completed", kNoteworthyBurst}, LogLevel::info,
                   [] { return std::string("timed motion sent its last pose"); });
      return;
    }
  } else if (twist_) {
    auto rates = twist_rates(*twist_, /*strict=*/false);
    auto moved = rates ? arm_.move_at_velocities(*rates) : Expected<void>(unexpected(rates.error()));
    if (!moved) {
      log_repeated({"end-effector velocities ended by the arm", kNoteworthyBurst}, LogLevel::error,
                   [&] { return "end-effector velocity ended: " + moved.error().message(); });
      ++counters_.refused_by_arm;
      stop_platform("end-effector velocity ended");
      return;
    }
  } else {
    return;
  }
  schedule_control_tick();
}

// ---- Safety -----------------------------------------------------------------

// Each velocity, effort or end-effector velocity command restarts the
// command timeout; when it runs out, the arm holds, as if the controller
// had gone (a lost link that the controller's liveness would notice only
// after seconds). Control is kept: the next command moves the arm again.
void PrimitiveManipulator::arm_command_timeout() {
  cancel_timer(command_timer_);
  if (options_.command_timeout <= Duration::zero()) return;
  command_timer_ = env().scheduler.call_at(env().clock.now() + options_.command_timeout, [this] {
    command_timer_ = kNoTimer;
    if (motion_ != Motion::efforts && motion_ != Motion::velocities && motion_ != Motion::end_effector_velocity)
      return;
    ++counters_.command_timeouts;
    stop_platform("no new velocity or effort command for " + seconds_text(options_.command_timeout));
  });
}

void PrimitiveManipulator::cancel_timer(TimerId& timer) {
  if (timer == kNoTimer) return;
  env().scheduler.cancel(timer);
  timer = kNoTimer;
}

// Safety: the one place the arm is told to stop (see the header): it holds
// where it is. Any timed motion or streamed velocity is cancelled and no
// command is kept, so nothing resumes it.
void PrimitiveManipulator::command_stop(std::string_view why) {
  end_motion();
  arm_.hold();
  ++counters_.holds;
  motion_ = Motion::holding;
  std::fill(commanded_efforts_.begin(), commanded_efforts_.end(), 0.0);
  // Every Standby, Emergency, release or takeover holds the arm: a peer looping them is
  // one line per hold up to the burst, then a count (the hold itself is never limited).
  log_repeated({"arm holds", kNoteworthyBurst}, LogLevel::info, [&] { return "arm holding: " + std::string(why); });
}

}  // namespace jaus::components
