// The local vector driver (component 44): Set Local Vector 0x0408 (speed and
// heading, both always present) and Query/Report Local Vector 0x2408/0x4408.
// The heading is measured from the local frame's x axis, which points north
// (local_frame.hpp), in the same sense as the global heading, so it is
// followed exactly as the global vector driver's (vector_driver.hpp).
#pragma once

#include "jaus/components/vector_driver.hpp"
#include "jaus/messages/platform_messages.hpp"

namespace jaus::components {

class LocalVectorDriver final : public VectorDriver {
 public:
  LocalVectorDriver(rt::ComponentConfig config, rt::Environment env, PoseSource& pose, VectorDriverOptions options);

  // The commanded vector. The message has no presence vector: before any
  // Set (or after a Reset) it gives speed 0 and the vehicle's heading now
  // (what speed 0 holds), 0 without a pose.
  msg::ReportLocalVector report();
};

}  // namespace jaus::components
