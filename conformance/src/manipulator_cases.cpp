// The primitive manipulator cases (Part 3, manipulator subgroup): every
// joint report has the joint count of its specifications, a command with one
// joint out of range moves no joint, a non-controller's command moves
// nothing, and a stop holds the joints where they are and resumes nothing.
// A case that moves the arm moves one joint by a few hundredths of a radian
// and ends commanding every joint back where it found it, before releasing
// control (PositionsRestoredOnExit, then ControlHeld).
#include <cmath>
#include <cstdio>

#include "case_support.hpp"
#include "jaus/messages/manipulator_messages.hpp"
#include "state_support.hpp"
#include "stop_paths.hpp"

namespace jaus::conform {

namespace {

using namespace detail;

// How far a still joint may seem to move between two reports (rad or m):
// far above the wire's resolution, far below the motion the cases command.
constexpr double kStillTolerance = 0.005;
// The share of a joint's speed limit the cases move it at, for 0.2 s.
constexpr double kGentleShareOfMaxVelocity = 0.2;
constexpr auto kMoveTime = std::chrono::milliseconds(200);
constexpr auto kWatchTime = std::chrono::milliseconds(300);
// Set Joint Velocities' revolute range, Part 3 Code 0603h: +-10 pi rad/s.
constexpr double kWireMaxVelocity = 10 * 3.14159265358979;

std::string value_text(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4f", v);
  return text;
}

std::string unless_manipulator(const ComponentUnderTest& component) {
  if (auto why = unless_accepts(component, msg::QueryManipulatorSpecifications::code,
                                "Query Manipulator Specifications (0x2600)");
      !why.empty())
    return why;
  return unless_accepts(component, msg::QueryJointPositions::code, "Query Joint Positions (0x2602)");
}

std::string unless_moved_by_velocities(const ComponentUnderTest& component) {
  if (auto why = unless_manipulator(component); !why.empty()) return why;
  if (auto why = unless_accepts(component, msg::SetJointVelocities::code, "Set Joint Velocities (0x0603)");
      !why.empty())
    return why;
  return unless_accepts(component, msg::QueryJointVelocities::code, "Query Joint Velocities (0x2603)");
}

struct Specifications {
  std::size_t joints = 0;
  std::vector<double> max_velocity;  // per joint, rad/s or m/s
};

Expected<Specifications> specifications(CaseContext& c) {
  auto report = ask<msg::ReportManipulatorSpecifications>(c, msg::QueryManipulatorSpecifications{});
  if (!report) return unexpected(report.error());
  Specifications spec;
  spec.joints = report->joint_count;
  for (const auto& joint : report->joints) spec.max_velocity.push_back(joint.max_velocity_rps_or_mps);
  spec.max_velocity.push_back(report->last_joint_max_velocity_rps_or_mps);
  return spec;
}

Expected<std::vector<double>> positions(CaseContext& c) {
  auto report = ask<msg::ReportJointPositions>(c, msg::QueryJointPositions{});
  if (!report) return unexpected(report.error());
  return report->positions_rad;
}

Expected<std::vector<double>> velocities(CaseContext& c) {
  auto report = ask<msg::ReportJointVelocities>(c, msg::QueryJointVelocities{});
  if (!report) return unexpected(report.error());
  return report->velocities_rps;
}

// The first joint that differs by more than kStillTolerance ("" when none).
std::string moved(const std::vector<double>& before, const std::vector<double>& after) {
  if (before.size() != after.size())
    return std::to_string(before.size()) + " joints, then " + std::to_string(after.size());
  for (std::size_t j = 0; j < before.size(); ++j)
    if (std::fabs(after[j] - before[j]) > kStillTolerance)
      return "joint " + std::to_string(j + 1) + " moved from " + value_text(before[j]) + " to " + value_text(after[j]);
  return {};
}

// Joint 1 at a gentle share of its speed limit, toward zero (away from
// its limits, wherever they are), the others still.
msg::SetJointVelocities gentle_motion(const Specifications& spec, const std::vector<double>& at) {
  msg::SetJointVelocities m;
  m.velocities_rps.assign(spec.joints, 0.0);
  const double toward_zero = !at.empty() && at[0] > 0 ? -1 : 1;
  m.velocities_rps[0] = toward_zero * kGentleShareOfMaxVelocity * spec.max_velocity[0];
  return m;
}

// Every joint back where the case found it, and the time to get there.
void move_back(CaseContext& c, const std::vector<double>& found) {
  msg::SetJointPositions back;
  back.positions_rad = found;
  send(c, back);
  c.session.run_for(kMoveTime);
}

// Moves every joint back where the case found it when the case ends, however
// it ends. Declared after the ControlHeld, so it is sent while the runner
// still controls the arm.
class PositionsRestoredOnExit {
 public:
  PositionsRestoredOnExit(CaseContext& c, std::vector<double> found) : c_(c), found_(std::move(found)) {}
  ~PositionsRestoredOnExit() { move_back(c_, found_); }
  PositionsRestoredOnExit(const PositionsRestoredOnExit&) = delete;
  PositionsRestoredOnExit& operator=(const PositionsRestoredOnExit&) = delete;

 private:
  CaseContext& c_;
  std::vector<double> found_;
};

const std::vector<double>& joint_values(const msg::JointPositionsBody& b) { return b.positions_rad; }
const std::vector<double>& joint_values(const msg::JointVelocitiesBody& b) { return b.velocities_rps; }
const std::vector<double>& joint_values(const msg::JointEffortsBody& b) { return b.efforts_percent; }
const std::vector<double>& joint_values(const msg::JointForceTorquesBody& b) { return b.force_torques_nm; }

// How many joints a joint report lists.
template <class Report, class Query>
Expected<std::size_t> joints_in(CaseContext& c) {
  auto report = ask<Report>(c, Query{});
  if (!report) return unexpected(report.error());
  return joint_values(*report).size();
}

// Report Joint Positions, Velocities (and Efforts, Force/Torques when it
// takes their queries) list as many joints as its specifications.
CaseOutcome joint_count(CaseContext& c) {
  auto spec = specifications(c);
  if (!spec) return fail(spec.error().message());
  if (spec->joints == 0) return fail("Report Manipulator Specifications gives 0 joints (0 is reserved)");
  std::string checked;
  auto check = [&](std::string_view report, Expected<std::size_t> count) -> std::string {
    if (!count) return count.error().message();
    if (*count != spec->joints)
      return std::string(report) + " lists " + std::to_string(*count) + " joints, its specifications " +
             std::to_string(spec->joints);
    checked += (checked.empty() ? "" : ", ") + std::string(report);
    return {};
  };
  if (auto why = check("Report Joint Positions", joints_in<msg::ReportJointPositions, msg::QueryJointPositions>(c));
      !why.empty())
    return fail(why);
  if (c.component.accepts(msg::QueryJointVelocities::code))
    if (auto why =
            check("Report Joint Velocities", joints_in<msg::ReportJointVelocities, msg::QueryJointVelocities>(c));
        !why.empty())
      return fail(why);
  if (c.component.accepts(msg::QueryJointEfforts::code))
    if (auto why = check("Report Joint Efforts", joints_in<msg::ReportJointEfforts, msg::QueryJointEfforts>(c));
        !why.empty())
      return fail(why);
  if (c.component.accepts(msg::QueryJointForceTorques::code))
    if (auto why = check("Report Joint Force/Torques",
                         joints_in<msg::ReportJointForceTorques, msg::QueryJointForceTorques>(c));
        !why.empty())
      return fail(why);
  return pass(std::to_string(spec->joints) + " joints in its specifications and in " + checked);
}

// What a case that moves the arm needs first: Ready, its specifications,
// where its joints are, and that they are still.
struct ArmFound {
  Specifications spec;
  std::vector<double> at;
};

Expected<ArmFound> still_arm(CaseContext& c, std::string& skip_why) {
  auto state = primary_status(c);
  if (!state) return unexpected(state.error());
  if (*state != msg::PrimaryStatus::ready) {
    skip_why = "in " + state_text(*state) + ": joints are commanded in Ready";
    return ArmFound{};
  }
  auto spec = specifications(c);
  if (!spec) return unexpected(spec.error());
  if (spec->joints == 0 || spec->max_velocity.size() != spec->joints) {
    skip_why = "its specifications give no joint to move";
    return ArmFound{};
  }
  auto first = positions(c);
  if (!first) return unexpected(first.error());
  c.session.run_for(std::chrono::milliseconds(100));
  auto second = positions(c);
  if (!second) return unexpected(second.error());
  if (auto motion = moved(*first, *second); !motion.empty()) {
    skip_why = "the arm is moving (" + motion + ")";
    return ArmFound{};
  }
  return ArmFound{*spec, *second};
}

// A command with one joint over its speed limit is refused whole: the joints
// within their limits do not move either.
CaseOutcome out_of_range_refused_whole(CaseContext& c) {
  std::string skip_why;
  auto found = still_arm(c, skip_why);
  if (!found) return fail(found.error().message());
  if (!skip_why.empty()) return skip(skip_why);
  const std::size_t last = found->spec.joints - 1;
  const double over = std::min(found->spec.max_velocity[last] * 1.5 + 0.1, kWireMaxVelocity);
  if (over <= found->spec.max_velocity[last])
    return skip("joint " + std::to_string(last + 1) + "'s speed limit is the wire's: no velocity is out of its range");
  if (found->spec.joints < 2) return skip("one joint: no joint within its limits to watch");
  ControlHeld control(c);
  if (!control.granted()) return skip("control not granted (" + control.why() + ")");
  PositionsRestoredOnExit restore(c, found->at);
  msg::SetJointVelocities command = gentle_motion(found->spec, found->at);
  command.velocities_rps[last] = over;
  send(c, command);
  c.session.run_for(kWatchTime);
  auto after = positions(c);
  if (!after) return fail(after.error().message());
  if (auto motion = moved(found->at, *after); !motion.empty())
    return fail("Set Joint Velocities with joint " + std::to_string(last + 1) + " at " + value_text(over) + " (limit " +
                value_text(found->spec.max_velocity[last]) + ") was executed in part: " + motion);
  return pass("joint " + std::to_string(last + 1) + " at " + value_text(over) + " over its limit " +
              value_text(found->spec.max_velocity[last]) + ": no joint moved in 0.3 s");
}

// Set Joint Velocities from a non-controller moves nothing.
CaseOutcome arm_non_controller_ignored(CaseContext& c) {
  auto controller = current_controller(c);
  if (!controller) return fail(controller.error().message());
  if (*controller == c.session.self()) return skip("the runner controls it");
  std::string skip_why;
  auto found = still_arm(c, skip_why);
  if (!found) return fail(found.error().message());
  if (!skip_why.empty()) return skip(skip_why);
  send(c, gentle_motion(found->spec, found->at));
  c.session.run_for(kWatchTime);
  auto after = positions(c);
  if (!after) return fail(after.error().message());
  if (auto motion = moved(found->at, *after); !motion.empty()) {
    ControlHeld control(c);
    if (control.granted()) move_back(c, found->at);
    return fail("Set Joint Velocities from a non-controller (controller " + controller->to_string() + ") executed: " +
                motion + (control.granted() ? "; moved back" : "; control not granted to move it back"));
  }
  return pass("Set Joint Velocities from a non-controller: no joint moved in 0.3 s");
}

// A still arm for the next stop path: one the last path moved back may
// still be on its way.
Expected<ArmFound> settled_arm(CaseContext& c, std::string& skip_why) {
  constexpr int kTries = 5;
  for (int attempt = 1;; ++attempt) {
    skip_why.clear();
    auto found = still_arm(c, skip_why);
    if (!found || skip_why.empty() || attempt == kTries) return found;
    c.session.run_for(kWatchTime);
  }
}

// One stop path while joint 1 moves: every joint held where the stop found
// it, no joint speed reported, and the way back moving none. Returns what
// was wrong ("" when held); `not_judged` says why the path (or its way back)
// could not be judged.
std::string held_through(CaseContext& c, StopPath path, std::string& not_judged) {
  auto found = settled_arm(c, not_judged);
  if (!found) return found.error().message();
  if (!not_judged.empty()) return {};
  StopAlong along(c, path);
  if (!along.why_not().empty()) {
    not_judged = along.why_not();
    return {};
  }
  PositionsRestoredOnExit restore(c, found->at);  // sent while the runner controls it again
  send(c, gentle_motion(found->spec, found->at));
  c.session.run_for(kMoveTime);
  auto moving = positions(c);
  if (!moving) return moving.error().message();
  if (moved(found->at, *moving).empty()) {
    not_judged = "Set Joint Velocities did not move joint 1 in 0.2 s: nothing to stop";
    return {};
  }
  if (auto stopped = along.stop(); !stopped) {
    not_judged = stopped.error().message();
    return {};
  }
  const std::string stop = path_text(path);
  c.session.run_for(kMoveTime);  // a real arm brakes
  auto held = positions(c);
  c.session.run_for(kWatchTime);
  auto still_held = positions(c);
  auto speeds = velocities(c);
  const auto way_back = along.come_back();
  c.session.run_for(kWatchTime);
  auto resumed = positions(c);
  if (!held) return "after " + stop + ", " + held.error().message();
  if (!still_held) return "after " + stop + ", " + still_held.error().message();
  if (auto motion = moved(*held, *still_held); !motion.empty())
    return "after " + stop + ", " + motion + " in 0.3 s: not held";
  if (!speeds) return "after " + stop + ", " + speeds.error().message();
  for (std::size_t j = 0; j < speeds->size(); ++j)
    if (std::fabs((*speeds)[j]) > kStillTolerance)
      return "after " + stop + ", Report Joint Velocities gives joint " + std::to_string(j + 1) + " " +
             value_text((*speeds)[j]);
  if (!way_back) {
    not_judged = "held; the way back: " + way_back.error().message();
    return {};
  }
  if (!resumed) return "after " + way_back_text(path) + ", " + resumed.error().message();
  if (auto motion = moved(*still_held, *resumed); !motion.empty())
    return stop + ", then " + way_back_text(path) + " with no new command: " + motion + ", the stopped motion resumed";
  return {};
}

// Every stop while a joint moves (Standby, Set Emergency, Reset, the release
// of control, a takeover) holds every joint where it is (an arm must not
// fall: zero effort is no stop), and the way back starts nothing again.
CaseOutcome hold_on_stop(CaseContext& c) {
  std::string judged, not_judged;
  for (const StopPath path : kStopPaths) {
    std::string why_not;
    if (auto wrong = held_through(c, path, why_not); !wrong.empty()) return fail(wrong);
    if (!why_not.empty()) {
      not_judged += (not_judged.empty() ? "" : "; ") + path_text(path) + ": " + why_not;
      continue;
    }
    judged += (judged.empty() ? "" : ", ") + path_text(path);
  }
  if (judged.empty()) return skip(not_judged);
  return pass("joint 1 moving; " + judged + ": each held every joint, and the way back moved none" +
              (not_judged.empty() ? "" : " (not judged: " + not_judged + ")"));
}

}  // namespace

std::span<const ConformanceCase> manipulator_cases() {
  static const std::vector<ConformanceCase> list{
      {"manipulator.joint_count", "every joint report lists as many joints as its specifications",
       "Part 3, Code 4600h Report Manipulator Specifications, Code 4602h Report Joint Positions, Code 4603h Report "
       "Joint Velocities",
       unless_manipulator, joint_count},
      {"manipulator.out_of_range_refused_whole", "a command with one joint over its limit moves no joint",
       "Part 3, Code 0603h Set Joint Velocities, Code 4600h Report Manipulator Specifications (maximum velocity); "
       "docs/components.md Primitive Manipulator refusals",
       unless_moved_by_velocities, out_of_range_refused_whole},
      {"manipulator.non_controller_ignored", "Set Joint Velocities from a non-controller moves nothing",
       "Part 3, Code 000Dh Request Component Control (commands are the controller's), Code 4602h Report Joint "
       "Positions",
       unless_moved_by_velocities, arm_non_controller_ignored},
      {"manipulator.hold_on_stop",
       "Standby, Set Emergency, Reset, the release of control and a takeover each hold every joint; the way back "
       "moves none",
       "Part 3, Code 0003h Standby (cease internal functions), Code 0006h Set Emergency, Code 0005h Reset, Code "
       "000Eh Release Component Control, Code 000Dh Request Component Control, Code 0004h Resume, Code 0007h Clear "
       "Emergency; docs/components.md Primitive Manipulator safety",
       unless_moved_by_velocities, hold_on_stop},
  };
  return list;
}

}  // namespace jaus::conform
