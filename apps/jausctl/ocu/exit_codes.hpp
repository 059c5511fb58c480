// Exit codes shared by every jausctl command.
#pragma once

namespace jausctl {

inline constexpr int kExitOk = 0;
inline constexpr int kExitFailure = 1;  // the command ran but its target did not answer / failed
inline constexpr int kExitBadInput = 2; // bad arguments or malformed input

}  // namespace jausctl
