// The node's metrics (metrics.hpp) over HTTP, for Prometheus and curl
// (jausd's `metrics:` section, docs/running.md "Metrics"): GET /metrics is
// answered with the text exposition format, rendered on the io_context's
// thread (the node's own, so nothing is read while it changes); anything
// else is 404, a method other than GET or HEAD 405. One request per
// connection, at most max_connections at once (more are closed at once),
// each given 5 s.
//
// Security as jaus-console's: on loopback by default, beyond it only with a
// token, which a scrape then gives as `Authorization: Bearer TOKEN` (the
// scrape job's `authorization: {credentials: TOKEN}`) or `?token=TOKEN`
// (401 otherwise). The counters say what traffic a vehicle sees, not how to
// command it: nothing here acts.
#pragma once

#include <utility>  // Boost 1.74's Asio headers need it first

#include <boost/asio/io_context.hpp>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "jaus/base/expected.hpp"
#include "jaus/transport/ipv4.hpp"

namespace jaus::host {

inline constexpr std::uint16_t kDefaultMetricsPort = 9794;

struct MetricsServerOptions {
  transport::Ipv4Endpoint listen{0x7F000001, kDefaultMetricsPort};  // port 0: any free one
  std::string token;  // empty: none asked, and then only on loopback
  std::size_t max_connections = 8;
};

struct MetricsServerCounters {
  std::uint64_t served = 0;        // 200
  std::uint64_t unauthorized = 0;  // 401: a wrong or missing token
  std::uint64_t not_found = 0;     // 404 and 405
  std::uint64_t turned_away = 0;   // closed at once: max_connections were open
  std::uint64_t failed = 0;        // a request that did not parse or timed out, or a connection not accepted
};

class MetricsServer {
 public:
  // Listens (errors: a token missing beyond loopback, the address in use, in one line).
  static Expected<std::unique_ptr<MetricsServer>> start(boost::asio::io_context& io, MetricsServerOptions options,
                                                        std::function<std::string()> render);
  // Stops listening; connections under way end on their own.
  ~MetricsServer();
  MetricsServer(const MetricsServer&) = delete;
  MetricsServer& operator=(const MetricsServer&) = delete;

  std::uint16_t port() const;
  const MetricsServerCounters& counters() const;

  struct Impl;

 private:
  explicit MetricsServer(std::shared_ptr<Impl> impl) : impl_(std::move(impl)) {}
  std::shared_ptr<Impl> impl_;
};

}  // namespace jaus::host
