// clearpath-sim's text interface: the lines an operator (or a test) types on
// standard input, and the JSON lines it prints on standard output. Pure
// functions: main.cpp does the reading and the printing.
#pragma once

#include <chrono>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <variant>

#include "jaus/clearpath/sim/sim_platform.hpp"

namespace jaus::clearpath::sim::console {

// `estop on|off`, `pause on|off`: set or release a hardware input.
struct Press {
  HardwareInput input;
  bool on;
};
// `deaf on|off`: a one-way line, now (SimServer::set_deaf): on, every frame
// received is ignored while data still goes; off, the platform hears again.
struct Deaf {
  bool on;
};
// `estop for MS`, `pause for MS` (1-10000): set now, released MS
// milliseconds later by the simulator's own timer, not by a later line: a
// stop of a known length however late standard input is read (a loaded
// machine may hand over two lines at once). Both edges answer as Press does.
struct PressFor {
  HardwareInput input;
  std::chrono::milliseconds duration;
};
// `status`: print the status line at once.
struct StatusNow {};
// A blank line: nothing to do, nothing to answer.
struct Blank {};
// Anything else: answered with error_line(), changes nothing.
struct Unknown {
  std::string line;
};
using Line = std::variant<Press, PressFor, Deaf, StatusNow, Blank, Unknown>;

Line parse_line(std::string_view text);

const char* input_name(HardwareInput input);

// {"input":"estop","on":true,"safety_flags":24}
std::string press_answer(const Press& press, std::uint16_t safety_flags);
// {"deaf":true}
std::string deaf_answer(const Deaf& deaf);
// {"error":"unknown input line 'xyz': expected estop on|off, pause on|off, deaf on|off"}
std::string error_line(const Unknown& unknown);
// {"status":{...}}: the vehicle's true state (what --status-every prints),
// and whether the platform is deaf (SimServer::deaf).
std::string status_line(const SimPlatform& platform, bool deaf = false);
// {"event":"...",...,"steady_ns":N}: N is the event's time on the steady
// clock, in nanoseconds since its epoch (what another process's steady_clock reads).
std::string event_line(const PlatformEvent& event);

}  // namespace jaus::clearpath::sim::console
