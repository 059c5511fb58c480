// The primitive driver cases (Part 3, Set and Report Wrench Effort): the
// effort its controller sets is the effort it reports, a non-controller's is
// never executed, every stop zeroes it and nothing resumes it afterwards.
// Safety first: a case commands at most 5 % of propulsive linear X, and a
// case that commands effort ends commanding zero effort and releasing
// control, however it ends (ZeroEffortOnExit, then ControlHeld).
#include <cmath>
#include <cstdio>
#include <optional>

#include "case_support.hpp"
#include "jaus/messages/platform_messages.hpp"
#include "state_support.hpp"
#include "stop_paths.hpp"

namespace jaus::conform {

namespace {

using namespace detail;

constexpr double kSmallEffortPercent = 5;
// The wire resolves 0.003 %; a drive may round the effort to its own steps.
constexpr double kEffortTolerancePercent = 0.5;
constexpr std::uint16_t kPropulsiveLinearX = 1u << 0;  // Set/Report Wrench Effort presence bit

std::string percent_text(double percent) {
  char text[32];
  std::snprintf(text, sizeof text, "%.2f %%", percent);
  return text;
}

bool near(double a, double b) { return std::fabs(a - b) <= kEffortTolerancePercent; }

std::string unless_driver(const ComponentUnderTest& component) {
  if (auto why = unless_accepts(component, msg::SetWrenchEffort::code, "Set Wrench Effort (0x0405)"); !why.empty())
    return why;
  if (auto why = unless_accepts(component, msg::QueryWrenchEffort::code, "Query Wrench Effort (0x2405)"); !why.empty())
    return why;
  // A driver that says which fields it reports must act on throttle.
  if (component.provides(msg::ReportWrenchEffort::code) &&
      (component.outputs.at(msg::ReportWrenchEffort::code) & kPropulsiveLinearX) == 0)
    return "it reports no propulsive linear X effort";
  return {};
}

msg::SetWrenchEffort effort_forward(double percent) {
  msg::SetWrenchEffort m;
  m.propulsive_linear_effort_x_percent = percent;
  return m;
}

// Every propulsive field at zero: whatever else moved it stops too.
msg::SetWrenchEffort zero_effort() {
  msg::SetWrenchEffort m = effort_forward(0);
  m.propulsive_linear_effort_y_percent = m.propulsive_linear_effort_z_percent = 0;
  m.propulsive_rotational_effort_x_percent = m.propulsive_rotational_effort_y_percent = 0;
  m.propulsive_rotational_effort_z_percent = 0;
  return m;
}

// Sends zero effort when the case ends, however it ends. Declared after the
// ControlHeld, so it is sent while the runner still controls the driver.
class ZeroEffortOnExit {
 public:
  explicit ZeroEffortOnExit(CaseContext& c) : c_(c) {}
  ~ZeroEffortOnExit() { send(c_, zero_effort()); }
  ZeroEffortOnExit(const ZeroEffortOnExit&) = delete;
  ZeroEffortOnExit& operator=(const ZeroEffortOnExit&) = delete;

 private:
  CaseContext& c_;
};

// The propulsive linear X effort it reports (Query Wrench Effort, every field
// asked for); an error when it does not answer or leaves that field out.
Expected<double> reported_forward_effort(CaseContext& c) {
  auto report = ask<msg::ReportWrenchEffort>(c, msg::QueryWrenchEffort{{0x0FFF}});
  if (!report) return unexpected(report.error());
  if (!report->propulsive_linear_effort_x_percent)
    return unexpected(make_error(ErrorCode::malformed, "Report Wrench Effort leaves propulsive linear X out"));
  return *report->propulsive_linear_effort_x_percent;
}

// A driver that executed what it should not have: stopped again by its
// controller's zero effort or, when control is not granted, by Standby.
std::string stop_it(CaseContext& c) {
  ControlHeld control(c);
  if (!control.granted()) {
    send(c, msg::Standby{});
    return "control not granted (" + control.why() + "): sent Standby to stop it";
  }
  ZeroEffortOnExit zero(c);
  return "stopped again with zero effort";
}

// The verdict when the driver is not Ready (effort is set in Ready only).
std::optional<CaseOutcome> unless_ready(CaseContext& c) {
  auto state = primary_status(c);
  if (!state) return fail(state.error().message());
  if (*state != msg::PrimaryStatus::ready) return skip("in " + state_text(*state) + ": effort is set in Ready");
  return std::nullopt;
}

// Its controller's effort is applied and reported; zero effort is reported as zero.
CaseOutcome effort_reported(CaseContext& c) {
  if (auto not_ready = unless_ready(c)) return *not_ready;
  ControlHeld control(c);
  if (!control.granted()) return skip("control not granted (" + control.why() + ")");
  ZeroEffortOnExit zero(c);
  send(c, effort_forward(kSmallEffortPercent));
  auto driving = reported_forward_effort(c);
  send(c, zero_effort());
  auto stopped = reported_forward_effort(c);
  if (!driving)
    return fail("after Set Wrench Effort " + percent_text(kSmallEffortPercent) + ", " + driving.error().message());
  if (!near(*driving, kSmallEffortPercent))
    return fail("Set Wrench Effort " + percent_text(kSmallEffortPercent) + " from its controller, reported as " +
                percent_text(*driving));
  if (!stopped) return fail("after zero effort, " + stopped.error().message());
  if (!near(*stopped, 0)) return fail("zero effort from its controller, reported as " + percent_text(*stopped));
  return pass("propulsive linear X " + percent_text(kSmallEffortPercent) + " set and reported as " +
              percent_text(*driving) + ", then zero");
}

// A Set Wrench Effort from a non-controller is not executed: its own report
// of the effort does not change.
CaseOutcome non_controller_ignored(CaseContext& c) {
  auto state = primary_status(c);
  if (!state) return fail(state.error().message());
  if (*state != msg::PrimaryStatus::ready)
    return skip("in " + state_text(*state) + ": outside Ready no effort is executed, whoever sends it");
  auto controller = current_controller(c);
  if (!controller) return fail(controller.error().message());
  if (*controller == c.session.self()) return skip("the runner controls it");
  auto before = reported_forward_effort(c);
  if (!before) return fail(before.error().message());
  if (!near(*before, 0))
    return skip("it is driving (" + percent_text(*before) + "): a change could be its controller's");
  send(c, effort_forward(kSmallEffortPercent));
  auto after = reported_forward_effort(c);
  if (!after) return fail("after Set Wrench Effort from a non-controller, " + after.error().message());
  if (!near(*after, *before)) {
    const std::string stopped = stop_it(c);
    return fail("Set Wrench Effort " + percent_text(kSmallEffortPercent) + " from a non-controller (controller " +
                controller->to_string() + ") executed: reported " + percent_text(*after) + "; " + stopped);
  }
  return pass("Set Wrench Effort from a non-controller: still " + percent_text(*after));
}

// What the driver reported along one stop path: driving at 5 %, stopped,
// and back (Resume, Clear Emergency, re-initialised, control granted again)
// with no new effort.
struct StopObserved {
  std::string skip;   // the path could not be judged: why
  std::string error;  // it stopped answering: what was seen
  double driving = 0;
  double stopped = 0;
  double back = 0;
};

StopObserved through(CaseContext& c, StopPath path) {
  StopObserved seen;
  StopAlong along(c, path);
  if (!along.why_not().empty()) {
    seen.skip = along.why_not();
    return seen;
  }
  ZeroEffortOnExit zero(c);  // sent while the runner still controls it, if the way back gave control again
  send(c, effort_forward(kSmallEffortPercent));
  auto driving = reported_forward_effort(c);
  if (!driving || !near(*driving, kSmallEffortPercent)) {
    seen.skip = "Set Wrench Effort " + percent_text(kSmallEffortPercent) + " is not reported as set (" +
                (driving ? percent_text(*driving) : driving.error().message()) + ")";
    return seen;
  }
  seen.driving = *driving;
  if (auto stopped_along = along.stop(); !stopped_along) {
    seen.skip = stopped_along.error().message();
    return seen;
  }
  auto stopped = reported_forward_effort(c);
  if (!stopped) {
    seen.error = "after " + path_text(path) + ", " + stopped.error().message();
    return seen;
  }
  seen.stopped = *stopped;
  if (auto came_back = along.come_back(); !came_back) {
    seen.skip = came_back.error().message();
    return seen;
  }
  auto back = reported_forward_effort(c);
  if (!back) {
    seen.error = "after " + way_back_text(path) + ", " + back.error().message();
    return seen;
  }
  seen.back = *back;
  return seen;
}

// Runs every stop path and judges each with `judge` (empty: as it should
// be; else what was wrong). A path that cannot be judged is named in the
// verdict; the case is skipped only when no path could be judged.
template <class Judge>
CaseOutcome along_every_stop_path(CaseContext& c, Judge judge, const std::string& passed) {
  if (auto not_ready = unless_ready(c)) return *not_ready;
  std::string judged, not_judged;
  for (const StopPath path : kStopPaths) {
    const StopObserved observed = through(c, path);
    if (!observed.error.empty()) return fail(observed.error);
    if (!observed.skip.empty()) {
      not_judged += (not_judged.empty() ? "" : "; ") + path_text(path) + ": " + observed.skip;
      continue;
    }
    if (auto wrong = judge(path, observed); !wrong.empty()) return fail(wrong);
    judged += (judged.empty() ? "" : ", ") + path_text(path);
  }
  if (judged.empty()) return skip(not_judged);
  return pass(judged + ": " + passed + (not_judged.empty() ? "" : " (not judged: " + not_judged + ")"));
}

// Every stop path zeroes the effort at once: Standby, Set Emergency, Reset,
// the release of control, a takeover.
CaseOutcome stop_zeroes_effort(CaseContext& c) {
  return along_every_stop_path(
      c,
      [](StopPath path, const StopObserved& observed) -> std::string {
        if (near(observed.stopped, 0)) return {};
        return path_text(path) + " while driving at " + percent_text(observed.driving) +
               " left propulsive linear X at " + percent_text(observed.stopped);
      },
      "each zeroed " + percent_text(kSmallEffortPercent));
}

// After a stop, the way back (Resume, Clear Emergency, the end of
// re-initialisation, control granted again) resumes nothing: the effort stays
// zero until a new Set Wrench Effort.
CaseOutcome no_resume_after_stop(CaseContext& c) {
  return along_every_stop_path(
      c,
      [](StopPath path, const StopObserved& observed) -> std::string {
        if (near(observed.back, 0)) return {};
        return path_text(path) + " then " + way_back_text(path) +
               " resumed the latched effort: " + percent_text(observed.back);
      },
      "still zero after the way back");
}

}  // namespace

std::span<const ConformanceCase> primitive_driver_cases() {
  static const std::vector<ConformanceCase> list{
      {"driver.effort_reported", "its controller's Set Wrench Effort is reported by Report Wrench Effort",
       "Part 3, Code 0405h Set Wrench Effort, Code 4405h Report Wrench Effort (the current commanded effort)",
       unless_driver, effort_reported},
      {"driver.non_controller_ignored", "Set Wrench Effort from a non-controller is never executed",
       "Part 3, Code 000Dh Request Component Control (commands are the controller's), Code 4405h Report Wrench "
       "Effort",
       unless_driver, non_controller_ignored},
      {"driver.stop_zeroes_effort",
       "Standby, Set Emergency, Reset, the release of control and a takeover each zero the effort",
       "Part 3, Code 0003h Standby (cease internal functions), Code 0006h Set Emergency (the Stop condition), Code "
       "0005h Reset, Code 000Eh Release Component Control, Code 000Dh Request Component Control (a higher "
       "authority takes over); docs/components.md Primitive Driver safety rules",
       unless_driver, stop_zeroes_effort},
      {"driver.no_resume_after_stop",
       "Resume, Clear Emergency, the end of a Reset or a new grant of control resume no latched effort",
       "Part 3, Code 0004h Resume, Code 0007h Clear Emergency, Code 0005h Reset; docs/components.md Primitive Driver "
       "safety rules",
       unless_driver, no_resume_after_stop},
  };
  return list;
}

}  // namespace jaus::conform
