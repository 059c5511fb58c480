// Fuzz target: any datagram into a node, as the UDP link hands it over: the
// framing is checked, then the node (a node manager and a communicator, under
// virtual time) receives it and its components decode and act. The bytes are
// also tried behind an OPC prefix, so raw JAUS vectors are useful seeds. The
// node lives across inputs, so sequences (large data sets, control, service
// connections) are explored too; its tables are bounded, so memory is as well.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "jaus/node/node.hpp"
#include "jaus/components/communicator.hpp"
#include "jaus/components/node_manager.hpp"
#include "jaus/base/virtual_time.hpp"
#include "jaus/transport/framing.hpp"

namespace {

using namespace jaus;

class NullLink : public node::Link {
 public:
  void transmit(const Header& header, std::span<const std::uint8_t> packet) override {
    // What the node sends must itself be a valid message, with the header it says.
    const auto decoded = decode_packet(packet);
    if (!decoded || !(decoded->header == header)) std::abort();
  }
};

struct FuzzNode {
  FuzzNode() : node(node::NodeConfig{}, time, time, link) {
    rt::ComponentConfig manager;
    manager.address = Address{1, 1, 1, 1};
    node.add(std::make_unique<components::NodeManager>(manager, node.environment(), node,
                                                       components::NodeManagerConfig{}));
    rt::ComponentConfig communicator;
    communicator.address = Address{1, 1, 35, 1};
    node.add(std::make_unique<components::Communicator>(communicator, node.environment()));
  }
  void datagram(std::span<const std::uint8_t> bytes) {
    // As the UDP link does: unframe (header decoded and checked once), then the node.
    if (auto unframed = transport::unframe(bytes)) node.receive(unframed->packet);
    time.advance(std::chrono::milliseconds(3));
  }
  rt::VirtualTime time;
  NullLink link;
  node::Node node;
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static FuzzNode fuzz;
  const std::span<const std::uint8_t> bytes(data, size);
  fuzz.datagram(bytes);
  std::vector<std::uint8_t> opc(transport::kOpcPrefix.begin(), transport::kOpcPrefix.end());
  opc.insert(opc.end(), bytes.begin(), bytes.end());
  fuzz.datagram(opc);
  return 0;
}
