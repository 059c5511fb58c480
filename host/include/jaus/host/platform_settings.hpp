// What the vehicle components drive and read: the components' own simulated
// hardware (no protocol), or a Clearpath platform through the bridge, either
// simulated in this process (the bytes still cross the Clearpath protocol) or
// real, on a serial port, UDP or TCP. make_platform (platform.hpp) makes the
// platform a configuration names.
#pragma once

#include "jaus/bridge/clearpath_arm.hpp"
#include "jaus/bridge/clearpath_cameras.hpp"
#include "jaus/bridge/clearpath_vehicle.hpp"
#include "jaus/clearpath/client_core.hpp"
#include "jaus/clearpath/link.hpp"
#include "jaus/clearpath/sim/sim_platform.hpp"

namespace jaus::host {

struct PlatformSettings {
  enum class Kind {
    model,          // the components' simulated vehicle, cameras and arm, called directly
    clearpath_sim,  // a simulated Clearpath platform in this process, through the bridge
    clearpath,      // a Clearpath platform at `endpoint`, through the bridge
  } kind = Kind::model;
  clearpath::PlatformEndpoint endpoint;  // clearpath
  clearpath::sim::PlatformConfig sim;    // clearpath_sim
  clearpath::ClientConfig client;        // retries, silence, setpoint period and maximum age
  bridge::ClearpathVehicleConfig vehicle;  // the mobility components' mapping
  // The visual sensor's camera mounts on the platform (images still come from
  // the simulated cameras); cameras not listed keep their simulated mount.
  bridge::ClearpathCamerasConfig cameras;
  // The manipulator's joints on the platform; none: the arm stays simulated.
  bridge::ClearpathArmConfig arm;
};

}  // namespace jaus::host
