// The suite's vehicles: veh1 (subsystem 1, node 1) driving a clearpath-sim
// on its own loopback over UDP; veh2a and veh2b, nodes 1 and 2 of subsystem
// 2 (two computers of one vehicle: the drive on one, camera and arm on the
// other). How they find each other is the test's choice.
#pragma once

#include <string>
#include <vector>

#include "lab_jausd.hpp"

namespace jaus::test::network {

// How the vehicles find each other; `alone`: neither (a test with veh1 only).
enum class Finding { multicast_and_peers, multicast_only, peers_only, alone };

inline constexpr const char* kSimulatorAddress = "127.0.0.1";  // veh1's own loopback

// The `transport:` keys of a vehicle on `self`'s host.
inline std::string transport_for(Finding finding, const LabHost& self, const std::string& more = "") {
  std::string keys;
  // jausd joins 224.1.0.1:3794 by default: without multicast is said (each lab is its own network).
  keys = std::string("multicast: ") +
         ((finding == Finding::multicast_and_peers || finding == Finding::multicast_only) ? kMulticastGroup : "null");
  if (finding == Finding::multicast_and_peers || finding == Finding::peers_only) {
    std::string peers;
    for (const auto& host : {kVeh1, kVeh2a, kVeh2b})
      if (std::string(host.name) != self.name) peers += (peers.empty() ? "" : ", ") + std::string(host.address);
    keys += (keys.empty() ? "" : ", ") + std::string("peers: [") + peers + "]";
  }
  if (!more.empty()) keys += (keys.empty() ? "" : ", ") + more;
  return keys;
}

inline LabNodeSpec veh1_spec(Finding finding, const std::string& more_transport = "") {
  return {kVeh1,
          1,
          1,
          {{"node_manager", 1},
           {"communicator", 35},
           {"primitive_driver", 33},
           {"global_pose_sensor", 38},
           {"velocity_state_sensor", 42},
           {"global_vector_driver", 34, "authority: 1"}},
          transport_for(finding, kVeh1, more_transport),
          std::string("platform: {udp: ") + kSimulatorAddress + ":7300}\n"};
}

inline LabNodeSpec veh2a_spec(Finding finding, const std::string& more_transport = "") {
  return {kVeh2a,
          2,
          1,
          {{"node_manager", 1}, {"communicator", 35}, {"primitive_driver", 33}, {"global_pose_sensor", 38}},
          transport_for(finding, kVeh2a, more_transport),
          ""};
}

inline LabNodeSpec veh2b_spec(Finding finding) {
  return {kVeh2b, 2, 2, {{"node_manager", 1}, {"visual_sensor", 37}, {"primitive_manipulator", 49}},
          transport_for(finding, kVeh2b), ""};
}

}  // namespace jaus::test::network
