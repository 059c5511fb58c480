// jausctl's OCU and the target node (virtual_target.hpp, tests/support) in
// one process on a jaus::testing memory network under virtual time: no
// socket, no real clock.
// A command that waits advances the virtual clock, so a timeout of 30 s
// takes no real time and every time a test reads is exact. The same
// interface as OcuTest (ocu_fixture.hpp): a test moves over by naming this
// fixture.
#pragma once

#include <functional>
#include <memory>
#include <sstream>
#include <stdexcept>

#include "jaus/ocu/session.hpp"
#include "jaus/testing/memory_link.hpp"
#include "jaus/testing/virtual_time.hpp"
#include "ocu/ocu_commands.hpp"
#include "command_output.hpp"
#include "memory_ocu.hpp"
#include "virtual_target.hpp"

namespace jausctl::test {

class VirtualOcuTest : public ::testing::Test, public CommandOutput {
 protected:
  void SetUp() override { start_target({}); }

  void start_target(const TargetOptions& options) {
    target.reset();
    target = std::make_unique<VirtualTarget>(time, network, options);
  }

  std::unique_ptr<ocu::OcuSession> open_ocu(jaus::Address self = ocu::kDefaultOcuAddress, std::uint8_t authority = 0) {
    ocu::SessionOptions options;
    options.self = self;
    options.authority = authority;
    auto session = jaus::test_support::attach_ocu(time, network, options);
    if (!session) {
      ADD_FAILURE() << session.error().message();
      return nullptr;
    }
    return std::move(*session);
  }

  // Lets virtual time pass until `done` or 10 s of it.
  bool run_until(const std::function<bool()>& done) { return jaus::testing::run_until(time, done, 10s); }

  // Runs `action` once `condition` holds, looked at every 10 ms of virtual
  // time while a command waits.
  void once(std::function<bool()> condition, std::function<void()> action) {
    time.call_at(time.now() + 10ms, [this, condition = std::move(condition), action = std::move(action)]() mutable {
      if (condition()) return action();
      once(std::move(condition), std::move(action));
    });
  }


  jaus::rt::VirtualTime time;
  jaus::testing::MemoryNetwork network{time, time};
  std::unique_ptr<VirtualTarget> target;
};

}  // namespace jausctl::test
