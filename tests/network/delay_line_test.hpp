// The fixture of the suites whose OCU reaches veh1 only through the delay
// line (delay_line.hpp): the line in the `ocu` namespace at
// 10.77.0.10:4794, forwarding to veh1's 10.77.0.11:3794, and the
// in-process OCU with the line as its only peer. The OCU goes before the
// line: nothing is left to relay.
#pragma once

#include "delay_line.hpp"
#include "network_test.hpp"

namespace jaus::test::network {

class ThroughDelayLine : public NetworkTest {
 protected:
  static constexpr std::uint16_t kLinePort = 4794;

  // `options` with where the line listens and forwards filled in.
  void start_line(DelayLineOptions options) {
    options.name_space = lab->namespace_of(kOcu);
    options.listen = ipv4_endpoint(kOcu.address, kLinePort);
    options.vehicle = ipv4_endpoint(kVeh1.address, 3794);
    auto started = DelayLine::start(std::move(options));
    ASSERT_TRUE(started) << started.error().message();
    line = std::move(*started);
  }
  void open_ocu_through_line() {
    ASSERT_NE(open_ocu_at({jaus::transport::Ipv4Endpoint{jaus::transport::parse_endpoint(kOcu.address)->address,
                                                         kLinePort}}),
              nullptr);
  }
  void TearDown() override {
    ocu.reset();
    line.reset();
    NetworkTest::TearDown();
  }

  std::unique_ptr<DelayLine> line;
};

}  // namespace jaus::test::network
