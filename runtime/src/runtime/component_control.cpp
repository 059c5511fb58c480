// Control: Request and Release Component Control decided by the arbiter
// (control_arbiter.hpp), the controller's liveness watch, and the stop
// every change of hands makes.
#include <algorithm>
#include <chrono>

#include "jaus/runtime/component.hpp"

namespace jaus::rt {

namespace {
// How often a controlled component asks its controller for its status: the
// reply (or any other traffic) proves the controller is alive.
constexpr int kControllerQueriesPerTimeout = 3;
}  // namespace

void Component::answer_refused_control(const Address& to) {
  if (config_.reject_refused_requests)
    send(to, msg::RejectComponentControl{});
  else
    send(to, msg::ConfirmComponentControl{{msg::control_response::kNotAccepted}});
}

void Component::on_request_control(const Header& h, const msg::RequestComponentControl& m) {
  // Control is state the node must end when the controller goes (and only
  // hosts allowed to command may hold it): answered as any refused request.
  if (standing_ != SenderStanding::trusted) {
    refuse_for_standing(h, "Request Component Control");
    return answer_refused_control(h.source);
  }
  const auto previous = control_.controller();
  const auto outcome = control_.request(h.source, m.authority);
  if (!outcome.accepted) {
    log_repeated("control requests refused", LogLevel::info, [&] {
      return "control request from " + h.source.to_string() + " (authority " + std::to_string(m.authority) +
             ") refused: " + std::string(outcome.why);
    });
    return answer_refused_control(h.source);
  }
  send(h.source, msg::ConfirmComponentControl{{msg::control_response::kAccepted}});
  controller_last_heard_ = env_.clock.now();
  if (!previous || previous->address != h.source) {
    ++counters_.control_changes;
    log_repeated({"control granted", kNoteworthyBurst}, LogLevel::info,
                 [&] { return "controlled by " + to_string(*control_.controller()) + ": " + std::string(outcome.why); });
    arm_controller_watch();
    end_stale_command_connections("control changed hands");
  }
  if (outcome.displaced) {
    send(outcome.displaced->address, msg::RejectComponentControl{});
    log_repeated({"control taken over", kNoteworthyBurst}, LogLevel::info,
                 [&] { return "control taken from " + to_string(*outcome.displaced); });
    // The new controller has not commanded anything yet: stop what the old one commanded.
    enforce_stop("control changed hands");
  }
}

void Component::on_release_control(const Header& h) {
  if (!control_.release(h.source)) {
    log_repeated("Release Component Control from a non-controller ignored", LogLevel::info, [&] {
      return "Release Component Control from " + h.source.to_string() + " ignored: not the controller";
    });
    return;
  }
  ++counters_.control_changes;
  log_repeated({"control released", kNoteworthyBurst}, LogLevel::info,
               [&] { return "released by " + h.source.to_string(); });
  if (controller_timer_ != kNoTimer) env_.scheduler.cancel(controller_timer_);
  controller_timer_ = kNoTimer;
  end_stale_command_connections("control released");
  enforce_stop("control released");
}

void Component::take_control_away(std::string_view why) {
  if (controller_timer_ != kNoTimer) env_.scheduler.cancel(controller_timer_);
  controller_timer_ = kNoTimer;
  if (const auto previous = control_.drop()) {
    ++counters_.control_changes;
    // A controller that takes control and goes silent (or away) in a loop repeats this: limited.
    log_repeated({"control dropped", kNoteworthyBurst}, LogLevel::warn,
                 [&] { return "control of " + to_string(*previous) + " dropped: " + std::string(why); });
    send(previous->address, msg::RejectComponentControl{});
    end_stale_command_connections(why);
    enforce_stop(why);
  }
}

void Component::end_stale_command_connections(std::string_view why) {
  const auto& controller = control_.controller();
  services_.end_commands_not_from(controller ? std::optional<Address>(controller->address) : std::nullopt, why);
}

void Component::arm_controller_watch() {
  if (controller_timer_ != kNoTimer) env_.scheduler.cancel(controller_timer_);
  controller_timer_ = kNoTimer;
  if (config_.controller_timeout <= Duration::zero()) return;
  schedule_controller_check();
}

// The next look at the controller: a query period from now, or the moment
// its silence outlasts the timeout if that comes first. So control goes 1 ms
// after controller_timeout of silence, not up to a query period later (the
// checks alone could leave a silent controller in control for 4/3 of it).
void Component::schedule_controller_check() {
  const TimePoint now = env_.clock.now();
  const TimePoint next_query = now + config_.controller_timeout / kControllerQueriesPerTimeout;
  const TimePoint silent_enough = controller_last_heard_ + config_.controller_timeout + std::chrono::milliseconds(1);
  controller_timer_ =
      env_.scheduler.call_at(std::max(now, std::min(next_query, silent_enough)), [this] { check_controller(); });
}

void Component::check_controller() {
  controller_timer_ = kNoTimer;
  const auto& controller = control_.controller();
  if (!controller) return;
  const Duration silence = env_.clock.now() - controller_last_heard_;
  if (silence > config_.controller_timeout) {  // "longer than": ComponentConfig::controller_timeout
    take_control_away("controller silent for " +
                      std::to_string(std::chrono::duration_cast<std::chrono::milliseconds>(silence).count()) + " ms");
    return;
  }
  // Ask for a sign of life; the reply (or any other message) refreshes liveness.
  send(controller->address, msg::QueryComponentStatus{});
  schedule_controller_check();
}

}  // namespace jaus::rt
