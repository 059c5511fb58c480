// One OCU on the network: a node (with a node manager, so the other side
// hears this OCU's heartbeats and keeps its service connections and control
// alive) and the OCU component. Commands are thin: they send, then wait
// (run_until) until what they wait for arrives or their time is up.
//
// Two ways to open one: open() on UDP, a node host on an io_context (jausctl,
// jaus-conform); attach() on an injected link, clock and scheduler and a way
// to wait (tests on jaus::testing's memory link and virtual time, where
// waiting advances the virtual clock instead of blocking).
//
// Single-threaded like the runtime: everything here runs on the thread that
// calls run_until(), but request_stop(). Signals are the application's: it
// handles them and calls request_stop(). Listening, waiting for replies, the
// run loop and the stop request are SessionCore's (session_core.hpp), as
// the JSS session's.
#pragma once

#include <utility>  // Boost 1.74's Asio headers need it first

#include <boost/asio/io_context.hpp>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "jaus/node/node.hpp"
#include "jaus/ocu/must_arrive_settings.hpp"
#include "jaus/ocu/ocu_component.hpp"
#include "jaus/ocu/session_core.hpp"
#include "jaus/transport/framing.hpp"
#include "jaus/transport/ipv4.hpp"

// The node host is only held here: its header (every component kind, the
// bridge, the Clearpath link) stays out of every OCU translation unit.
namespace jaus::host {
class NodeHost;
}
namespace jaus::transport {
class UdpLink;
}

namespace jaus::ocu {

// 254 is the last subsystem ID: vehicles count up from 1, so an OCU there
// does not collide with them; 40 is the System Commander's component ID, the
// RA's name for an operator's component. Component 1 of the node is the OCU's
// node manager.
inline constexpr jaus::Address kDefaultOcuAddress{254, 1, 40, 1};
inline constexpr std::uint16_t kOcuSubsystemType = 20001;  // 20001+: OCU

struct SessionOptions {
  jaus::Address self = kDefaultOcuAddress;
  // The nodes to talk to: static peers, so they are reached before they are
  // heard. Messages to a node not heard from yet, and broadcasts, go to each.
  std::vector<jaus::transport::Ipv4Endpoint> to{{0x7F000001, jaus::transport::kJausPort}};
  // Any address, any free port. Peers that answer to IP:3794 instead of the
  // sender's port need the OCU bound to its own address and port 3794.
  jaus::transport::Ipv4Endpoint bind{0, 0};
  // A multicast group (e.g. 224.1.0.1:3794, as jausd's transport.multicast):
  // broadcasts (discovery) and messages to nodes not heard from yet go there
  // too, and the session joins it to hear the nodes' heartbeats. With it, `to`
  // may be empty. Best effort like jausd's: a host without a multicast route
  // logs a warning and talks to `to` only.
  std::optional<jaus::transport::Ipv4Endpoint> multicast;
  jaus::transport::Framing framing = jaus::transport::Framing::opc;
  jaus::wire::Dialect dialect = jaus::wire::Dialect::ra;
  std::uint8_t authority = 0;  // the OCU component's own authority
  // How long and how often a command that must arrive is sent again
  // (must_arrive.hpp), and the round-trip bounds of its node's pace.
  MustArriveSettings must_arrive{};
  jaus::rt::LogFn log;
};

// What an attached session runs on instead of UDP and an io_context.
struct SessionEnvironment {
  jaus::rt::Clock* clock = nullptr;
  jaus::rt::Scheduler* scheduler = nullptr;
  // Where the session's node transmits.
  jaus::node::Link* link = nullptr;
  // Hands the link what takes each packet it receives (16-byte header and
  // payload); called once by attach(), and again with an empty function when
  // the session goes.
  std::function<void(std::function<void(std::span<const std::uint8_t>)>)> connect;
  // Lets time pass up to `until` at most and returns (after one step of
  // virtual time, one handler of an event loop): run_until looks at its
  // condition between calls. jaus::testing::stepper(time) for VirtualTime.
  std::function<void(jaus::rt::TimePoint until)> wait;
};

// A message addressed to the OCU component.
struct Received {
  jaus::Header header;
  std::vector<std::uint8_t> payload;
  const jaus::Address& source() const { return header.source; }
  std::uint16_t code() const { return header.command_code; }
};

class OcuSession : public SessionCore<Received> {
 public:
  using Watcher = std::function<void(const jaus::Header&)>;

  // Binds the socket (and joins the multicast group) and starts the node.
  // `io` null: the session runs its own.
  // The error (io, invalid_argument) says it in one line, e.g. "0.0.0.0:3794
  // is already in use".
  static jaus::Expected<std::unique_ptr<OcuSession>> open(SessionOptions options,
                                                         boost::asio::io_context* io = nullptr);
  // The same node on an injected link, clock and scheduler (options.to, bind,
  // framing and multicast are the link's business and not used). Errors: an invalid
  // address, an environment with something missing (invalid_argument).
  static jaus::Expected<std::unique_ptr<OcuSession>> attach(SessionOptions options, SessionEnvironment environment);
  // Shuts the node down in order: subscriptions still open are terminated.
  ~OcuSession();

  const jaus::Address& self() const { return options_.self; }
  const SessionOptions& options() const { return options_; }
  OcuComponent& component() { return *component_; }
  jaus::node::Node& node() { return *node_; }
  // A session opened on UDP: its link; null for an attached session.
  jaus::transport::UdpLink* udp_link();

  // Sends from the OCU component; the datagram has left when this returns.
  template <class M>
  void send(const jaus::Address& to, const M& message, std::uint8_t priority = jaus::priority::kDefault) {
    component_->send_message(to, message, priority);
  }
  // A message known only at run time: source set to the OCU, data size to the payload.
  void send_raw(jaus::Header header, std::span<const std::uint8_t> payload);

  // (SessionCore's listen() hears the messages addressed to the OCU
  // component: reports, confirmations, rejects, and also those the runtime
  // answers itself, a controlled component's liveness queries, so callers see
  // everything sent to them; await_reply() the first from an address, 255s
  // matching any ID.)

  // Every JAUS message heard, whoever it is for (heartbeats go to broadcast
  // addresses the OCU's node does not match).
  ListenerId watch(Watcher watcher);
  // A listener's or a watcher's.
  void unlisten(ListenerId id) {
    SessionCore::unlisten(id);
    watchers_.erase(id);
  }

  // Sends `message` and waits for the first reply from `to` with one of `reply_codes`.
  template <class M>
  jaus::Expected<Received> request(const jaus::Address& to, const M& message,
                                                std::vector<std::uint16_t> reply_codes, jaus::rt::Duration timeout) {
    send(to, message);
    return await_reply(to, std::move(reply_codes), timeout);
  }

 private:
  explicit OcuSession(SessionOptions options);
  static jaus::Expected<void> check_address(const jaus::Address& self);
  void add_ocu_component();
  void receive_packet(std::span<const std::uint8_t> bytes);  // an attached session's link
  void observe(const jaus::PacketView& packet);

  SessionOptions options_;
  // On UDP: the io_context when the caller gave none, and the host.
  std::unique_ptr<boost::asio::io_context> owned_io_;
  std::unique_ptr<jaus::host::NodeHost> host_;
  // Attached: the environment and the node (declared after it: gone first).
  SessionEnvironment environment_;
  std::unique_ptr<jaus::node::Node> own_node_;
  jaus::node::Node* node_ = nullptr;
  OcuComponent* component_ = nullptr;
  std::map<ListenerId, Watcher> watchers_;
};

}  // namespace jaus::ocu
