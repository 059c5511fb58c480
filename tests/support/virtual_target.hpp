// The target node of target_node.hpp (node manager 1.1.1.1, communicator
// 1.1.35.1, pose sensor 1.1.38.1, on request a primitive driver 1.1.33.1;
// on another subsystem with TargetOptions::subsystem): the same node host,
// attached to a link of a jaus::testing memory network under virtual time.
// No socket, no real clock, no static peers (the network routes by
// address).
#pragma once

#include <memory>
#include <stdexcept>

#include "jaus/base/virtual_time.hpp"
#include "jaus/host/node_host.hpp"
#include "jaus/testing/memory_link.hpp"
#include "target_node.hpp"

namespace jausctl::test {

// The link and the host attached to it, made before the components the
// tests reach in it.
struct AttachedTargetHost {
  jaus::testing::MemoryLink& link;
  std::unique_ptr<jaus::host::NodeHost> host;
};

class VirtualTarget : private AttachedTargetHost, public TargetComponents {
 public:
  VirtualTarget(jaus::rt::VirtualTime& time, jaus::testing::MemoryNetwork& network, const TargetOptions& options)
      : AttachedTargetHost{network.attach(options.subsystem, 1), nullptr},
        TargetComponents(attach_host(time, options), options) {}
  ~VirtualTarget() {
    host->stop("test over");  // while its link still carries the last messages
    link.on_receive({});
    link.set_connected(false);  // a target started in its place gets a link of its own
  }
  VirtualTarget(const VirtualTarget&) = delete;
  VirtualTarget& operator=(const VirtualTarget&) = delete;

  // The network goes quiet (cable pulled, process frozen): nothing in or out.
  void go_silent() { link.set_connected(false); }
  jaus::node::Node& node() { return host->node(); }

 private:
  jaus::host::NodeHost& attach_host(jaus::rt::VirtualTime& time, const TargetOptions& options) {
    if (!options.peers.empty())
      throw std::invalid_argument("a virtual target has no static peers: the network routes by address");
    auto attached = jaus::host::NodeHost::attach(target_config(options), link, time, time);
    if (!attached) throw std::runtime_error(attached.error().message());
    host = std::move(*attached);
    link.deliver_to(host->node());
    return *host;
  }
};

}  // namespace jausctl::test
