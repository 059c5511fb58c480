// jausctl's OCU and a target node on one io_context: the session's run loop
// drives both, single-threaded, over real loopback sockets.
#pragma once

#include <sstream>

#include "ocu/ocu_commands.hpp"
#include "jaus/ocu/session.hpp"
#include "target_node.hpp"

namespace jausctl::test {

class OcuTest : public ::testing::Test {
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

  // Runs the shared io_context (so the target works) until `done` or 2 s.
  bool run_until(const std::function<bool()>& done) {
    const auto deadline = std::chrono::steady_clock::now() + 2s;
    while (!done()) {
      if (std::chrono::steady_clock::now() > deadline) return false;
      if (context.stopped()) context.restart();
      context.run_for(5ms);
    }
    return true;
  }

  ocu::CommandIo io() { return ocu::CommandIo{out, err}; }
  std::vector<std::string> out_lines() const {
    std::vector<std::string> lines;
    std::istringstream in(out.str());
    for (std::string line; std::getline(in, line);) lines.push_back(line);
    return lines;
  }

  boost::asio::io_context context;
  std::unique_ptr<TargetNode> target;
  std::ostringstream out;
  std::ostringstream err;
};

}  // namespace jausctl::test
