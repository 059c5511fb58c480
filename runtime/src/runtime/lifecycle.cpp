// Boost.MSM's transition tables are Boost.MPL vectors; this table has more
// rows than MPL's default limit of 20.
#define BOOST_MPL_CFG_NO_PREPROCESSED_HEADERS
#define BOOST_MPL_LIMIT_VECTOR_SIZE 30  // 26 rows
#define BOOST_MPL_LIMIT_MAP_SIZE 30

#include "jaus/runtime/lifecycle.hpp"

#include <boost/msm/back/state_machine.hpp>
#include <boost/msm/front/functor_row.hpp>
#include <boost/msm/front/state_machine_def.hpp>

namespace jaus::rt {

namespace {

namespace msmf = boost::msm::front;

// Events.
struct InitSucceeded {};
struct InitFailed {};
struct StandbyRequested {};
struct ResumeRequested {};
struct EmergencySet {};
struct EmergencyCleared {};
struct ResetRequested {};
struct ShutdownRequested {};
struct FailureDetected {};
struct FailureCleared {};

struct LifecycleDef : msmf::state_machine_def<LifecycleDef> {
  // Each state records itself as the primary status on entry.
  template <PrimaryStatus S>
  struct StatusState : msmf::state<> {
    template <class Event, class Fsm>
    void on_entry(const Event&, Fsm& fsm) {
      fsm.current = S;
    }
  };
  using Initialize = StatusState<PrimaryStatus::initialize>;
  using Ready = StatusState<PrimaryStatus::ready>;
  using Standby = StatusState<PrimaryStatus::standby>;
  using Failure = StatusState<PrimaryStatus::failure>;
  using Emergency = StatusState<PrimaryStatus::emergency>;
  struct Shutdown : StatusState<PrimaryStatus::shutdown> {};

  using initial_state = Initialize;

  // Remember which state the emergency interrupted, to return there.
  struct RememberInterrupted {
    template <class Event, class Fsm, class Source, class Target>
    void operator()(const Event&, Fsm& fsm, Source&, Target&) {
      fsm.interrupted = fsm.current;
    }
  };
  // Likewise the state a fault of the component's own interrupted (Ready or
  // Standby): its recovery returns there, so a Standby survives a fault.
  struct RememberFaultInterrupted {
    template <class Event, class Fsm, class Source, class Target>
    void operator()(const Event&, Fsm& fsm, Source&, Target&) {
      fsm.fault_interrupted = fsm.current;
    }
  };
  template <PrimaryStatus S>
  struct FaultInterrupted {
    template <class Event, class Fsm, class Source, class Target>
    bool operator()(const Event&, Fsm& fsm, Source&, Target&) {
      return fsm.fault_interrupted == S;
    }
  };
  template <PrimaryStatus S>
  struct Interrupted {
    template <class Event, class Fsm, class Source, class Target>
    bool operator()(const Event&, Fsm& fsm, Source&, Target&) {
      return fsm.interrupted == S;
    }
  };

  using none = msmf::none;
  template <class From, class Event, class To, class Action = none, class Guard = none>
  using Row = msmf::Row<From, Event, To, Action, Guard>;

  // clang-format off
  struct transition_table : boost::mpl::vector<
      Row<Initialize, InitSucceeded,    Ready>,
      Row<Initialize, InitFailed,       Failure>,
      Row<Ready,      StandbyRequested, Standby>,
      Row<Standby,    ResumeRequested,  Ready>,
      Row<Initialize, EmergencySet,     Emergency, RememberInterrupted>,
      Row<Ready,      EmergencySet,     Emergency, RememberInterrupted>,
      Row<Standby,    EmergencySet,     Emergency, RememberInterrupted>,
      Row<Failure,    EmergencySet,     Emergency, RememberInterrupted>,
      Row<Emergency,  EmergencyCleared, Ready,      none, Interrupted<PrimaryStatus::ready>>,
      Row<Emergency,  EmergencyCleared, Standby,    none, Interrupted<PrimaryStatus::standby>>,
      Row<Emergency,  EmergencyCleared, Initialize, none, Interrupted<PrimaryStatus::initialize>>,
      Row<Emergency,  EmergencyCleared, Failure,    none, Interrupted<PrimaryStatus::failure>>,
      Row<Initialize, ResetRequested,   Initialize>,
      Row<Ready,      ResetRequested,   Initialize>,
      Row<Standby,    ResetRequested,   Initialize>,
      Row<Failure,    ResetRequested,   Initialize>,
      Row<Ready,      FailureDetected,  Failure,   RememberFaultInterrupted>,
      Row<Standby,    FailureDetected,  Failure,   RememberFaultInterrupted>,
      Row<Failure,    FailureCleared,   Ready,      none, FaultInterrupted<PrimaryStatus::ready>>,
      Row<Failure,    FailureCleared,   Standby,    none, FaultInterrupted<PrimaryStatus::standby>>,
      Row<Emergency,  ResetRequested,   Initialize>,
      Row<Initialize, ShutdownRequested, Shutdown>,
      Row<Ready,      ShutdownRequested, Shutdown>,
      Row<Standby,    ShutdownRequested, Shutdown>,
      Row<Failure,    ShutdownRequested, Shutdown>,
      Row<Emergency,  ShutdownRequested, Shutdown>
  > {};
  // clang-format on

  template <class Fsm, class Event>
  void no_transition(const Event&, Fsm&, int) {
    refused = true;
  }

  PrimaryStatus current = PrimaryStatus::initialize;
  PrimaryStatus interrupted = PrimaryStatus::ready;
  PrimaryStatus fault_interrupted = PrimaryStatus::ready;
  bool refused = false;
};

using LifecycleMachine = boost::msm::back::state_machine<LifecycleDef>;

template <class Event>
bool apply(LifecycleMachine& sm) {
  sm.refused = false;
  sm.process_event(Event{});
  return !sm.refused;
}

}  // namespace

struct Lifecycle::Machine {
  LifecycleMachine sm;
};

Lifecycle::Lifecycle() : machine_(std::make_unique<Machine>()) { machine_->sm.start(); }
Lifecycle::~Lifecycle() = default;

bool Lifecycle::process(LifecycleEvent event) {
  auto& sm = machine_->sm;
  switch (event) {
    case LifecycleEvent::init_succeeded: return apply<InitSucceeded>(sm);
    case LifecycleEvent::init_failed: return apply<InitFailed>(sm);
    case LifecycleEvent::standby: return apply<StandbyRequested>(sm);
    case LifecycleEvent::resume: return apply<ResumeRequested>(sm);
    case LifecycleEvent::emergency_set: return apply<EmergencySet>(sm);
    case LifecycleEvent::emergency_cleared: return apply<EmergencyCleared>(sm);
    case LifecycleEvent::reset: return apply<ResetRequested>(sm);
    case LifecycleEvent::shutdown: return apply<ShutdownRequested>(sm);
    case LifecycleEvent::failure_detected: return apply<FailureDetected>(sm);
    case LifecycleEvent::failure_cleared: return apply<FailureCleared>(sm);
  }
  return false;
}

PrimaryStatus Lifecycle::state() const { return machine_->sm.current; }

std::string_view to_string(PrimaryStatus state) {
  switch (state) {
    case PrimaryStatus::initialize: return "Initialize";
    case PrimaryStatus::ready: return "Ready";
    case PrimaryStatus::standby: return "Standby";
    case PrimaryStatus::shutdown: return "Shutdown";
    case PrimaryStatus::failure: return "Failure";
    case PrimaryStatus::emergency: return "Emergency";
  }
  return "?";
}

std::string_view to_string(LifecycleEvent event) {
  switch (event) {
    case LifecycleEvent::init_succeeded: return "initialisation succeeded";
    case LifecycleEvent::init_failed: return "initialisation failed";
    case LifecycleEvent::standby: return "Standby";
    case LifecycleEvent::resume: return "Resume";
    case LifecycleEvent::emergency_set: return "Set Emergency";
    case LifecycleEvent::emergency_cleared: return "Clear Emergency";
    case LifecycleEvent::reset: return "Reset";
    case LifecycleEvent::shutdown: return "Shutdown";
    case LifecycleEvent::failure_detected: return "failure detected";
    case LifecycleEvent::failure_cleared: return "failure cleared";
  }
  return "?";
}

}  // namespace jaus::rt
