// The behaviour every JAUS component shares: identity and authority, the
// lifecycle, control arbitration with controller liveness, emergency holders,
// the core queries, and a handler table by command code that enforces who may
// command and in which state.
//
// Safety (where "the platform is commanded to stop" is kept): a component
// that drives hardware overrides command_stop(). It is called
//   - whenever the lifecycle leaves Ready (Standby, Emergency, Reset, Shutdown, Failure),
//   - whenever control is lost (released, taken over, or controller silent),
// see Component::enforce_stop(). Commands that move hardware are registered
// `ready_only`, so nothing moves outside Ready or without a live controller.
//
// Who may do what, by the sender's standing (rt::SenderStanding, decided by
// the transport and the node's liveness table; issue 28). The rule: what a
// sender asks may leave state behind only when the node can tie that state
// to the sender and end it when the sender goes (liveness), and only hosts
// allowed to command (transport.control_from) may change the component.
//   - trusted: everything the handlers allow (control, then commands).
//   - observer (outside transport.control_from): queries, inform service
//     connections (reports), Set Emergency and Clear Emergency of its own
//     hold. Refused: Request Component Control (answered as any refused
//     request), Standby, command service connections (response 3, as for a
//     non-controller), and every controller-only message, even from a
//     controller that became an observer.
//   - unrecorded (the node's tables are full): queries are answered,
//     Standby is obeyed (it only stops), Set Emergency is obeyed as a hold
//     only the local clear releases (EmergencyLatch::hold_unrecorded: its ID
//     cannot be tied to a sender, so no Clear Emergency is trusted to be its
//     own). Refused, since the node could never end what it would leave:
//     Create Service Connection (response 4), Request Component Control,
//     Clear Emergency, controller-only messages; derived components refuse
//     their own state-keeping requests (the node manager's Create Event)
//     through sender_standing().
// Every refusal is counted (refused_observer, refused_unrecorded) and logged
// through the repeat limiter. Release Component Control, Terminate/Suspend
// Service Connection and Cancel Event only end state: open to all.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <unordered_map>
#include <vector>

#include "jaus/messages/compiled_codecs.hpp"
#include "jaus/messages/core_messages.hpp"
#include "jaus/messages/discovery_messages.hpp"
#include "jaus/runtime/control_arbiter.hpp"
#include "jaus/runtime/emergency_latch.hpp"
#include "jaus/runtime/environment.hpp"
#include "jaus/runtime/lifecycle.hpp"
#include "jaus/runtime/repeat_limiter.hpp"
#include "jaus/runtime/sender_standing.hpp"
#include "jaus/runtime/service_connection_client.hpp"
#include "jaus/runtime/service_connections.hpp"

namespace jaus::rt {

// The largest message a component sends (as a large data set when over 4080 bytes).
inline constexpr std::size_t kMaxLargeDataSetSize = 1024 * 1024;

struct ComponentConfig {
  std::string name = "component";
  Address address;
  std::uint8_t authority = 0;
  // The highest authority this component may have, for a component that
  // controls others (the drivers above the primitive driver request it with
  // their own authority): Set Component Authority above it is refused (not
  // applied, counted, logged), so an operator above it always wins. None:
  // no ceiling (a component that controls nobody).
  std::optional<std::uint8_t> max_authority;
  // Silence from the controller longer than this releases control (0 disables).
  Duration controller_timeout = std::chrono::seconds(3);
  // Refused control requests get Reject Component Control instead of Confirm 2.
  bool reject_refused_requests = false;
  ServiceConnectionLimits service_connections;
};

struct ComponentCounters {
  std::uint64_t received = 0;
  std::uint64_t decode_errors = 0;
  std::uint64_t unsupported = 0;
  std::uint64_t refused_not_controller = 0;
  std::uint64_t refused_wrong_state = 0;
  std::uint64_t refused_transitions = 0;
  std::uint64_t refused_clears = 0;
  std::uint64_t control_changes = 0;
  // Set Component Authority above max_authority, not applied.
  std::uint64_t refused_authority_changes = 0;
  std::uint64_t stops_commanded = 0;
  // Entries into a state other than Ready (Emergency, Standby, Failure,
  // Shutdown, Initialize): the stop counter of Report Component Status.
  std::uint64_t stops_entered = 0;
  // Requests refused for the sender's standing (see the header comment).
  std::uint64_t refused_observer = 0;
  std::uint64_t refused_unrecorded = 0;
  // Set Emergency from unrecorded senders, held until the local clear.
  std::uint64_t unrecorded_emergencies = 0;
};

class Component {
 public:
  Component(ComponentConfig config, Environment env);
  virtual ~Component();
  Component(const Component&) = delete;
  Component& operator=(const Component&) = delete;

  // Runs initialisation: Initialize -> Ready, or Failure; or stays in
  // Initialize while the component waits for its hardware (wait_for_hardware).
  void start();
  // Local shutdown (the node is stopping): as a Shutdown message would, it
  // stops the platform, drops control and ends every service connection.
  void shutdown(std::string_view why);
  // One received message (header + payload). Never throws; bad payloads are
  // counted and logged, never acted upon. `standing` is what the node knows
  // of the sender (local components are trusted); see the header comment.
  void receive(const Header& header, std::span<const std::uint8_t> payload,
               wire::Dialect dialect = wire::Dialect::ra, SenderStanding standing = SenderStanding::trusted);

  const Address& address() const { return config_.address; }
  const std::string& name() const { return config_.name; }
  PrimaryStatus state() const { return lifecycle_.state(); }
  const ControlArbiter& control() const { return control_; }
  const EmergencyLatch& emergency() const { return *emergency_; }
  const ComponentCounters& counters() const { return counters_; }
  const ServiceConnectionProvider& service_connections() const { return services_; }

  // Opens a service connection to `provider` for report M; each report is
  // decoded and handed to `on_report`. The SC is created again when reports
  // stop. Returns an id for unsubscribe() and subscription().
  template <class M>
  SubscriptionId subscribe(const Address& provider, double rate_hz, std::uint32_t presence_vector,
                           std::function<void(const Header&, const M&)> on_report) {
    return subscriptions_.subscribe(
        provider, M::code, rate_hz, presence_vector,
        [this, on_report = std::move(on_report)](const Header& h, std::span<const std::uint8_t> payload) {
          M report{};
          if (auto decoded = wire::decode_payload_into(payload, report, wire::Dialect::ra, kHeaderSize); !decoded) {
            ++counters_.decode_errors;
            log(LogLevel::warn, "malformed " + std::string(M::name) + " from " + h.source.to_string() + ": " +
                                    decoded.error().message());
            return;
          }
          on_report(h, report);
        });
  }
  // The same for a report known only by its code (tools, bridges): each
  // report's payload is handed over undecoded.
  SubscriptionId subscribe_code(const Address& provider, std::uint16_t report_code, double rate_hz,
                                std::uint32_t presence_vector,
                                std::function<void(const Header&, std::span<const std::uint8_t>)> on_report) {
    return subscriptions_.subscribe(provider, report_code, rate_hz, presence_vector, std::move(on_report));
  }
  void unsubscribe(SubscriptionId id) { subscriptions_.unsubscribe(id); }
  const SubscriptionStatus* subscription(SubscriptionId id) const { return subscriptions_.status(id); }

  // What this component accepts (command codes with a handler) and offers on
  // service connections (report code -> available presence vector), for
  // Report Services.
  std::vector<std::uint16_t> input_codes() const;
  std::map<std::uint16_t, std::uint32_t> output_codes() const { return services_.provided(); }
  // What this component accepts and provides, as Report Services lists it.
  msg::ServiceEntry service_entry() const;

  // Emergency from the hardware itself (a platform's e-stop button or pause):
  // a local hold named `cause`, so the component is in Emergency until the
  // same cause is released, whatever JAUS Clear Emergency says; JAUS holders
  // still hold their own. Idempotent.
  void hold_hardware_emergency(std::string_view cause);
  void release_hardware_emergency(std::string_view cause);
  // Shares `latch` (owned by the caller, outliving this component) instead of
  // the component's own: a Set Emergency to any member holds them all
  // (emergency_scope: vehicle), and each holder clears its own hold from any.
  // Call before start().
  void share_emergency(EmergencyLatch& latch);
  // Hears every lifecycle transition, after the component has acted on it
  // (a host mirrors Emergency onto a platform's e-stop this way).
  using StateListener = std::function<void(PrimaryStatus before, PrimaryStatus after)>;
  void on_state_change(StateListener listener) { state_listener_ = std::move(listener); }

  // The node's liveness table says `peer` is gone (a node or subsystem, with
  // 0 below its level: every component under it is gone too): their service
  // connections end, and if the controller was among them, control is dropped
  // (platform stops).
  void peer_lost(const Address& peer);
  // Whether this component keeps state for a component under `node` (a node
  // address, 0 below: Address::covers): it is the controller, holds an
  // emergency on this component's latch (own or shared), or requests a
  // service connection. The transport keeps such a node's route pinned.
  // Derived components add what they keep (the node manager's events).
  virtual bool keeps_state_for(const Address& node) const;

 protected:
  // Who may have a message executed.
  enum class Access { anyone, controller };

  // Registers the handler of M. Controller-only, Ready-only messages are the
  // ones that move things; they may also arrive on command service connections.
  template <class M>
  void handle(Access access, bool ready_only, std::function<void(const Header&, const M&)> fn) {
    if (access == Access::controller && ready_only) services_.accept_commands(M::code);
    handlers_[M::code] = Handler{access, ready_only, M::name,
                                 [fn = std::move(fn)](const Header& h, std::span<const std::uint8_t> payload,
                                                      wire::Dialect dialect) -> Expected<void> {
                                   M message{};
                                   if (auto decoded = wire::decode_payload_into(payload, message, dialect, kHeaderSize);
                                       !decoded)
                                     return decoded;
                                   fn(h, message);
                                   return {};
                                 }};
  }

  template <class M>
  void send(const Address& to, const M& message, std::uint8_t priority = priority::kDefault) {
    // One buffer per component, reused: the outbox copies what it keeps.
    std::vector<std::uint8_t>& payload = send_buffer_;
    if (payload.size() < kMaxPayloadSize) payload.resize(kMaxPayloadSize);
    auto size = wire::encode_payload(message, payload);
    if (!size && size.error().code == ErrorCode::output_too_small) {
      // Larger than one packet (Report Image): the node sends a large data set.
      payload.resize(kMaxLargeDataSetSize);
      size = wire::encode_payload(message, payload);
    }
    if (!size) {
      log(LogLevel::error, std::string("cannot encode ") + std::string(M::name) + ": " + size.error().message());
      return;
    }
    Header header;
    header.priority = priority;
    header.command_code = M::code;
    header.destination = to;
    header.source = config_.address;
    header.data_size = static_cast<std::uint16_t>(*size);
    env_.outbox.send(header, std::span(payload).first(*size));
  }

  // A report this component can send on service connections: `produce`
  // returns the report with every field it has; fields outside the requested
  // presence vector are removed before sending. A source that updates at
  // most `max_rate_hz` (0: no limit of its own) confirms no faster rate.
  // A report over one packet (Report Image) goes as a large data set.
  template <class M>
  void provide(std::uint32_t available_presence, std::function<M()> produce, double max_rate_hz = 0) {
    provide_if<M>(
        available_presence, [produce = std::move(produce)]() -> std::optional<M> { return produce(); }, max_rate_hz);
  }
  // The same for a source that has nothing to send at times (a camera
  // outside Ready): a period whose `produce` returns nullopt sends nothing,
  // and the connection stays. Calling it (or provide) again for the same
  // report replaces the source (for every connection) and its rate (for
  // connections created after: the others keep their confirmed rate).
  template <class M>
  void provide_if(std::uint32_t available_presence, std::function<std::optional<M>()> produce,
                  double max_rate_hz = 0) {
    services_.provide(
        M::code, available_presence,
        [this, produce = std::move(produce)](std::uint32_t mask, std::vector<std::uint8_t>& payload) {
          std::optional<M> report = produce();
          if (!report) return false;
          wire::mask_presence(*report, mask);
          // The provider's buffer, reused: a report period allocates nothing.
          if (payload.size() < kMaxPayloadSize) payload.resize(kMaxPayloadSize);
          auto size = wire::encode_payload(*report, payload);
          if (!size && size.error().code == ErrorCode::output_too_small) {
            payload.resize(kMaxLargeDataSetSize);  // the node sends a large data set
            size = wire::encode_payload(*report, payload);
          }
          if (!size) {
            log(LogLevel::error, std::string("cannot encode ") + std::string(M::name) + ": " + size.error().message());
            return false;
          }
          payload.resize(*size);
          return true;
        },
        max_rate_hz);
  }

  // The fields of input `code` this component acts on (a command) or can
  // report (a query), for Report Services; 0 when not declared.
  void declare_input_presence(std::uint16_t code, std::uint32_t presence) { input_presence_[code] = presence; }

  // Safety: commands the platform to stop now (command_stop), as leaving
  // Ready does, for a reason of the component's own (a command timeout).
  void stop_platform(std::string_view why) { enforce_stop(why); }

  // A fault of the component's own (its data source went stale): Ready or
  // Standby -> Failure, which stops the platform; clear_failure() returns to
  // Ready once the fault is gone. Only a failure declared here is cleared
  // here: a failed initialisation still needs a Reset. Both are no-ops when
  // they do not apply (already failed, in Emergency, not failed by us).
  void declare_failure(std::string_view why);
  void clear_failure(std::string_view why);
  bool failure_declared() const { return failure_declared_; }

  // Initialisation that waits for the hardware's first data (RA: the
  // component stays in Initialize): initialize() calls wait_for_hardware(),
  // and hardware_ready() ends the wait (Initialize -> Ready, or when an
  // Emergency interrupted the wait, Ready once it is cleared). No-ops when
  // not waiting.
  void wait_for_hardware(std::string why);
  void hardware_ready();
  bool waiting_for_hardware() const { return waiting_for_hardware_; }

  // Hooks for derived components.
  virtual bool initialize() { return true; }
  // Bring the hardware to rest (drive: zero effort; arm: hold). Idempotent.
  virtual void command_stop(std::string_view /*why*/) {}
  // A message no handler is registered for (reports to an OCU, say). Return
  // true when taken; otherwise it is counted as unsupported.
  virtual bool unhandled(const Header& /*header*/, std::span<const std::uint8_t> /*payload*/) { return false; }
  // After every change of the lifecycle state (already in effect, the
  // platform already stopped when `after` is not Ready): a component that
  // must look at its hardware on entering a state does it here.
  virtual void state_changed(PrimaryStatus /*before*/, PrimaryStatus /*after*/) {}
  // Component-specific secondary status bits (16-19 of Report Component
  // Status; 20-31 carry the stop counter, stop_counter.hpp).
  virtual std::uint32_t component_status_bits() const { return 0; }
  // A peer is gone (peer_lost, after its service connections ended and its
  // control was taken away): what else this component keeps for it ends here.
  virtual void requester_lost(const Address& /*peer*/) {}

  // The standing of the sender of the message being handled (trusted
  // outside a handler): a derived component refuses by it what would leave
  // state the node cannot end (Create Event from an unrecorded sender).
  SenderStanding sender_standing() const { return standing_; }
  // Counts and logs (repeat-limited) a request refused for the standing of
  // its sender; the caller sends whatever refusal the message has.
  void refuse_for_standing(const Header& header, std::string_view what);

  void log(LogLevel level, const std::string& text) const;
  // A line remote input can repeat at will: written at most `kind.burst`
  // times per 10 s window of its kind (a string literal, "unsupported
  // messages ignored"), then counted, the count written when the window
  // ends; the text is only built when written.
  template <class MakeText>
  void log_repeated(Repeated kind, LogLevel level, MakeText make_text) {
    repeated_lines_.write(kind, level, make_text);
  }
  Environment& env() { return env_; }

 private:
  using Invoke = std::function<Expected<void>(const Header&, std::span<const std::uint8_t>, wire::Dialect)>;
  struct Handler {
    Access access;
    bool ready_only;
    std::string_view name;
    Invoke invoke;
  };

  void register_core_handlers();
  void dispatch(const Header& header, std::span<const std::uint8_t> payload, wire::Dialect dialect);
  msg::ReportComponentStatus status_report() const;
  void run_initialisation();
  // `by` names who asked in the log line; `cause`, when given, says why instead (a local hold).
  void transition(LifecycleEvent event, const Address& by, std::string_view cause = {});
  void enforce_stop(std::string_view why);
  void refuse_not_controller(const Header& header, std::string_view what);

  // Control.
  void on_request_control(const Header& header, const msg::RequestComponentControl& request);
  // Confirm Component Control "not accepted", or Reject if configured.
  void answer_refused_control(const Address& to);
  void on_release_control(const Header& header);
  void take_control_away(std::string_view why);
  // Control changed hands or ended: the command SCs of anyone but the new
  // controller end (a deadman belongs to the controller that announced it).
  void end_stale_command_connections(std::string_view why);
  void arm_controller_watch();
  void check_controller();
  void schedule_controller_check();

  // Emergency: the component follows its latch (its own, or the vehicle's).
  void follow_emergency();
  void on_set_emergency(const Header& header, const msg::SetEmergency& message);
  void on_clear_emergency(const Header& header, const msg::ClearEmergency& message);
  void on_create_service_connection(const Header& header, const msg::CreateServiceConnection& message);

  // Time.
  UtcTime component_time() const;
  void on_set_time(const msg::SetTime& message);

  ComponentConfig config_;
  Environment env_;
  Lifecycle lifecycle_;
  ControlArbiter control_;
  EmergencyLatch own_emergency_;
  EmergencyLatch* emergency_ = &own_emergency_;
  EmergencyLatch::MemberId emergency_membership_ = 0;
  StateListener state_listener_;
  ComponentCounters counters_;
  SenderStanding standing_ = SenderStanding::trusted;  // of the message being handled
  std::unordered_map<std::uint16_t, Handler> handlers_;
  ServiceConnectionProvider services_;
  ServiceConnectionClient subscriptions_;
  TimePoint controller_last_heard_{};
  TimerId controller_timer_ = kNoTimer;
  Duration time_offset_{};  // Set Time moves this component's clock, not the system's
  // Lines that remote input repeats at will, limited per reason (not per
  // sender, which a flood of forged sources would multiply).
  RepeatedLines repeated_lines_;
  std::vector<std::uint8_t> send_buffer_;
  bool failure_declared_ = false;  // Failure entered by declare_failure(), not by initialisation
  bool waiting_for_hardware_ = false;
  std::string waiting_for_;
  std::map<std::uint16_t, std::uint32_t> input_presence_;  // Report Services' input presence vectors
};

}  // namespace jaus::rt
