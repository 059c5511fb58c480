// One running node: the UDP transport, the node and its components, built
// from a checked configuration, on the caller's io_context.
#pragma once

#include <utility>  // Boost 1.74's Asio headers need it first

#include <boost/asio/io_context.hpp>
#include <memory>
#include <string>

#include "jaus/node/node.hpp"
#include "jaus/transport/asio_runtime.hpp"
#include "jaus/transport/udp_link.hpp"
#include "jausd_config.hpp"

namespace jausd {

class Daemon {
 public:
  // Opens the transport and hosts every configured component. A failure is
  // one line, e.g. "127.0.0.1:3794 is already in use".
  static jaus::Expected<std::unique_ptr<Daemon>, std::string> start(const JausdConfig& config,
                                                                    boost::asio::io_context& io,
                                                                    jaus::rt::LogFn log);
  ~Daemon();

  // Orderly stop. Safety: every component goes to Shutdown first, which
  // commands its platform to stop (Component::enforce_stop), drops control
  // and ends its service connections, with those messages sent; then the
  // transport closes. Idempotent.
  void stop(const std::string& why);

  const jaus::node::Node& node() const { return *node_; }
  const jaus::transport::UdpLink& link() const { return *link_; }

 private:
  Daemon(boost::asio::io_context& io, jaus::rt::LogFn log) : runtime_(io), log_(std::move(log)) {}

  jaus::transport::AsioRuntime runtime_;
  jaus::rt::LogFn log_;
  std::unique_ptr<jaus::transport::UdpLink> link_;
  std::unique_ptr<jaus::node::Node> node_;
  bool stopped_ = false;
};

// The transport options a configuration asks for.
jaus::transport::UdpLinkOptions link_options(const JausdConfig& config);

}  // namespace jausd
