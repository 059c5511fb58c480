// The operator ID jausctl keeps for runs without --as
// ($XDG_STATE_HOME/jaus/operator-id, jaus/ocu/operator_identity.hpp), written
// by a test before jausctl runs. jausctl would draw 254.N.40.1 with N in
// 1..254; tests name IDs with --as (and DefaultJausd::jausctl_own_id names
// 254.<bind octet>), all with N below 200. A drawn N is one of those in about
// one test in 254, and the node then takes the two processes for one ID on
// two hosts and drops one (DriveAVehicle and BroadcastStop each failed so in a
// clean CI run). So the kept ID is what jausctl would draw, with N in 200..253.
#pragma once

#include <filesystem>
#include <fstream>

namespace jaus::test {

// Writes 254.(200 + seed % 54).40.1 as the ID kept under `state_home`.
inline void keep_operator_id_outside_named_ones(const std::filesystem::path& state_home, int seed) {
  std::filesystem::create_directories(state_home / "jaus");
  std::ofstream(state_home / "jaus" / "operator-id") << "254." << 200 + seed % 54 << ".40.1\n";
}

}  // namespace jaus::test
