// Components broken on purpose, each in a way a conformance case must catch,
// on a node of their own (subsystem 3, node 1, on a memory network):
//   3.1.50.1 obeys anyone: a Reset from a non-controller puts it in Failure;
//   3.1.51.1 never confirms a service connection (it provides Report Global Pose);
//   3.1.52.1 echoes the presence vector it is asked for, whatever it has
//            (its hand-made service connection also ignores Suspend and outlives a
//            silent requester);
//   3.1.67.1 .. 3.1.70.1 keep control by hand, each with one flaw (ControlFlaw);
//   3.1.71.1 leaves Emergency on the first holder's Clear Emergency;
//   3.1.72.1 serves its service connections by hand and takes Activate from
//            an inform connection's creator;
//   3.1.76.1 does not answer Query Component Authority in Standby;
//   3.1.77.1 .. 3.1.79.1 keep control by hand, each with one more ControlFlaw;
//   3.1.80.1 .. 3.1.82.1 serve service connections by hand, each with one more
//            ConnectionFlaw;
//   3.1.85.1 keeps control by hand, its controller's first authority kept;
//   3.1.83.1 ignores Standby; 3.1.84.1 answers Query Component Authority
//            with an empty report and Query Heartbeat Pulse not at all;
//   3.1.53.1 .. 3.1.66.1 drivers, sensors, cameras and arms broken for the
//   per-kind cases (broken_kind_components.hpp).
#pragma once

#include <memory>
#include <optional>

#include "broken_kind_components.hpp"
#include "jaus/messages/all.hpp"
#include "memory_node.hpp"
#include "target_node.hpp"

namespace jaus::conform::test {

inline const Address kObeysAnyone{3, 1, 50, 1};
inline const Address kNeverConfirms{3, 1, 51, 1};
inline const Address kEchoesPresence{3, 1, 52, 1};
inline const Address kAnyoneTakesOver{3, 1, 67, 1};
inline const Address kNeverTakenOver{3, 1, 68, 1};
inline const Address kAnyoneReleases{3, 1, 69, 1};
inline const Address kKeepsSilentController{3, 1, 70, 1};
inline const Address kFirstClearEnds{3, 1, 71, 1};
inline const Address kActivatesInform{3, 1, 72, 1};
inline const Address kSilentInStandby{3, 1, 76, 1};
inline const Address kGrantsBelowOwnAuthority{3, 1, 77, 1};
inline const Address kIgnoresRelease{3, 1, 78, 1};
inline const Address kRefusesRenewal{3, 1, 79, 1};
inline const Address kSlowReports{3, 1, 80, 1};
inline const Address kIgnoresTerminate{3, 1, 81, 1};
inline const Address kAcceptsAnyConnection{3, 1, 82, 1};
inline const Address kIgnoresStandby{3, 1, 83, 1};
inline const Address kAnswersWrongly{3, 1, 84, 1};
inline const Address kKeepsFirstAuthority{3, 1, 85, 1};
// The authority of kGrantsBelowOwnAuthority: a request at 4 must be refused.
inline constexpr std::uint8_t kOwnAuthority = 5;

// Answers Query Component Authority in every state but Standby (Part 3: "in
// any state").
class SilentInStandby final : public rt::Component {
 public:
  SilentInStandby(rt::ComponentConfig config, rt::Environment env) : Component(std::move(config), std::move(env)) {
    handle<msg::QueryComponentAuthority>(Access::anyone, false,
                                         [this](const Header& h, const msg::QueryComponentAuthority&) {
                                           if (state() != rt::PrimaryStatus::standby)
                                             send(h.source, msg::ReportComponentAuthority{{0}});
                                         });
  }
};

// Sends `report` as a hand-made service connection's provider does: the SC
// flag and the connection's sequence number.
template <class M>
void send_on_connection(rt::Outbox& outbox, const Address& from, const Address& to, std::uint16_t sequence,
                        const M& report) {
  std::vector<std::uint8_t> payload(kMaxPayloadSize);
  const auto size = wire::encode_payload(report, payload);
  Header h;
  h.command_code = M::code;
  h.source = from;
  h.destination = to;
  h.service_connection = true;
  h.sequence = sequence;
  h.data_size = static_cast<std::uint16_t>(size ? *size : 0);
  outbox.send(h, std::span(payload).first(size ? *size : 0));
}

class ObeysAnyone final : public rt::Component {
 public:
  ObeysAnyone(rt::ComponentConfig config, rt::Environment env) : Component(std::move(config), std::move(env)) {
    // The broken part: Reset is executed whoever sends it.
    handle<msg::Reset>(Access::anyone, false, [this](const Header& h, const msg::Reset&) {
      declare_failure("Reset by " + h.source.to_string());
    });
  }
};

class NeverConfirms final : public rt::Component {
 public:
  NeverConfirms(rt::ComponentConfig config, rt::Environment env) : Component(std::move(config), std::move(env)) {
    provide<msg::ReportGlobalPose>(jausctl::test::PoseSensor::kAvailable,
                                   [] { return jausctl::test::PoseSensor::pose(); });
    handle<msg::CreateServiceConnection>(Access::anyone, false,
                                         [](const Header&, const msg::CreateServiceConnection&) {});  // silence
  }
};

// Serves its one service connection by hand, sending the requested presence
// vector back instead of the requested AND available one.
class EchoesPresence final : public rt::Component {
 public:
  EchoesPresence(rt::ComponentConfig config, rt::Environment env) : Component(std::move(config), std::move(env)) {
    provide<msg::ReportGlobalPose>(jausctl::test::PoseSensor::kAvailable,
                                   [] { return jausctl::test::PoseSensor::pose(); });
    handle<msg::CreateServiceConnection>(Access::anyone, false,
                                         [this](const Header& h, const msg::CreateServiceConnection& m) {
                                           msg::ConfirmServiceConnection confirm;
                                           confirm.command_code = m.command_code;
                                           confirm.confirmed_rate_hz = m.periodic_rate_hz;
                                           send(h.source, confirm);
                                           requester_ = h.source;
                                           presence_ = m.presence_vector;
                                           report_in(std::chrono::milliseconds(1));
                                         });
    handle<msg::TerminateServiceConnection>(
        Access::anyone, false, [this](const Header&, const msg::TerminateServiceConnection&) { requester_.reset(); });
  }
  ~EchoesPresence() override { env().scheduler.cancel(timer_); }

 private:
  void report_in(rt::Duration delay) {
    timer_ = env().scheduler.call_at(env().clock.now() + delay, [this] {
      if (!requester_) return;
      // Every field, those it does not have (attitude, time stamp) too.
      msg::ReportGlobalPose report = jausctl::test::PoseSensor::pose();
      report.attitude_rms_rad = 0.1;
      report.time_stamp = TimeStamp{1, 2, 3, 4, 5};
      wire::mask_presence(report, presence_);  // the broken part: not AND the available fields
      send_on_connection(env().outbox, address(), *requester_, sequence_++, report);
      report_in(std::chrono::milliseconds(100));
    });
  }

  std::optional<Address> requester_;
  std::uint32_t presence_ = 0;
  std::uint16_t sequence_ = 0;
  rt::TimerId timer_ = rt::kNoTimer;
};

// Inform service connections of Report Global Pose served by hand, one at a
// time at 10 Hz, as the RA says but for one flaw.
enum class ConnectionFlaw {
  activates_inform,   // Activate from the creator of an inform connection starts it again
  slow_reports,       // confirms the rate asked for, sends at 2 Hz
  ignores_terminate,  // Terminate changes nothing
  accepts_anything,   // creates connections for reports it does not provide, at any rate
};

class HandMadeConnections final : public rt::Component {
 public:
  HandMadeConnections(rt::ComponentConfig config, rt::Environment env, ConnectionFlaw flaw)
      : Component(std::move(config), std::move(env)), flaw_(flaw) {
    provide<msg::ReportGlobalPose>(jausctl::test::PoseSensor::kAvailable,
                                   [] { return jausctl::test::PoseSensor::pose(); });
    handle<msg::CreateServiceConnection>(
        Access::anyone, false, [this](const Header& h, const msg::CreateServiceConnection& m) {
          msg::ConfirmServiceConnection confirm;
          confirm.command_code = m.command_code;
          if (flaw_ != ConnectionFlaw::accepts_anything && m.command_code != msg::ReportGlobalPose::code) {
            confirm.response_code = msg::sc_response::kCommandNotSupported;
          } else if (flaw_ != ConnectionFlaw::accepts_anything && !(m.periodic_rate_hz >= 0.0166)) {
            confirm.response_code = msg::sc_response::kInvalidParameters;
          } else {
            confirm.confirmed_rate_hz = flaw_ == ConnectionFlaw::slow_reports ? m.periodic_rate_hz : 10;
            requester_ = h.source;
            active_ = true;
            report_in(std::chrono::milliseconds(1));
          }
          send(h.source, confirm);
        });
    handle<msg::SuspendServiceConnection>(
        Access::anyone, false, [this](const Header&, const msg::SuspendServiceConnection&) { active_ = false; });
    handle<msg::ActivateServiceConnection>(Access::anyone, false,
                                           [this](const Header&, const msg::ActivateServiceConnection&) {
                                             if (flaw_ == ConnectionFlaw::activates_inform) active_ = true;
                                           });
    handle<msg::TerminateServiceConnection>(Access::anyone, false,
                                            [this](const Header&, const msg::TerminateServiceConnection&) {
                                              if (flaw_ != ConnectionFlaw::ignores_terminate) requester_.reset();
                                            });
  }
  ~HandMadeConnections() override { env().scheduler.cancel(timer_); }

 private:
  void report_in(rt::Duration delay) {
    env().scheduler.cancel(timer_);
    timer_ = env().scheduler.call_at(env().clock.now() + delay, [this] {
      if (!requester_) return;
      if (active_) {
        send_on_connection(env().outbox, address(), *requester_, sequence_++, jausctl::test::PoseSensor::pose());
      }
      report_in(flaw_ == ConnectionFlaw::slow_reports ? std::chrono::milliseconds(500)
                                                      : std::chrono::milliseconds(100));
    });
  }

  ConnectionFlaw flaw_;
  std::optional<Address> requester_;
  bool active_ = false;
  std::uint16_t sequence_ = 0;
  rt::TimerId timer_ = rt::kNoTimer;
};

// Standby from its controller changes nothing.
class IgnoresStandby final : public rt::Component {
 public:
  IgnoresStandby(rt::ComponentConfig config, rt::Environment env) : Component(std::move(config), std::move(env)) {
    handle<msg::Standby>(Access::controller, false, [](const Header&, const msg::Standby&) {});
  }
};

// Query Component Authority answered with an empty report (one byte short),
// Query Heartbeat Pulse not at all.
class AnswersWrongly final : public rt::Component {
 public:
  AnswersWrongly(rt::ComponentConfig config, rt::Environment env) : Component(std::move(config), std::move(env)) {
    handle<msg::QueryComponentAuthority>(Access::anyone, false,
                                         [this](const Header& h, const msg::QueryComponentAuthority&) {
                                           Header out;
                                           out.command_code = msg::ReportComponentAuthority::code;
                                           out.source = address();
                                           out.destination = h.source;
                                           this->env().outbox.send(out, {});
                                         });
    handle<msg::QueryHeartbeatPulse>(Access::anyone, false, [](const Header&, const msg::QueryHeartbeatPulse&) {});
  }
};

// Control kept by hand (the runtime's arbiter is private to Component), as
// the RA says but for one flaw; none has a controller liveness check, which
// is the flaw of keeps_silent_controller.
enum class ControlFlaw {
  anyone_takes_over,        // any request from another requester takes control, whatever its authority
  never_taken_over,         // a higher authority from another requester is refused
  anyone_releases,          // a Release from anyone ends control
  keeps_silent_controller,  // only the missing liveness check
  ignores_own_authority,    // grants control below its own authority (configured above 0)
  ignores_release,          // its controller's Release changes nothing
  refuses_renewal,          // its controller asking again is refused
  keeps_first_authority,    // its controller asking again at another authority keeps the first
};

class HandMadeControl final : public rt::Component {
 public:
  HandMadeControl(rt::ComponentConfig config, rt::Environment env, ControlFlaw flaw)
      : Component(std::move(config), std::move(env)), flaw_(flaw) {
    handle<msg::RequestComponentControl>(
        Access::anyone, false, [this](const Header& h, const msg::RequestComponentControl& m) {
          const bool taken_over = controller_ && *controller_ != h.source &&
                                  (flaw_ == ControlFlaw::anyone_takes_over ||
                                   (flaw_ != ControlFlaw::never_taken_over && m.authority > authority_));
          const bool renewal = controller_ && *controller_ == h.source;
          const bool granted = !controller_ || (renewal && flaw_ != ControlFlaw::refuses_renewal) || taken_over;
          if (taken_over) send(*controller_, msg::RejectComponentControl{});
          if (granted) {
            controller_ = h.source;
            if (!(renewal && flaw_ == ControlFlaw::keeps_first_authority)) authority_ = m.authority;
          }
          send(h.source, msg::ConfirmComponentControl{
                             {granted ? msg::control_response::kAccepted : msg::control_response::kNotAccepted}});
        });
    handle<msg::ReleaseComponentControl>(Access::anyone, false,
                                         [this](const Header& h, const msg::ReleaseComponentControl&) {
                                           if (flaw_ == ControlFlaw::ignores_release) return;
                                           if (controller_ == h.source || flaw_ == ControlFlaw::anyone_releases)
                                             controller_.reset();
                                         });
    handle<msg::QueryComponentControl>(
        Access::anyone, false, [this](const Header& h, const msg::QueryComponentControl&) {
          send(h.source, msg::ReportComponentControl{{controller_.value_or(Address{0, 0, 0, 0}), authority_}});
        });
  }

 private:
  ControlFlaw flaw_;
  std::optional<Address> controller_;
  std::uint8_t authority_ = 0;
};

// Emergency kept by hand with one flag instead of a holder per sender: the
// first Clear Emergency ends it, whoever else still holds it.
class FirstClearEnds final : public rt::Component {
 public:
  FirstClearEnds(rt::ComponentConfig config, rt::Environment env) : Component(std::move(config), std::move(env)) {
    handle<msg::SetEmergency>(Access::anyone, false, [this](const Header&, const msg::SetEmergency&) { set_ = true; });
    handle<msg::ClearEmergency>(Access::anyone, false,
                                [this](const Header&, const msg::ClearEmergency&) { set_ = false; });
    handle<msg::QueryComponentStatus>(Access::anyone, false, [this](const Header& h, const msg::QueryComponentStatus&) {
      const auto state = set_ ? msg::PrimaryStatus::emergency : msg::PrimaryStatus::ready;
      send(h.source, msg::ReportComponentStatus{{static_cast<std::uint8_t>(state), set_ ? 1u : 0u}});
    });
  }

 private:
  bool set_ = false;
};

class BrokenNode {
 public:
  BrokenNode(rt::VirtualTime& time, testing::MemoryNetwork& network) : node_(time, network, node_config()) {
    node_.emplace<ObeysAnyone>("obeys anyone", kObeysAnyone.component);
    node_.emplace<NeverConfirms>("never confirms", kNeverConfirms.component);
    node_.emplace<EchoesPresence>("echoes presence", kEchoesPresence.component);
    add<HandMadeControl>("anyone takes over", kAnyoneTakesOver, ControlFlaw::anyone_takes_over);
    add<HandMadeControl>("never taken over", kNeverTakenOver, ControlFlaw::never_taken_over);
    add<HandMadeControl>("anyone releases", kAnyoneReleases, ControlFlaw::anyone_releases);
    add<HandMadeControl>("keeps silent controller", kKeepsSilentController, ControlFlaw::keeps_silent_controller);
    node_.emplace<FirstClearEnds>("first clear ends", kFirstClearEnds.component);
    add<HandMadeConnections>("activates inform", kActivatesInform, ConnectionFlaw::activates_inform);
    add<HandMadeConnections>("slow reports", kSlowReports, ConnectionFlaw::slow_reports);
    add<HandMadeConnections>("ignores terminate", kIgnoresTerminate, ConnectionFlaw::ignores_terminate);
    add<HandMadeConnections>("accepts any connection", kAcceptsAnyConnection, ConnectionFlaw::accepts_anything);
    auto own_authority = node_.component_config("grants below own authority", kGrantsBelowOwnAuthority.component);
    own_authority.authority = kOwnAuthority;
    node_.add<HandMadeControl>(std::move(own_authority), ControlFlaw::ignores_own_authority);
    add<HandMadeControl>("ignores release", kIgnoresRelease, ControlFlaw::ignores_release);
    add<HandMadeControl>("refuses renewal", kRefusesRenewal, ControlFlaw::refuses_renewal);
    add<HandMadeControl>("keeps first authority", kKeepsFirstAuthority, ControlFlaw::keeps_first_authority);
    node_.emplace<IgnoresStandby>("ignores standby", kIgnoresStandby.component);
    node_.emplace<AnswersWrongly>("answers wrongly", kAnswersWrongly.component);
    node_.emplace<SilentInStandby>("silent in standby", kSilentInStandby.component);
    add<BrokenDriver>("driver obeys anyone", kDriverObeysAnyone, DriverFlaw::obeys_anyone);
    add<BrokenDriver>("driver forgets effort", kDriverForgetsEffort, DriverFlaw::forgets_effort);
    add<BrokenDriver>("driver keeps effort", kDriverKeepsEffortOnStop, DriverFlaw::keeps_effort_on_stop);
    add<BrokenDriver>("driver resumes effort", kDriverResumesLatchedEffort, DriverFlaw::resumes_latched_effort);
    add<BrokenPoseSensor>("frozen time", kSensorFrozenTime, SensorFlaw::frozen_time);
    add<BrokenPoseSensor>("echoes query presence", kSensorEchoesQueryPresence, SensorFlaw::echoes_query_presence);
    add<BrokenPoseSensor>("sc elsewhere", kSensorScElsewhere, SensorFlaw::sc_elsewhere);
    add<BrokenCameras>("ignores selection", kCamerasIgnoreSelection, CamerasFlaw::ignores_selection);
    add<BrokenCameras>("cameras obey anyone", kCamerasObeyAnyone, CamerasFlaw::obeys_anyone);
    add<BrokenCameras>("mislabels format", kCamerasMislabelFormat, CamerasFlaw::mislabels_format);
    add<BrokenArm>("arm executes partly", kArmExecutesPartly, ArmFlaw::executes_partly);
    add<BrokenArm>("arm obeys anyone", kArmObeysAnyone, ArmFlaw::obeys_anyone);
    add<BrokenArm>("arm keeps moving", kArmKeepsMovingOnStop, ArmFlaw::keeps_moving_on_stop);
    add<BrokenArm>("arm miscounts joints", kArmMiscountsJoints, ArmFlaw::miscounts_joints);
    add<BrokenDriver>("driver keeps effort on reset", kDriverKeepsEffortOnReset, DriverFlaw::keeps_effort_on_reset);
    add<BrokenDriver>("driver keeps effort on takeover", kDriverKeepsEffortOnTakeover,
                      DriverFlaw::keeps_effort_on_takeover);
    add<BrokenArm>("arm keeps moving on release", kArmKeepsMovingOnRelease, ArmFlaw::keeps_moving_on_release);
  }
  node::Node& node() { return node_.node(); }

 private:
  static node::NodeConfig node_config() {
    node::NodeConfig config;
    config.subsystem = 3;
    config.node = 1;
    return config;
  }
  template <class C, class Flaw>
  void add(const char* name, const Address& at, Flaw flaw) {
    node_.emplace<C>(name, at.component, flaw);
  }

  test_support::MemoryNode node_;
};

}  // namespace jaus::conform::test
