// A peer known from the start (configuration, command line): where it is and
// how to frame what goes to it. Plain values, no socket library.
#pragma once

#include "jaus/transport/framing.hpp"
#include "jaus/transport/ipv4.hpp"

namespace jaus::transport {

struct StaticPeer {
  Ipv4Endpoint endpoint;
  Framing framing = Framing::opc;
  bool operator==(const StaticPeer&) const = default;
};

}  // namespace jaus::transport
