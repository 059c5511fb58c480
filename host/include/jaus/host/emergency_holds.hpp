// Emergency holds that survive a restart of jausd, and how far one Set
// Emergency reaches (docs/safety.md).
//
// Scope: with `vehicle` (the default) the vehicle's moving components (the
// primitive driver, the primitive manipulator, the visual sensor's mounts)
// share one latch: a Set Emergency to any of them holds all of them, and each
// holder clears its own hold from any of them (Part 3's per-holder rule).
// With `component` each component has its own latch, as Part 3 describes.
//
// Persistence: every latch of a component with hardware is the host's, and
// each change of its JAUS holders is written to <state directory>/
// emergency-holds as soon as the change has taken effect (the stop never
// waits for the disk; NodeHost::schedule_persisting); at start the holders
// are restored before any component starts, so a restarted jausd comes up in
// Emergency. A file that cannot be read holds every latch, fail safe, until
// the local clear.
//
// The local clear, for holders gone for good (an OCU that will never send
// its Clear Emergency, senders beyond the recorded ones): SIGUSR1 to jausd
// clears every JAUS holder, logged with who held what. The platform's own
// stops are not touched: only the platform clears those.
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "jaus/base/expected.hpp"
#include "jaus/core/address.hpp"

namespace jaus::host {

enum class EmergencyScope { vehicle, component };

struct EmergencySettings {
  EmergencyScope scope = EmergencyScope::vehicle;
  // Where holds persist; empty: $STATE_DIRECTORY (systemd's StateDirectory=),
  // and without it holds are not persisted (the host logs a warning).
  std::string state_directory;
};

// The holds file, or nullopt when holds are not persisted.
std::optional<std::filesystem::path> emergency_holds_file(const EmergencySettings& settings);

// One latch's JAUS holds: "vehicle", or a component's address ("1.1.38.1").
struct PersistedHold {
  std::vector<Address> holders;
  bool overflowed = false;  // holders beyond the recorded ones: held until the local clear
  bool operator==(const PersistedHold&) const = default;
};
using PersistedHolds = std::map<std::string, PersistedHold>;

// A missing file is no holds. An unreadable or malformed one is an error
// naming the file and line; the caller holds every latch (fail safe).
Expected<PersistedHolds> read_emergency_holds(const std::filesystem::path& file);
// Written whole to a temporary file, synced and renamed over `file`, so a
// crash leaves the old holds or the new ones, never half.
Expected<void> write_emergency_holds(const std::filesystem::path& file, const PersistedHolds& holds);

}  // namespace jaus::host
