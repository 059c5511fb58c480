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
  void transmit(std::span<const std::uint8_t> packet) override {
    // What the node sends must itself be a valid message.
    if (!decode_packet(packet)) std::abort();
  }
};

struct FuzzNode {
  FuzzNode() : node(node::NodeConfig{}, time, time, link) {
    rt::ComponentConfig manager;
    manager.address = Address{1, 1, 1, 1};
    node.set_node_manager(static_cast<rt::NodeManager*>(
        &node.add(std::make_unique<rt::NodeManager>(manager, node.environment(), node, rt::NodeManagerConfig{}))));
    rt::ComponentConfig communicator;
    communicator.address = Address{1, 1, 35, 1};
    node.add(std::make_unique<rt::Communicator>(communicator, node.environment()));
  }
  void datagram(std::span<const std::uint8_t> bytes) {
    if (auto unframed = transport::unframe(bytes)) {
      const std::size_t prefix = unframed->framing == transport::Framing::opc ? transport::kOpcPrefix.size()
                                                                              : transport::kJudpPrefixSize;
      node.receive(bytes.subspan(prefix));
    }
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
