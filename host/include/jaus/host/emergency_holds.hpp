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
// are restored before any component starts and before the link receives,
// each bound to its dialect, ID and host, so a restarted jausd comes up in
// Emergency and only the same holder from the same host clears it. A file
// that cannot be read (or is stale) holds every latch, fail safe, until the
// local clear. A state directory that cannot be written refuses the start;
// a write that fails while running refuses every Clear Emergency until a
// write succeeds (NodeHost::persist_emergency_holds).
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
#include "jaus/jss/jss_id.hpp"

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

// Who a persisted hold belongs to (issue 42): the dialect it came in, its ID
// and the host (IPv4 address) it came from, so a restart binds the same
// holder again and nobody else inherits it.
//   ra:  `holder` is the RA sender's address (its node's route is bound to `host`);
//   jss: `holder` is the JSS client's alias (slot = holder.node) and
//        `jss_client` the client's JSS ID (its JSS route is bound to `host`).
// Without a host (`host` nullopt: a file of the previous version, or a holder
// whose host the node did not know) the holder is bound to nothing: it is
// restored as a hold only the local clear releases.
enum class HolderDialect { unknown, ra, jss };
struct PersistedHolder {
  Address holder;
  HolderDialect dialect = HolderDialect::unknown;
  std::optional<jss::JssId> jss_client;  // jss only
  std::optional<std::uint32_t> host;
  bool operator==(const PersistedHolder&) const = default;
};

// One latch's JAUS holds: "vehicle", or a component's address ("1.1.38.1").
struct PersistedHold {
  std::vector<PersistedHolder> holders;
  bool overflowed = false;  // holders beyond the recorded ones: held until the local clear
  bool operator==(const PersistedHold&) const = default;
};
using PersistedHolds = std::map<std::string, PersistedHold>;

// What the file holds, and the generation it was written at (0: none yet,
// or a file of the previous version, which has none).
struct PersistedState {
  PersistedHolds holds;
  std::uint64_t generation = 0;
  bool previous_version = false;  // written by a jausd before issue 42: no dialects, no hosts
};

// The generation's sidecar file beside the holds file (<file>.generation).
std::filesystem::path generation_file(const std::filesystem::path& holds_file);

// A missing file (and no generation written) is no holds. An unreadable or
// malformed one is an error naming the file and line; the caller holds every
// latch (fail safe). So is a stale one: every write records its generation
// in the sidecar first and then in the holds file, and the two must agree,
// so a holds file older than the last change written (lost, or put back
// from a copy) is never read as "no holds".
Expected<PersistedState> read_emergency_holds(const std::filesystem::path& file);
// Writes `generation` to the sidecar, then the holds with it; each written
// whole to a temporary file, synced and renamed over the old one, so a crash
// leaves the old holds or the new ones, never half (and a crash between the
// two a stale holds file: read as unreadable, fail safe).
Expected<void> write_emergency_holds(const std::filesystem::path& file, const PersistedHolds& holds,
                                     std::uint64_t generation);
// Whether `directory` takes files: created if missing, a probe file written,
// synced and removed. The error says why not (jausd refuses to start on it).
Expected<void> check_state_directory(const std::filesystem::path& directory);

std::string to_string(HolderDialect dialect);
std::string ipv4_to_string(std::uint32_t address);

}  // namespace jaus::host
