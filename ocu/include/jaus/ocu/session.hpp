// One OCU on the network: a node host (UDP link, node and a node manager, so
// the other side hears this OCU's heartbeats and keeps its service
// connections and control alive) and the OCU component, all on one
// io_context. Commands are thin: they send, then run the io_context until
// what they wait for arrives or their time is up.
//
// Single-threaded like the runtime: everything here runs on the thread that
// calls run_until(). Tests pass their own io_context so that a target node
// and the OCU share it.
#pragma once

#include <utility>  // Boost 1.74's Asio headers need it first

#include <boost/asio/io_context.hpp>
#include <boost/asio/signal_set.hpp>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "jaus/node/node.hpp"
#include "jaus/ocu/ocu_component.hpp"
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
  jaus::transport::Framing framing = jaus::transport::Framing::opc;
  jaus::wire::Dialect dialect = jaus::wire::Dialect::ra;
  std::uint8_t authority = 0;  // the OCU component's own authority
  jaus::rt::LogFn log;
};

// A message addressed to the OCU component.
struct Received {
  jaus::Header header;
  std::vector<std::uint8_t> payload;
};

class OcuSession {
 public:
  using Listener = std::function<void(const Received&)>;
  using Watcher = std::function<void(const jaus::Header&)>;
  using ListenerId = std::uint64_t;

  // Binds the socket and starts the node. `io` null: the session runs its own.
  // The error (io, invalid_argument) says it in one line, e.g. "0.0.0.0:3794
  // is already in use".
  static jaus::Expected<std::unique_ptr<OcuSession>> open(SessionOptions options,
                                                         boost::asio::io_context* io = nullptr);
  // Shuts the node down in order: subscriptions still open are terminated.
  ~OcuSession();
  OcuSession(const OcuSession&) = delete;
  OcuSession& operator=(const OcuSession&) = delete;

  const jaus::Address& self() const { return options_.self; }
  const SessionOptions& options() const { return options_; }
  OcuComponent& component() { return *component_; }
  jaus::node::Node& node();
  jaus::transport::UdpLink& link();
  jaus::rt::Clock& clock();
  // What runs it: another session opened on it runs whenever this one does.
  boost::asio::io_context& io_context() { return io_; }

  // Sends from the OCU component; the datagram has left when this returns.
  template <class M>
  void send(const jaus::Address& to, const M& message, std::uint8_t priority = jaus::priority::kDefault) {
    component_->send_message(to, message, priority);
  }
  // A message known only at run time: source set to the OCU, data size to the payload.
  void send_raw(jaus::Header header, std::span<const std::uint8_t> payload);

  // Messages addressed to the OCU component: reports, confirmations, rejects,
  // and also those the runtime answers itself (a controlled component's
  // liveness queries), so callers see everything sent to them.
  ListenerId listen(Listener listener);
  // Every JAUS message heard, whoever it is for (heartbeats go to broadcast
  // addresses the OCU's node does not match).
  ListenerId watch(Watcher watcher);
  void unlisten(ListenerId id);

  // Runs the io_context until `done()`, `limit` has passed or the session is
  // interrupted. True when `done()`.
  bool run_until(const std::function<bool()>& done, jaus::rt::Duration limit);
  void run_for(jaus::rt::Duration limit) { run_until([] { return false; }, limit); }

  // SIGINT and SIGTERM interrupt the session (commands then clean up: release
  // control, terminate service connections).
  void stop_on_signals();
  void interrupt() { interrupted_ = true; }
  bool interrupted() const { return interrupted_; }

  // The first message from `from` (255s match any ID) with one of `codes`
  // (any code when empty). Errors: timeout ("no reply from 1.1.33.1 within
  // 1 s") or interrupted.
  jaus::Expected<Received> await_reply(const jaus::Address& from, std::vector<std::uint16_t> codes,
                                       jaus::rt::Duration timeout);
  template <class M>
  jaus::Expected<Received> request(const jaus::Address& to, const M& message,
                                                std::vector<std::uint16_t> reply_codes, jaus::rt::Duration timeout) {
    send(to, message);
    return await_reply(to, std::move(reply_codes), timeout);
  }

 private:
  OcuSession(SessionOptions options, boost::asio::io_context* io);
  void observe(const jaus::PacketView& packet);
  void arm_signals();
  void deliver(const Received& message);

  SessionOptions options_;
  std::unique_ptr<boost::asio::io_context> owned_io_;
  boost::asio::io_context& io_;
  std::unique_ptr<jaus::host::NodeHost> host_;
  OcuComponent* component_ = nullptr;
  std::optional<boost::asio::signal_set> signals_;
  bool interrupted_ = false;
  ListenerId last_id_ = 0;
  std::map<ListenerId, Listener> listeners_;
  std::map<ListenerId, Watcher> watchers_;
};

// timeout: "no reply from 1.1.33.1 within 1 s"
jaus::Error no_reply_error(const jaus::Address& from, jaus::rt::Duration timeout);

}  // namespace jaus::ocu
