// jausd's configuration file, as the node host takes it.
#pragma once

#include "jaus/host/node_host.hpp"
#include "jausd_config.hpp"

namespace jausd {

jaus::host::HostConfig host_config(const JausdConfig& config);

}  // namespace jausd
