// The component front (component.hpp): construction, the lifecycle it
// drives, failures, shutdown, what it offers (service entry) and its clock.
// The jobs it fronts have files of their own: dispatch and refusals
// (component_dispatch.cpp), the core messages (component_core_messages.cpp),
// emergency (component_emergency.cpp) and control (component_control.cpp).
#include "jaus/runtime/component.hpp"

#include <algorithm>
#include <chrono>

namespace jaus::rt {

Component::Component(ComponentConfig config, Environment env)
    : config_(std::move(config)),
      env_(std::move(env)),
      control_(config_.authority),
      services_(
          env_, config_.address, config_.service_connections,
          [this](Header h, std::span<const std::uint8_t> payload) { env_.outbox.send(h, payload); },
          [this](const Address& who, std::uint16_t) { return control_.is_controller(who); },
          [this](const Address& commander, std::uint16_t code) {
            enforce_stop("loss of command: service connection 0x" + wire::detail::hex_u32(code) + " from " +
                         commander.to_string() + " went silent");
          }),
      subscriptions_(
          env_, ServiceConnectionClient::Options{},
          [this](const Address& provider, const msg::CreateServiceConnection& m) { send(provider, m); },
          [this](const Address& provider, const msg::TerminateServiceConnection& m) { send(provider, m); }),
      repeated_lines_(env_.clock, env_.scheduler,
                      [this](LogLevel level, const std::string& text) { log(level, text); }) {
  register_core_handlers();
  emergency_membership_ = emergency_->join([this] { follow_emergency(); });
  // Safety (an operator above the ceiling always wins): a component made
  // with an authority above its own ceiling (the kinds refuse such a
  // configuration; this is for code that builds one directly) starts at the
  // ceiling, never above it.
  if (config_.max_authority && config_.authority > *config_.max_authority) {
    log(LogLevel::error, "authority " + std::to_string(config_.authority) + " above max_authority " +
                             std::to_string(*config_.max_authority) + ": " +
                             std::to_string(*config_.max_authority) + " used");
    config_.authority = *config_.max_authority;
    control_.set_own_authority(config_.authority);
  }
}

Component::~Component() {
  // Lifetimes: a shared latch outlives its members; nothing keeps a pointer here after this.
  emergency_->leave(emergency_membership_);
  if (controller_timer_ != kNoTimer) env_.scheduler.cancel(controller_timer_);
}

void Component::share_emergency(EmergencyLatch& latch) {
  emergency_->leave(emergency_membership_);
  emergency_ = &latch;
  emergency_membership_ = emergency_->join([this] { follow_emergency(); });
}

void Component::log(LogLevel level, const std::string& text) const {
  env_.log(level, config_.name + " " + config_.address.to_string() + ": " + text);
}

void Component::start() { run_initialisation(); }

void Component::run_initialisation() {
  waiting_for_hardware_ = false;
  const bool ok = initialize();
  if (!ok) transition(LifecycleEvent::init_failed, config_.address);
  // A controller's Reset runs this again: a Reset loop is one line per window, then a count.
  else if (waiting_for_hardware_)
    log_repeated({"initialisations waiting for the hardware", kNoteworthyBurst}, LogLevel::info,
                 [&] { return "initialising: waiting for " + waiting_for_; });
  else transition(LifecycleEvent::init_succeeded, config_.address);
  // An emergency latched before a reset (or restored at start) still holds after it.
  follow_emergency();
}

void Component::wait_for_hardware(std::string why) {
  waiting_for_hardware_ = true;
  waiting_for_ = std::move(why);
}

void Component::hardware_ready() {
  if (!waiting_for_hardware_) return;
  waiting_for_hardware_ = false;
  log_repeated({"hardware ready", kNoteworthyBurst}, LogLevel::info, [] { return std::string("hardware ready: initialised"); });
  // In Emergency the wait ends when the emergency returns to Initialize (follow_emergency).
  if (lifecycle_.state() == PrimaryStatus::initialize) transition(LifecycleEvent::init_succeeded, config_.address);
}

void Component::transition(LifecycleEvent event, const Address& by, std::string_view cause) {
  const PrimaryStatus before = lifecycle_.state();
  if (!lifecycle_.process(event)) {
    ++counters_.refused_transitions;
    log_repeated({"refused state changes", kNoteworthyBurst}, LogLevel::warn, [&] {
      return std::string(to_string(event)) + " from " + by.to_string() + " refused in " +
             std::string(to_string(before));
    });
    return;
  }
  const PrimaryStatus after = lifecycle_.state();
  log_repeated({"state changes", kNoteworthyBurst}, LogLevel::info, [&] {
    return std::string(to_string(before)) + " -> " + std::string(to_string(after)) + " (" +
           std::string(to_string(event)) + (cause.empty() ? " from " + by.to_string() : ": " + std::string(cause)) +
           ")";
  });
  // Safety: leaving Ready, or re-entering a non-Ready state, always stops the
  // platform, and counts: the stop counter every Report Component Status
  // carries (stop_counter.hpp) shows a stop to a controller that sampled
  // neither side of it.
  if (after != PrimaryStatus::ready) {
    ++counters_.stops_entered;
    enforce_stop(std::string("entered ") + std::string(to_string(after)));
  }
  if (after == PrimaryStatus::initialize || after == PrimaryStatus::shutdown) failure_declared_ = false;
  if (after == PrimaryStatus::shutdown) {
    take_control_away("component shut down");
    services_.end_all("component shut down");
    subscriptions_.unsubscribe_all();
  }
  state_changed(before, after);
  if (state_listener_) state_listener_(before, after);
  // No unsolicited Report Component Status goes to the controller: the RA
  // sends it only as an answer or on a service connection, and a peer that
  // pairs answers with its queries (jaus-conform did) reads it as the answer
  // to its next query. The stop counter shows the stop at the next sample.
}

void Component::shutdown(std::string_view why) {
  log(LogLevel::info, "shutting down: " + std::string(why));
  transition(LifecycleEvent::shutdown, config_.address);
}

std::vector<std::uint16_t> Component::input_codes() const {
  std::vector<std::uint16_t> codes;
  for (const auto& [code, handler] : handlers_) codes.push_back(code);
  std::sort(codes.begin(), codes.end());
  return codes;
}

msg::ServiceEntry Component::service_entry() const {
  msg::ServiceEntry service;
  service.type = config_.address.component;
  for (auto code : input_codes()) {
    const auto declared = input_presence_.find(code);
    service.inputs.push_back({code, declared != input_presence_.end() ? declared->second : 0});
  }
  for (const auto& [code, presence] : output_codes()) service.outputs.push_back({code, presence});
  return service;
}

void Component::peer_lost(const Address& peer) {
  services_.end_all_from(peer, "requester gone");
  if (const auto& controller = control_.controller(); controller && peer.covers(controller->address))
    take_control_away("controller " + controller->address.to_string() + " gone");
  requester_lost(peer);
}

void Component::declare_failure(std::string_view why) {
  const PrimaryStatus state = lifecycle_.state();
  if (state != PrimaryStatus::ready && state != PrimaryStatus::standby) return;
  // A controller's Reset or Resume on faulted hardware declares it again: limited.
  log_repeated({"failures", kNoteworthyBurst}, LogLevel::warn, [&] { return "failure: " + std::string(why); });
  transition(LifecycleEvent::failure_detected, config_.address);
  failure_declared_ = lifecycle_.state() == PrimaryStatus::failure;
}

void Component::clear_failure(std::string_view why) {
  if (!failure_declared_) return;
  // In Emergency the failure is what the emergency interrupted: it stays
  // declared, and clears once the emergency has returned to Failure.
  if (lifecycle_.state() != PrimaryStatus::failure) return;
  log_repeated({"failures cleared", kNoteworthyBurst}, LogLevel::info,
               [&] { return "failure cleared: " + std::string(why); });
  failure_declared_ = false;
  transition(LifecycleEvent::failure_cleared, config_.address);
}

void Component::enforce_stop(std::string_view why) {
  ++counters_.stops_commanded;
  command_stop(why);
}

bool Component::keeps_state_for(const Address& node) const {
  if (const auto& c = control_.controller(); c && node.covers(c->address)) return true;
  return emergency_->held_by_any_under(node) || services_.has_requester_under(node);
}

// ---- time ----------------------------------------------------------------------

UtcTime Component::component_time() const { return env_.clock.utc_now() + time_offset_; }

void Component::on_set_time(const msg::SetTime& m) {
  using namespace std::chrono;
  const auto now = component_time();
  const auto today = floor<days>(now);
  year_month_day date{sys_days{today}};
  if (m.date) date = year_month_day{year{m.date->year}, month{m.date->month}, day{m.date->day}};
  Duration time_of_day = now - today;
  if (m.time) {
    // The time stamp carries its own day of month.
    date = year_month_day{date.year(), date.month(), day{m.time->day}};
    time_of_day = hours{m.time->hour} + minutes{m.time->minute} + seconds{m.time->second} +
                  milliseconds{m.time->millisecond};
  }
  if (!date.ok()) {
    log_repeated("Set Time with an invalid date ignored", LogLevel::warn,
                 [&] { return "Set Time with an invalid date ignored"; });
    return;
  }
  const UtcTime target = sys_days{date} + time_of_day;
  time_offset_ += target - now;
  log_repeated("time set", LogLevel::info, [&] {
    return "time set (offset " + std::to_string(duration_cast<milliseconds>(time_offset_).count()) + " ms)";
  });
}

}  // namespace jaus::rt
