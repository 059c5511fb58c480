// A fixture, never compiled: the runtime reaching up into the transport,
// which the layering check must refuse (tests/layering/CMakeLists.txt).
#include "jaus/node/node.hpp"
#include "jaus/transport/udp_link.hpp"
