#include "jaus/runtime/component.hpp"

#include <algorithm>
#include <chrono>

#include "jaus/messages/communications_messages.hpp"
#include "jaus/messages/discovery_messages.hpp"
#include "jaus/runtime/stop_counter.hpp"

namespace jaus::rt {

namespace {
// How often a controlled component asks its controller for its status: the
// reply (or any other traffic) proves the controller is alive.
constexpr int kControllerQueriesPerTimeout = 3;

std::string describe(const Controller& c) {
  return c.address.to_string() + " (authority " + std::to_string(c.authority) + ")";
}
}  // namespace

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

// Safety: the one place a component enters or leaves Emergency, following its
// latch. Idempotent: a shared latch calls every member on every change.
void Component::follow_emergency() {
  const PrimaryStatus state = lifecycle_.state();
  if (state == PrimaryStatus::shutdown) return;
  // A Set or Clear Emergency names its sender; anything else (a local hold,
  // a restored or shared latch) says who holds it.
  const Address& sender = emergency_->last_changed_by();
  const Address by = sender.is_valid() ? sender : config_.address;
  const std::string cause = sender.is_valid() ? std::string()
                            : emergency_->active() ? "held by " + emergency_->describe_holders()
                                                   : std::string("no longer held");
  if (emergency_->active() && state != PrimaryStatus::emergency) {
    transition(LifecycleEvent::emergency_set, by, cause);
  } else if (!emergency_->active() && state == PrimaryStatus::emergency) {
    transition(LifecycleEvent::emergency_cleared, by, cause);
    // The hardware spoke while the emergency interrupted the wait for it.
    if (lifecycle_.state() == PrimaryStatus::initialize && !waiting_for_hardware_)
      transition(LifecycleEvent::init_succeeded, config_.address);
  }
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

void Component::hold_hardware_emergency(std::string_view cause) {
  // A hardware stop can flap (or be toggled through a platform a peer reaches): limited like remote input.
  if (emergency_->hold_local(cause))
    log_repeated({"emergency Stops from the hardware", kNoteworthyBurst}, LogLevel::warn,
                 [&] { return "emergency Stop from the hardware: " + std::string(cause); });
}

void Component::release_hardware_emergency(std::string_view cause) {
  switch (emergency_->release_local(cause)) {
    case EmergencyLatch::ClearResult::not_a_holder:
    case EmergencyLatch::ClearResult::refused:  // (only JAUS clears are refused)
      return;
    case EmergencyLatch::ClearResult::still_held:
      log_repeated({"hardware emergencies cleared", kNoteworthyBurst}, LogLevel::info, [&] {
        return "hardware emergency cleared (" + std::string(cause) + "); still held by " +
               emergency_->describe_holders();
      });
      return;
    case EmergencyLatch::ClearResult::released_last:
      log_repeated({"hardware emergencies cleared", kNoteworthyBurst}, LogLevel::info,
                   [&] { return "hardware emergency cleared: " + std::string(cause); });
      return;
  }
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

// ---- dispatch --------------------------------------------------------------

void Component::receive(const Header& header, std::span<const std::uint8_t> payload, wire::Dialect dialect,
                        SenderStanding standing) {
  // Handlers read it through sender_standing(); kept for this message only
  // (a message sent meanwhile is queued by the node, never handled inside this call).
  const SenderStanding outer = standing_;
  standing_ = standing;
  dispatch(header, payload, dialect);
  standing_ = outer;
}

void Component::dispatch(const Header& header, std::span<const std::uint8_t> payload, wire::Dialect dialect) {
  ++counters_.received;
  if (lifecycle_.state() == PrimaryStatus::shutdown) return;  // a shut-down component answers nothing

  // Any traffic from the controller proves it is alive.
  if (control_.is_controller(header.source)) controller_last_heard_ = env_.clock.now();

  // Reports on our own service connections go to their subscribers.
  if (subscriptions_.on_report(header, payload)) return;

  const auto it = handlers_.find(header.command_code);
  if (it == handlers_.end()) {
    if (unhandled(header, payload)) return;
    ++counters_.unsupported;
    // A broadcast reaches every component, most of which have no use for it
    // (the node manager's own heartbeat, each second): counted, not a line.
    if (header.destination.is_broadcast()) return;
    log_repeated("unsupported messages ignored", LogLevel::debug, [&] {
      return "ignored unsupported message 0x" + wire::detail::hex_u32(header.command_code) + " from " +
             header.source.to_string();
    });
    return;
  }
  const Handler& handler = it->second;
  if (handler.access == Access::controller && !control_.is_controller(header.source)) {
    refuse_not_controller(header, handler.name);
    return;
  }
  // A controller that is no longer trusted (moved outside control_from, or
  // its route lost to a full table) commands nothing.
  if (handler.access == Access::controller && standing_ != SenderStanding::trusted) {
    refuse_for_standing(header, handler.name);
    return;
  }
  if (handler.ready_only && lifecycle_.state() != PrimaryStatus::ready) {
    ++counters_.refused_wrong_state;
    log_repeated("commands not executed outside Ready", LogLevel::warn, [&] {
      return std::string(handler.name) + " from " + header.source.to_string() + " not executed in " +
             std::string(to_string(lifecycle_.state()));
    });
    return;
  }
  if (auto handled = handler.invoke(header, payload, dialect); !handled) {
    ++counters_.decode_errors;
    log_repeated("malformed messages ignored", LogLevel::warn, [&] {
      return "malformed " + std::string(handler.name) + " from " + header.source.to_string() + ": " +
             handled.error().message();
    });
    return;
  }
  // Only a command that decoded (and, checked above, came from the
  // controller) feeds the deadman of its service connection.
  if (handler.access == Access::controller && handler.ready_only) services_.on_command(header);
}

void Component::refuse_not_controller(const Header& header, std::string_view what) {
  ++counters_.refused_not_controller;
  log_repeated("commands from a non-controller not executed", LogLevel::warn, [&] {
    const auto& controller = control_.controller();
    return std::string(what) + " from " + header.source.to_string() +
           " not executed: " + (controller ? "controlled by " + describe(*controller) : "not controlled");
  });
}

void Component::refuse_for_standing(const Header& header, std::string_view what) {
  const bool unrecorded = standing_ == SenderStanding::unrecorded;
  ++(unrecorded ? counters_.refused_unrecorded : counters_.refused_observer);
  const auto line = [&] {
    return std::string(what) + " from " + header.source.to_string() + " refused: sender " +
           std::string(to_string(standing_));
  };
  // Per standing, not per sender: a flood of forged sources is one line and a count.
  if (unrecorded)
    log_repeated("requests from unrecorded senders refused", LogLevel::warn, line);
  else
    log_repeated("requests from observers refused", LogLevel::info, line);
}

bool Component::keeps_state_for(const Address& node) const {
  if (const auto& c = control_.controller(); c && node.covers(c->address)) return true;
  return emergency_->held_by_any_under(node) || services_.has_requester_under(node);
}

// ---- core messages -----------------------------------------------------------

msg::ReportComponentStatus Component::status_report() const {
  msg::ReportComponentStatus report;
  report.primary_status = static_cast<std::uint8_t>(lifecycle_.state());
  // Bit 0 of the emergency secondary status: the Stop condition is set;
  // bits 16-19 the component's own; 20-31 the stop counter.
  report.secondary_status = (emergency_->active() ? 1u : 0u) |
                            (component_status_bits() & stop_counter::kComponentBits) |
                            stop_counter::bits(counters_.stops_entered);
  return report;
}

void Component::register_core_handlers() {
  using namespace msg;
  handle<QueryComponentAuthority>(Access::anyone, false, [this](const Header& h, const QueryComponentAuthority&) {
    send(h.source, ReportComponentAuthority{{control_.own_authority()}});
  });
  // OCUs ask every component who it is (Query Identification, type 4); the
  // node manager also answers for its subsystem and node.
  handle<QueryIdentification>(Access::anyone, false, [this](const Header& h, const QueryIdentification& m) {
    if (m.query_type != identification::kComponent) {
      log_repeated("Query Identification of another type not answered", LogLevel::debug, [&] {
        return "Query Identification type " + std::to_string(m.query_type) + " from " + h.source.to_string() +
               " not answered: only node managers speak for a node";
      });
      return;
    }
    send(h.source, ReportIdentification{{identification::kComponent, control_.own_authority(), 0, name()}});
  });
  // ...and what it does (Query Services); the node manager answers for every
  // component of its node instead.
  handle<QueryServices>(Access::anyone, false, [this](const Header& h, const QueryServices&) {
    send(h.source, ReportServices{{{service_entry()}}});
  });
  handle<QueryComponentStatus>(Access::anyone, false,
                                [this](const Header& h, const QueryComponentStatus&) { send(h.source, status_report()); });
  // Controlling OCUs watch a component through a service connection to its
  // status (about 5 Hz) and treat silence as loss (docs/wire-format.md, "Service connections").
  provide<ReportComponentStatus>(0, [this] { return status_report(); });
  handle<QueryComponentControl>(Access::anyone, false, [this](const Header& h, const QueryComponentControl&) {
    ReportComponentControl report;
    if (const auto& c = control_.controller()) {
      report.controller = c->address;
      report.authority = c->authority;
    }
    send(h.source, report);
  });
  handle<QueryTime>(Access::anyone, false, [this](const Header& h, const QueryTime& query) {
    const auto now = component_time();
    const auto day = std::chrono::floor<std::chrono::days>(now);
    const std::chrono::year_month_day date{std::chrono::sys_days{day}};
    const std::chrono::hh_mm_ss time{std::chrono::floor<std::chrono::milliseconds>(now - day)};
    ReportTime report;
    if (query.presence_vector & 0x1)
      report.time = TimeStamp{static_cast<std::uint16_t>(time.subseconds().count()),
                              static_cast<std::uint8_t>(time.seconds().count()),
                              static_cast<std::uint8_t>(time.minutes().count()),
                              static_cast<std::uint8_t>(time.hours().count()),
                              static_cast<std::uint8_t>(static_cast<unsigned>(date.day()))};
    // The date stamp holds 2000-2127 only; outside that the date is left out.
    const int year = static_cast<int>(date.year());
    if ((query.presence_vector & 0x2) && year >= 2000 && year <= 2127)
      report.date = DateStamp{static_cast<std::uint8_t>(static_cast<unsigned>(date.day())),
                              static_cast<std::uint8_t>(static_cast<unsigned>(date.month())),
                              static_cast<std::uint16_t>(year)};
    send(h.source, report);
  });
  handle<QueryHeartbeatPulse>(Access::anyone, false, [this](const Header& h, const QueryHeartbeatPulse&) {
    send(h.source, ReportHeartbeatPulse{});
  });

  handle<SetComponentAuthority>(Access::controller, false, [this](const Header& h, const SetComponentAuthority& m) {
    // Safety (an operator above the ceiling always wins): a component that
    // controls others requests with its own authority, so its controller may
    // not raise it above max_authority. Refused means not applied (the RA has
    // no reply to this message); Query Component Authority keeps reporting
    // the authority in effect. Lowering it, or any value up to the ceiling, is applied.
    if (config_.max_authority && m.authority > *config_.max_authority) {
      ++counters_.refused_authority_changes;
      log_repeated({"authority changes refused", kNoteworthyBurst}, LogLevel::warn, [&] {
        return "Set Component Authority " + std::to_string(m.authority) + " from " + h.source.to_string() +
               " refused: above max_authority " + std::to_string(*config_.max_authority) +
               " (an operator above it must always be able to take over what this component controls); authority stays " +
               std::to_string(control_.own_authority());
      });
      return;
    }
    log_repeated({"authority changes", kNoteworthyBurst}, LogLevel::info, [&] {
      return "authority " + std::to_string(control_.own_authority()) + " -> " + std::to_string(m.authority) +
             " (by " + h.source.to_string() + ")";
    });
    control_.set_own_authority(m.authority);
  });
  handle<SetTime>(Access::controller, false, [this](const Header&, const SetTime& m) { on_set_time(m); });

  handle<Shutdown>(Access::controller, false,
                   [this](const Header& h, const Shutdown&) { transition(LifecycleEvent::shutdown, h.source); });
  handle<Reset>(Access::controller, false, [this](const Header& h, const Reset&) {
    transition(LifecycleEvent::reset, h.source);
    if (lifecycle_.state() == PrimaryStatus::initialize) run_initialisation();
  });
  handle<Resume>(Access::controller, false,
                 [this](const Header& h, const Resume&) { transition(LifecycleEvent::resume, h.source); });
  // Standby and Set Emergency only make the vehicle safer: anyone may send
  // them, but an observer (a host not allowed to command) may not stop the
  // vehicle in a way it would need Resume (a controller's) to undo.
  handle<Standby>(Access::anyone, false, [this](const Header& h, const Standby&) {
    if (standing_ == SenderStanding::observer) return refuse_for_standing(h, "Standby");
    transition(LifecycleEvent::standby, h.source);
  });
  handle<SetEmergency>(Access::anyone, false,
                       [this](const Header& h, const SetEmergency& m) { on_set_emergency(h, m); });
  handle<ClearEmergency>(Access::anyone, false,
                         [this](const Header& h, const ClearEmergency& m) { on_clear_emergency(h, m); });

  // Service connections: anyone the node can record may subscribe to
  // reports; command SCs check control themselves (response 3 for a
  // non-controller); on_create_service_connection refuses by standing.
  handle<CreateServiceConnection>(Access::anyone, false, [this](const Header& h, const CreateServiceConnection& m) {
    on_create_service_connection(h, m);
  });
  handle<ConfirmServiceConnection>(Access::anyone, false, [this](const Header& h, const ConfirmServiceConnection& m) {
    subscriptions_.on_confirm(h, m);
  });
  handle<ActivateServiceConnection>(Access::anyone, false,
                                    [this](const Header& h, const ActivateServiceConnection& m) { services_.on_activate(h, m); });
  handle<SuspendServiceConnection>(Access::anyone, false,
                                   [this](const Header& h, const SuspendServiceConnection& m) { services_.on_suspend(h, m); });
  handle<TerminateServiceConnection>(Access::anyone, false, [this](const Header& h, const TerminateServiceConnection& m) {
    services_.on_terminate(h, m);
  });

  handle<RequestComponentControl>(Access::anyone, false,
                                  [this](const Header& h, const RequestComponentControl& m) { on_request_control(h, m); });
  handle<ReleaseComponentControl>(Access::anyone, false,
                                  [this](const Header& h, const ReleaseComponentControl&) { on_release_control(h); });
}

// ---- emergency -----------------------------------------------------------------

void Component::on_set_emergency(const Header& h, const msg::SetEmergency& m) {
  if ((m.emergency_code & 0x1) == 0) {
    log_repeated("Set Emergency without the Stop bit ignored", LogLevel::warn,
                 [&] { return "Set Emergency from " + h.source.to_string() + " without the Stop bit ignored"; });
    return;
  }
  if (standing_ == SenderStanding::unrecorded) {
    // Obeyed, fail safe: the node cannot tie this ID to a sender, so the hold
    // is the latch's unnamed one (as its overflow), released only locally.
    ++counters_.unrecorded_emergencies;
    const bool first = emergency_->hold_unrecorded();
    log_repeated(first ? Repeated{"emergency Stop set", kNoteworthyBurst} : Repeated{"repeated Set Emergency"},
                 LogLevel::warn, [&] {
                   return "emergency Stop set by " + h.source.to_string() + ", " +
                          std::string(to_string(standing_)) + ": held until cleared locally";
                 });
    return;
  }
  const bool first = emergency_->set(h.source);  // every member follows (follow_emergency)
  if (first) {
    log_repeated({"emergency Stop set", kNoteworthyBurst}, LogLevel::warn,
                 [&] { return "emergency Stop set by " + h.source.to_string(); });
    return;
  }
  // Already held: the platform is already stopped; nothing changes, and a
  // flood of repeats is one line and a count per window.
  log_repeated("repeated Set Emergency", LogLevel::warn, [&] {
    return "emergency Stop set by " + h.source.to_string() + " (already in Emergency" +
           (emergency_->overflowed() ? "; holders beyond the recorded ones hold it until cleared locally" : "") + ")";
  });
}

void Component::on_clear_emergency(const Header& h, const msg::ClearEmergency& m) {
  if ((m.emergency_code & 0x1) == 0) {
    log_repeated("Clear Emergency without the Stop bit ignored", LogLevel::warn,
                 [&] { return "Clear Emergency from " + h.source.to_string() + " without the Stop bit ignored"; });
    return;
  }
  if (standing_ == SenderStanding::unrecorded) {
    // Not trusted to be the holder it names: the hold stays (its own, if it
    // set one, is unnamed and released only locally).
    ++counters_.refused_clears;
    return refuse_for_standing(h, "Clear Emergency");
  }
  switch (emergency_->clear(h.source)) {  // on the last one, every member follows
    case EmergencyLatch::ClearResult::not_a_holder:
      ++counters_.refused_clears;
      log_repeated("Clear Emergency from a non-holder refused", LogLevel::warn,
                   [&] { return "Clear Emergency from " + h.source.to_string() + " refused: it holds no emergency"; });
      return;
    case EmergencyLatch::ClearResult::still_held: {
      ++counters_.refused_clears;
      log_repeated("Clear Emergency while others hold it", LogLevel::warn, [&] {
        return "emergency cleared by " + h.source.to_string() + "; still held by " + emergency_->describe_holders();
      });
      return;
    }
    case EmergencyLatch::ClearResult::refused:
      // Its Report Component Status still says Emergency: the OCU sees its clear not taken.
      ++counters_.refused_clears;
      log_repeated("Clear Emergency refused while holds cannot be persisted", LogLevel::error, [&] {
        return "Clear Emergency from " + h.source.to_string() +
               " refused: the emergency holds cannot be persisted (state directory); held until they can be, "
               "or until the local clear";
      });
      return;
    case EmergencyLatch::ClearResult::released_last:
      return;
  }
}

// ---- service connections -----------------------------------------------------

void Component::on_create_service_connection(const Header& h, const msg::CreateServiceConnection& m) {
  if (standing_ == SenderStanding::unrecorded) {
    // Response 4, "refused due to internal component restrictions": the
    // node has no room to record the requester, so it could never end the
    // connection when the requester goes; the same code the provider gives
    // when its own table is full, so a requester may retry later.
    refuse_for_standing(h, "Create Service Connection");
    return services_.refuse(h, m, msg::sc_response::kRefused);
  }
  if (standing_ == SenderStanding::observer && services_.accepts_command(m.command_code)) {
    // Response 3, as for any non-controller: an observer never commands.
    refuse_for_standing(h, "Create Service Connection (command)");
    return services_.refuse(h, m, msg::sc_response::kInsufficientAuthority);
  }
  services_.on_create(h, m);
}

// ---- control -------------------------------------------------------------------

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
                 [&] { return "controlled by " + describe(*control_.controller()) + ": " + std::string(outcome.why); });
    arm_controller_watch();
    end_stale_command_connections("control changed hands");
  }
  if (outcome.displaced) {
    send(outcome.displaced->address, msg::RejectComponentControl{});
    log_repeated({"control taken over", kNoteworthyBurst}, LogLevel::info,
                 [&] { return "control taken from " + describe(*outcome.displaced); });
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
                 [&] { return "control of " + describe(*previous) + " dropped: " + std::string(why); });
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
