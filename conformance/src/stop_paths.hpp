// The ways a controlled component is stopped (Standby, Set Emergency, Reset,
// the release of control, a takeover by a higher authority) and the way back
// from each (Resume, Clear Emergency, the end of re-initialisation, control
// granted again), for the cases that check that every stop stops the
// actuators and that nothing resumes afterwards. Private to the conformance
// library.
#pragma once

#include <optional>
#include <string>

#include "jaus/base/expected.hpp"
#include "state_support.hpp"

namespace jaus::conform::detail {

enum class StopPath { standby, emergency, reset, release, takeover };
inline constexpr StopPath kStopPaths[] = {StopPath::standby, StopPath::emergency, StopPath::reset, StopPath::release,
                                          StopPath::takeover};

std::string path_text(StopPath path);
std::string way_back_text(StopPath path);

// The component's state once a Reset's re-initialisation is over (Initialize
// for as long as it lasts, up to a limit).
Expected<msg::PrimaryStatus> state_after_initialising(CaseContext& c);

// The runner in control of the component for one stop path, the stop, and
// the way back. Control is taken at the highest authority, or for a takeover
// just above the component's own, so that the second OCU can take over above
// it. Whatever happens, the runner ends in control when the way back
// succeeded, and every control it or the second OCU took is released when
// this ends.
class StopAlong {
 public:
  StopAlong(CaseContext& c, StopPath path);
  StopAlong(const StopAlong&) = delete;
  StopAlong& operator=(const StopAlong&) = delete;

  // Empty when the runner controls the component; else why the path cannot
  // be judged (control not granted, no authority to take over with).
  const std::string& why_not() const { return why_not_; }
  // Stops the component along the path. An error says why the stop could
  // not be made (the path then cannot be judged).
  Expected<void> stop();
  // Takes the way back, with no new command. An error says why it could
  // not be taken.
  Expected<void> come_back();

 private:
  CaseContext& c_;
  StopPath path_;
  std::uint8_t authority_ = 255;
  std::optional<ControlHeld> control_;
  std::optional<ControlHeld> taken_over_by_;
  std::string why_not_;
};

}  // namespace jaus::conform::detail
