#include "jaus/bridge/clearpath_arm.hpp"

#include "command_stream.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <deque>
#include <functional>
#include <numbers>
#include <set>
#include <sstream>
#include <tuple>
#include <utility>

namespace jaus::bridge {

namespace cp = clearpath;
using components::ArmConfig;
using components::JointSample;
using components::kJointLimitSlack;

using detail::CommandStream;
using detail::number_text;
using detail::outcome_text;

namespace {

constexpr double kPi = std::numbers::pi;  // Clearpath joint angles: [-pi, pi]

// The JAUS range of a joint the platform can reach: its limits within
// Clearpath's +-pi after mapping (lo > hi: none).
std::pair<double, double> reachable(const components::JointConfig& joint, const ClearpathJointMapping& map) {
  double a = map.sign * (-kPi - map.offset_rad), b = map.sign * (kPi - map.offset_rad);
  if (a > b) std::swap(a, b);
  return {std::max(joint.min_position, a), std::min(joint.max_position, b)};
}

Expected<void> refusal(ErrorCode code, std::string why) { return unexpected(make_error(code, std::move(why))); }

}  // namespace

Expected<void> check_clearpath_arm_config(const ArmConfig& arm, const ClearpathArmConfig& config) {
  const auto bad = [](std::string why) { return refusal(ErrorCode::invalid_argument, "Clearpath arm: " + why); };
  if (auto ok = components::check_arm_config(arm); !ok) return bad(ok.error().message());
  if (config.joints.size() != arm.joints.size())
    return bad(std::to_string(config.joints.size()) + " joint mappings for an arm of " +
               std::to_string(arm.joints.size()) + " joints");
  if (config.data_rate_hz < 1 || config.data_rate_hz > 100)
    return bad("data_rate_hz " + std::to_string(config.data_rate_hz) + " outside 1..100");
  if (!(config.control_rate_hz > 0 && config.control_rate_hz <= 1000))
    return bad("control_rate_hz " + number_text(config.control_rate_hz) + " outside (0, 1000]");
  std::set<std::uint8_t> ids;
  for (std::size_t i = 0; i < arm.joints.size(); ++i) {
    const auto& joint = arm.joints[i];
    const auto& map = config.joints[i];
    const std::string label = components::joint_label(arm, i);
    if (joint.prismatic) return bad(label + ": prismatic, but Clearpath joints are angles");
    if (!ids.insert(map.clearpath_joint).second)
      return bad(label + ": Clearpath joint " + std::to_string(map.clearpath_joint) + " is mapped twice");
    if (map.sign != 1 && map.sign != -1) return bad(label + ": sign " + number_text(map.sign) + " is not +1 or -1");
    if (!std::isfinite(map.offset_rad)) return bad(label + ": offset_rad is not finite");
    const auto [lo, hi] = reachable(joint, map);
    if (lo >= hi)
      return bad(label + ": limits [" + number_text(joint.min_position) + ", " + number_text(joint.max_position) +
                 "] rad are beyond Clearpath's [-pi, pi] with this sign and offset");
  }
  return {};
}

struct ClearpathArm::State {
  struct Joint {
    enum class Mode { idle, to_goal, at_rate } mode = Mode::idle;
    double lo = 0, hi = 0;  // the reachable range (JAUS rad)
    double max_velocity = 0;
    double setpoint = 0;    // the ramp: what was last sent (JAUS rad)
    double goal = 0;
    double rate = 0;

    // One step of `seconds`; false once the joint is idle.
    bool step(double seconds) {
      if (mode == Mode::to_goal) {
        const double delta = goal - setpoint, reach = max_velocity * seconds;
        if (std::abs(delta) <= reach) {
          setpoint = goal;
          mode = Mode::idle;
        } else {
          setpoint += std::copysign(reach, delta);
        }
      } else if (mode == Mode::at_rate) {
        // Stops at the nearer limit; a setpoint beyond one (the platform was
        // there) only moves back toward the range.
        const double next = setpoint + rate * seconds;
        if (rate > 0 && next >= hi) {
          setpoint = std::max(setpoint, hi);
          mode = Mode::idle;
        } else if (rate < 0 && next <= lo) {
          setpoint = std::min(setpoint, lo);
          mode = Mode::idle;
        } else {
          setpoint = next;
        }
      }
      return mode != Mode::idle;
    }
  };

  State(PlatformConnection& p, rt::Scheduler& s, ArmConfig g, ClearpathArmConfig c)
      : platform(p), scheduler(s), geometry(std::move(g)), config(std::move(c)) {}

  ~State() { cancel_timer(); }

  PlatformConnection& platform;
  rt::Scheduler& scheduler;
  ArmConfig geometry;
  ClearpathArmConfig config;
  std::vector<Joint> joints;
  std::unique_ptr<CommandStream> stream;
  ClearpathArmCounters counters;
  Motion motion = Motion::holding;
  rt::TimerId timer = rt::kNoTimer;
  rt::TimePoint stepped_at{};
  // The latest data, in the platform's terms.
  std::optional<cp::AbsoluteJointsData> setpoints;
  rt::TimePoint setpoints_at{};
  bool fresh = false;  // 0x9010 heard since the platform (last) came up: commands may start from it
  // The joints' setpoints are the platform's (what the bridge last sent, or
  // took from 0x9010); false after homing, a failed command or a lost link:
  // the next command starts from the reported setpoints.
  bool synced = false;
  std::optional<cp::JointTorqueData> torques;
  bool short_data_logged = false;

  rt::TimePoint now() const { return platform.clock().now(); }
  const ClearpathJointMapping& map(std::size_t i) const { return config.joints[i]; }
  double to_clearpath(std::size_t i, double q) const { return map(i).offset_rad + map(i).sign * q; }
  double from_clearpath(std::size_t i, double angle) const { return map(i).sign * (angle - map(i).offset_rad); }

  void build() {
    for (std::size_t i = 0; i < geometry.joints.size(); ++i) {
      Joint j;
      std::tie(j.lo, j.hi) = reachable(geometry.joints[i], map(i));
      j.max_velocity = geometry.joints[i].max_velocity;
      joints.push_back(j);
    }
    stream = std::make_unique<CommandStream>(platform.client(), counters.commands_sent,
                                             [this](const cp::AnyMessage& m, const cp::CommandOutcome& o) { failed(m, o); });
  }

  void cancel_timer() {
    if (timer != rt::kNoTimer) scheduler.cancel(timer);
    timer = rt::kNoTimer;
  }

  void stop_ramp() {
    cancel_timer();
    for (Joint& j : joints) j.mode = Joint::Mode::idle;
  }

  void failed(const cp::AnyMessage& m, const cp::CommandOutcome& outcome) {
    ++counters.commands_failed;
    const bool homing = m.holds<cp::HomeJoint>();
    const bool was_ramping = timer != rt::kNoTimer;
    if (!homing) stop_ramp();  // safety: a stream of targets the platform does not take ends here
    synced = false;
    std::string what = homing ? "Home Joint (joint " + std::to_string(m.get<cp::HomeJoint>().joint) + ")"
                              : std::string("Set Absolute Joints");
    platform.log(rt::LogLevel::warn, "Clearpath arm: " + what + " not applied (" + outcome_text(outcome) + ")" +
                                         (was_ramping && !homing ? "; motion ended" : ""));
  }

  // Positions from the latest 0x9010, or none when it does not cover every mapped joint.
  std::optional<std::vector<double>> positions() const {
    if (!setpoints) return std::nullopt;
    std::vector<double> q(joints.size());
    for (std::size_t i = 0; i < q.size(); ++i) {
      if (map(i).clearpath_joint >= setpoints->angles.size()) return std::nullopt;
      q[i] = from_clearpath(i, setpoints->angles[map(i).clearpath_joint]);
    }
    return q;
  }

  Expected<void> refuse(ErrorCode code, std::string why) {
    ++counters.refused;
    platform.log(rt::LogLevel::info, "Clearpath arm: command refused: " + why);
    return refusal(code, std::move(why));
  }

  // The common checks of a motion command; the ramp's starting point set.
  Expected<void> check(const std::vector<double>& values, const char* what, bool positions_check) {
    if (values.size() != joints.size())
      return refuse(ErrorCode::out_of_range, std::string(what) + " for " + std::to_string(values.size()) +
                                                 " joints; the arm has " + std::to_string(joints.size()));
    for (std::size_t i = 0; i < values.size(); ++i) {
      const auto& jc = geometry.joints[i];
      const double v = values[i];
      const double lo = positions_check ? jc.min_position : -jc.max_velocity;
      const double hi = positions_check ? jc.max_position : jc.max_velocity;
      const std::string label = components::joint_label(geometry, i);
      if (!std::isfinite(v) || v < lo - kJointLimitSlack || v > hi + kJointLimitSlack)
        return refuse(ErrorCode::out_of_range,
                      label + ": " + what + " " + number_text(v) + " outside [" + number_text(lo) + ", " + number_text(hi) + "]");
      if (!positions_check) continue;
      const double angle = to_clearpath(i, std::clamp(v, jc.min_position, jc.max_position));
      if (std::abs(angle) > kPi + kJointLimitSlack)
        return refuse(ErrorCode::out_of_range, label + ": position " + number_text(v) + " is " + number_text(angle) +
                                                   " rad on Clearpath joint " +
                                                   std::to_string(map(i).clearpath_joint) + ", outside [-pi, pi]");
    }
    if (!platform.alive()) return refuse(ErrorCode::io, "the Clearpath platform is not alive");
    const auto q = positions();
    if (!q || !fresh) return refuse(ErrorCode::io, "no joint data (0x9010) from the Clearpath platform yet");
    // A ramp goes on from where the last one was; after anything else, from the platform's setpoints.
    if (!synced)
      for (std::size_t i = 0; i < joints.size(); ++i) joints[i].setpoint = (*q)[i];
    synced = true;
    stream->clear();  // a new command supersedes what has not gone out (homing too)
    return {};
  }

  void start_timer() {
    if (timer != rt::kNoTimer) return;
    stepped_at = now();
    schedule();
  }

  void schedule() {
    const auto period =
        std::chrono::duration_cast<rt::Duration>(std::chrono::duration<double>(1.0 / config.control_rate_hz));
    timer = scheduler.call_at(now() + period, [this] { tick(); });
  }

  void tick() {
    timer = rt::kNoTimer;
    const rt::TimePoint t = now();
    const double seconds = std::chrono::duration<double>(t - stepped_at).count();
    stepped_at = t;
    bool active = false;
    for (Joint& j : joints) active = j.step(seconds) || active;
    send_setpoints();
    if (active) schedule();
  }

  void send_setpoints() {
    cp::SetAbsoluteJoints m;
    for (std::size_t i = 0; i < joints.size(); ++i)
      m.joints.push_back({map(i).clearpath_joint, std::clamp(to_clearpath(i, joints[i].setpoint), -kPi, kPi)});
    stream->post(std::move(m), true);
  }

  void on_setpoints(const cp::AbsoluteJointsData& d) {
    setpoints = d;
    setpoints_at = now();
    if (positions()) {
      fresh = true;
      ++counters.samples;
    } else if (!short_data_logged) {
      short_data_logged = true;
      platform.log(rt::LogLevel::warn, "Clearpath arm: 0x9010 reports " + std::to_string(d.angles.size()) +
                                           " joints, fewer than the mapping names; no joint positions");
    }
  }

  void on_alive(bool alive) {
    if (alive) return;
    const bool was_ramping = timer != rt::kNoTimer;
    stop_ramp();
    stream->clear();
    fresh = false;  // commands wait for fresh data; sample() keeps the last, with its time
    synced = false;
    motion = Motion::holding;
    if (was_ramping) platform.log(rt::LogLevel::warn, "Clearpath arm: platform lost; motion ended");
  }
};

Expected<std::unique_ptr<ClearpathArm>> ClearpathArm::make(PlatformConnection& platform, rt::Scheduler& scheduler,
                                                           ArmConfig geometry, ClearpathArmConfig config) {
  if (auto ok = check_clearpath_arm_config(geometry, config); !ok) return unexpected(ok.error());
  return std::unique_ptr<ClearpathArm>(new ClearpathArm(platform, scheduler, std::move(geometry), std::move(config)));
}

ClearpathArm::ClearpathArm(PlatformConnection& platform, rt::Scheduler& scheduler, ArmConfig geometry,
                           ClearpathArmConfig config)
    : state_(std::make_shared<State>(platform, scheduler, std::move(geometry), std::move(config))) {
  State& s = *state_;
  s.build();
  std::weak_ptr<State> weak = state_;
  platform.on_data(cp::AbsoluteJointsData::kType, [weak](const cp::Envelope& e) {
    const auto self = weak.lock();
    if (!self) return;
    if (const auto* d = e.message.get_if<cp::AbsoluteJointsData>()) self->on_setpoints(*d);
  });
  platform.on_data(cp::JointTorqueData::kType, [weak](const cp::Envelope& e) {
    const auto self = weak.lock();
    if (!self) return;
    if (const auto* d = e.message.get_if<cp::JointTorqueData>()) self->torques = *d;
  });
  platform.on_alive([weak](bool alive) {
    if (const auto self = weak.lock()) self->on_alive(alive);
  });
  const auto subscribed = [weak](const char* what) {
    return [weak, what](const cp::CommandOutcome& outcome) {
      const auto self = weak.lock();
      if (!self || outcome.ok()) return;
      self->platform.log(rt::LogLevel::warn, std::string("Clearpath arm: ") + what + " subscription not applied (" +
                                                 detail::subscription_outcome_text(outcome) + ")");
    };
  };
  cp::RequestAbsoluteJoints joints;
  joints.subscription = s.config.data_rate_hz;
  platform.client().subscribe(joints, subscribed("joint setpoint (0x5010)"));
  cp::RequestJointTorques torques;
  torques.subscription = s.config.data_rate_hz;
  platform.client().subscribe(torques, subscribed("joint torque (0x5014)"));
}

ClearpathArm::~ClearpathArm() = default;

const ArmConfig& ClearpathArm::geometry() const { return state_->geometry; }

Expected<void> ClearpathArm::move_to_positions(const std::vector<double>& positions) {
  State& s = *state_;
  if (auto ok = s.check(positions, "position", true); !ok) return ok;
  for (std::size_t i = 0; i < s.joints.size(); ++i) {
    auto& j = s.joints[i];
    j.goal = std::clamp(positions[i], j.lo, j.hi);
    j.mode = j.goal == j.setpoint ? State::Joint::Mode::idle : State::Joint::Mode::to_goal;
  }
  s.motion = Motion::positions;
  s.start_timer();
  return {};
}

Expected<void> ClearpathArm::move_at_velocities(const std::vector<double>& velocities) {
  State& s = *state_;
  if (auto ok = s.check(velocities, "velocity", false); !ok) return ok;
  for (std::size_t i = 0; i < s.joints.size(); ++i) {
    auto& j = s.joints[i];
    j.rate = std::clamp(velocities[i], -j.max_velocity, j.max_velocity);
    j.mode = j.rate == 0 ? State::Joint::Mode::idle : State::Joint::Mode::at_rate;
  }
  s.motion = Motion::velocities;
  s.start_timer();
  return {};
}

Expected<void> ClearpathArm::apply_efforts(const std::vector<double>&) {
  return state_->refuse(ErrorCode::refused,
                        "joint efforts: the Clearpath protocol has no joint effort command (use positions or velocities)");
}

void ClearpathArm::hold() {
  State& s = *state_;
  s.stop_ramp();
  s.motion = Motion::holding;
  s.stream->clear();
  if (!s.platform.alive()) return;  // the platform keeps its last setpoint; nothing goes out
  if (s.synced) {
    // Where the bridge's targets are: the platform's setpoint, up to the step
    // not yet sent. The reported setpoints are a little older; going back to
    // them would reverse the joints.
    s.send_setpoints();
    return;
  }
  const auto q = s.positions();
  if (!q || !s.fresh) return;  // no data: nothing was sent since the platform came up
  for (std::size_t i = 0; i < s.joints.size(); ++i) s.joints[i].setpoint = (*q)[i];
  s.synced = true;
  cp::SetAbsoluteJoints m;
  for (std::size_t i = 0; i < s.joints.size(); ++i) {  // exactly what the platform reported, in its own terms
    const std::uint8_t id = s.map(i).clearpath_joint;
    m.joints.push_back({id, s.setpoints->angles[id]});
  }
  s.stream->post(std::move(m), true);
}

std::optional<JointSample> ClearpathArm::sample() const {
  const State& s = *state_;
  auto q = s.positions();
  if (!q) return std::nullopt;
  JointSample sample;
  sample.positions = std::move(*q);
  if (s.torques) {
    std::vector<double> torques(s.joints.size());
    bool covered = true;
    for (std::size_t i = 0; i < torques.size() && covered; ++i) {
      const std::uint8_t id = s.map(i).clearpath_joint;
      covered = id < s.torques->torques.size();
      if (covered) torques[i] = s.map(i).sign * s.torques->torques[id];
    }
    if (covered) sample.force_torques = std::move(torques);
  }
  sample.sampled_at = s.setpoints_at;
  return sample;
}

void ClearpathArm::home() {
  State& s = *state_;
  if (!s.platform.alive()) {
    s.platform.log(rt::LogLevel::warn, "Clearpath arm: homing skipped: the Clearpath platform is not alive");
    return;
  }
  s.stop_ramp();
  s.stream->clear();
  s.synced = false;
  for (std::size_t i = 0; i < s.joints.size(); ++i) s.stream->post(cp::HomeJoint{s.map(i).clearpath_joint}, false);
  s.motion = Motion::homing;
  ++s.counters.homings;
  s.platform.log(rt::LogLevel::info, "Clearpath arm: homing " + std::to_string(s.joints.size()) + " joints (0x1013)");
}

ClearpathArm::Motion ClearpathArm::motion() const { return state_->motion; }
bool ClearpathArm::ramping() const { return state_->timer != rt::kNoTimer; }
const ClearpathArmConfig& ClearpathArm::config() const { return state_->config; }
const ClearpathArmCounters& ClearpathArm::counters() const { return state_->counters; }

}  // namespace jaus::bridge
