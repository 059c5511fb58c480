// The core messages every component answers (Part 3's core: authority,
// status, time, lifecycle commands, service connections, control), each
// registered with who may send it.
#include "jaus/messages/communications_messages.hpp"
#include "jaus/messages/discovery_messages.hpp"
#include "jaus/runtime/component.hpp"
#include "jaus/runtime/stop_counter.hpp"

namespace jaus::rt {

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

}  // namespace jaus::rt
