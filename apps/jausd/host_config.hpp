// jausd's configuration file, as the node host takes it.
#pragma once

#include "jaus/host/node_host.hpp"
#include "jausd_config.hpp"

namespace jausd {

jaus::host::HostConfig host_config(const JausdConfig& config);

// What carries the vehicle, as the host takes it: the kind `platform:` names
// with its options, and the `clearpath:` mapping (with the vehicle's figures,
// the cameras and the arm it maps) as the section a Clearpath platform reads
// (jaus::host::ClearpathSettings; a kind that reads none ignores it).
jaus::host::PlatformSettings platform_settings(const JausdConfig& config);

}  // namespace jausd
