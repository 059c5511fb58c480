// What a user of a Clearpath platform (the bridge, a tool) needs of its
// connection, whatever carries it: ClearpathLink (serial, UDP or TCP through
// Boost.Asio) or sim::LoopbackClient (a simulated platform in the same process,
// under the runtime's virtual time). Both run ClientCore on the runtime's
// injected Clock and Scheduler; every call and callback is on that one thread.
#pragma once

#include <cstdint>
#include <string>

#include "jaus/clearpath/client_core.hpp"

namespace jaus::clearpath {

class Client {
 public:
  virtual ~Client() = default;

  // A command or request with ACK, retried; done(outcome) runs once. One in
  // flight per kind (type, and mount or joint), latest wins (an older one
  // finishes `superseded`), Set Safety System first, and queue_full beyond
  // ClientConfig::max_waiting_commands (see ClientCore::send).
  virtual void send(AnyMessage message, ClientCore::CommandCallback done = {}) = 0;
  // A subscription kept alive across reconnects.
  virtual void subscribe(AnyMessage request, ClientCore::CommandCallback done = {}) = 0;
  // Latest-wins stream resent to feed the platform's watchdog, for at most
  // ClientConfig::setpoint_max_age from now unless set again (see ClientCore).
  // It supersedes send() commands of its type: none of them reaches the
  // platform after it.
  virtual void set_setpoint(AnyMessage command) = 0;
  virtual void clear_setpoint(std::uint16_t type) = 0;
  // Safety: `stop` (a zero setpoint) written once, first, and the stream of
  // its type ends there.
  virtual void stop_setpoint(AnyMessage stop) = 0;
  // Every data message from the platform; after the link went down because
  // the platform no longer heard us, none until it acknowledges something
  // again (ClientCounters::data_withheld).
  virtual void on_data(ClientCore::DataCallback callback) = 0;
  // Every change of the connection's state.
  virtual void on_state(ClientCore::StateCallback callback) = 0;
  // Every piece of input passed over (a bad CRC, a frame that does not
  // decode), saying where and why (ClientCore::on_problem).
  virtual void on_problem(ClientCore::ProblemCallback callback) = 0;

  virtual ConnectionState state() const = 0;
  virtual const ClientCounters& counters() const = 0;
  // Why the link last went down, in words (ClientCore::down_reason).
  virtual const std::string& down_reason() const = 0;
};

}  // namespace jaus::clearpath
