// Exit codes shared by every jausctl command.
#pragma once

namespace jausctl {

inline constexpr int kExitOk = 0;
inline constexpr int kExitFailure = 1;  // the command ran but its target did not answer / failed
inline constexpr int kExitBadInput = 2; // bad arguments or malformed input
// `control --send`: the component was not Ready (Emergency, Standby, Failure, ...),
// so the command stopped for good and control was released. Not a failure of
// the tool: a stop someone else asked for, which only the operator may undo.
inline constexpr int kExitLeftReady = 3;

}  // namespace jausctl
