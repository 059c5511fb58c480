// jausctl's OCU and a target node on one io_context: the session's run loop
// drives both, single-threaded, over real loopback sockets.
#pragma once

#include <utility>  // Boost 1.74's Asio headers need it first

#include <boost/asio/steady_timer.hpp>
#include <list>
#include <sstream>

#include "ocu/ocu_commands.hpp"
#include "jaus/ocu/session.hpp"
#include "command_output.hpp"
#include "target_node.hpp"

namespace jausctl::test {

class OcuTest : public ::testing::Test, public CommandOutput {
 protected:
  void SetUp() override { start_target({}); }

  void start_target(TargetOptions options) {
    target.reset();
    target = std::make_unique<TargetNode>(context, options);
  }

  std::unique_ptr<ocu::OcuSession> open_ocu(jaus::Address self = ocu::kDefaultOcuAddress, std::uint8_t authority = 0) {
    ocu::SessionOptions options;
    options.self = self;
    options.authority = authority;
    options.to = {target->endpoint()};
    options.bind = jaus::transport::Ipv4Endpoint{kLoopback, 0};
    auto session = ocu::OcuSession::open(options, &context);
    if (!session) {
      ADD_FAILURE() << session.error().message();
      return nullptr;
    }
    return std::move(*session);
  }

  // Runs the shared io_context (so the target works) until `done` or 10 s:
  // generous, since a loaded 2-core machine under ASan can stall this process.
  bool run_until(const std::function<bool()>& done) {
    const auto deadline = std::chrono::steady_clock::now() + 10s;
    while (!done()) {
      if (std::chrono::steady_clock::now() > deadline) return false;
      if (context.stopped()) context.restart();
      context.run_for(5ms);
    }
    return true;
  }

  // Runs `action` once `condition` holds, looked at every 10 ms while the
  // io_context runs (a command runs it): a test acts on what has happened
  // (a state shown, a report in), not at a time by which it should have.
  void once(std::function<bool()> condition, std::function<void()> action) {
    poll(pollers_.emplace_back(context), std::move(condition), std::move(action));
  }


  boost::asio::io_context context;
  std::unique_ptr<TargetNode> target;

 private:
  void poll(boost::asio::steady_timer& timer, std::function<bool()> condition, std::function<void()> action) {
    timer.expires_after(10ms);
    timer.async_wait([this, &timer, condition = std::move(condition),
                      action = std::move(action)](const boost::system::error_code& ec) mutable {
      if (ec) return;
      if (condition()) return action();
      poll(timer, std::move(condition), std::move(action));
    });
  }
  std::list<boost::asio::steady_timer> pollers_;  // declared after the io_context: gone before it
};

}  // namespace jausctl::test
