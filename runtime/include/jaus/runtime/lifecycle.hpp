// The component lifecycle of RA 3.x (Part 3, Report Component Status):
//
//            init ok              standby
//   Initialize ------> Ready <-------------> Standby
//        |   init fail   ^      resume         |
//        v               |                     |
//     Failure            | clear (all holders) |
//                        |                     |
//   any state but Shutdown --- set emergency --> Emergency
//   (Emergency returns, when every condition is cleared, to the state it
//    interrupted: Ready, Standby, Initialize or Failure)
//   any state but Shutdown --- reset --> Initialize
//   any state but Shutdown --- shutdown --> Shutdown (final)
//   Ready or Standby --- failure detected --> Failure --- failure cleared --> the state it interrupted
//   (a component's own fault, a stale sensor or a lost platform link, and its
//    recovery: a Standby stays a Standby through a fault; a failed
//    initialisation leaves Failure only by Reset)
//
// Written with Boost.MSM; the machine itself lives in lifecycle.cpp so that
// its compile cost is paid once. A refused event (Standby while in Emergency,
// Resume from Ready, ...) changes nothing and is reported as refused.
#pragma once

#include <cstdint>
#include <memory>
#include <string_view>

#include "jaus/messages/primary_status.hpp"

namespace jaus::rt {

using msg::PrimaryStatus;

enum class LifecycleEvent : std::uint8_t {
  init_succeeded,
  init_failed,
  standby,
  resume,
  emergency_set,
  emergency_cleared,  // every emergency condition has been cleared
  reset,
  shutdown,
  failure_detected,  // the component found a fault of its own (its data source went stale)
  failure_cleared,   // ...and the fault is gone
};

std::string_view to_string(PrimaryStatus state);
std::string_view to_string(LifecycleEvent event);

class Lifecycle {
 public:
  Lifecycle();
  ~Lifecycle();
  Lifecycle(const Lifecycle&) = delete;
  Lifecycle& operator=(const Lifecycle&) = delete;

  // Applies the event; false (and no change) when the current state refuses it.
  bool process(LifecycleEvent event);
  PrimaryStatus state() const;

 private:
  struct Machine;
  std::unique_ptr<Machine> machine_;
};

}  // namespace jaus::rt
