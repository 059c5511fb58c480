// One step of a model-based sequence: what one operator, the platform, the
// clock or the process does. A sequence is a list of them; it prints as C++
// (to_cpp) so that a shrunk counterexample can be pasted into a regression
// test as it is.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace jaus::model {

// The operators. A and B: RA OCUs on the primitive driver; J: a JSS client
// through the face (an RA alias on the node); C: an RA OCU that drives through
// the local vector driver (and may also stop the vehicle).
enum class Party : std::uint8_t { a, b, j, c };
inline constexpr int kParties = 4;
const char* name(Party p);

// Where a Set/Clear Emergency or a Standby goes.
enum class Target : std::uint8_t { primitive_driver, vector_driver };

enum class Kind : std::uint8_t {
  request_control,   // who, value = authority (to the primitive driver)
  release_control,   // who
  effort,            // who, value = percent (one Set Wrench Effort)
  stick,             // who, value = percent, 0 = let go (streamed every 100 ms while time passes)
  set_emergency,     // who, target
  clear_emergency,   // who, target
  standby,           // who (to the primitive driver)
  resume,            // who
  set_authority,     // who, value = the primitive driver's own authority
  shutdown,          // who
  reset,             // who (to the primitive driver)
  link,              // who, value = 1 up, 0 down (its messages are lost both ways)
  estop,             // value = 1 pressed, 0 released, 2 pressed for 20 ms (the platform's hardware input)
  pause,             // value = 1 on, 0 off, 2 on for 20 ms
  advance,           // value = milliseconds of time passing (streams keep going)
  restart,           // jausd stops and starts again (holds from its state directory)
  local_clear,       // jausd's SIGUSR1: every Set Emergency holder cleared
  take_vector,       // C requests control of the vector driver (authority 5)
  release_vector,    // C releases the vector driver
  keep_vector,       // C keeps talking to the vector driver while time passes (value 1) or not (0)
  drive_vector,      // C sends Set Local Vector, value = speed in cm/s
};

struct Action {
  Kind kind = Kind::advance;
  Party who = Party::a;
  int value = 0;
  Target target = Target::primitive_driver;
  bool operator==(const Action&) const = default;
};

using Sequence = std::vector<Action>;

std::string describe(const Action& a);
// `{Kind::effort, Party::a, 60, Target::primitive_driver},` per line.
std::string to_cpp(const Sequence& s);

}  // namespace jaus::model
