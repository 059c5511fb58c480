// An OCU and the target node on a jaus::testing memory network under virtual
// time, the OCU's link losing datagrams at random (deterministic seeds) each
// way: what an operator on a lossy radio link sees (issue 32). The network
// takes 5 ms each way, a radio link's order of magnitude, so that times read
// are round trips, not zero.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

#include "virtual_fixture.hpp"

namespace jausctl::test {

inline constexpr jaus::rt::Duration kOneWay = 5ms;

class LossyOcuTest : public VirtualOcuTest {
 protected:
  void SetUp() override {
    network.set_latency(kOneWay);
    start_target(target_options());
  }
  virtual TargetOptions target_options() const { return {}; }

  // The OCU at 254.1.40.1 on its own link (ocu_link).
  std::unique_ptr<ocu::OcuSession> open_lossy_ocu(std::uint8_t authority = 0,
                                                  ocu::MustArriveSettings must_arrive = {}) {
    ocu::SessionOptions options;
    options.authority = authority;
    options.must_arrive = must_arrive;
    ocu_link = &network.attach(options.self.subsystem, options.self.node);
    auto session = jaus::test_support::attach_ocu(time, *ocu_link, options);
    if (!session) {
      ADD_FAILURE() << session.error().message();
      return nullptr;
    }
    return std::move(*session);
  }

  // `outbound` of what the OCU sends and `inbound` of what reaches it are lost.
  void lose(double outbound, double inbound, std::uint32_t seed) { ocu_link->set_loss(outbound, inbound, seed); }

  // Nothing leaves or reaches the OCU for `duration` from now: the first
  // datagrams of what it sends next are lost, deterministically.
  void cut_for(jaus::rt::Duration duration) {
    ocu_link->set_connected(false);
    time.call_at(time.now() + duration, [link = ocu_link] { link->set_connected(true); });
  }

  jaus::testing::MemoryLink* ocu_link = nullptr;
};

// The p-th percentile (0..100) of `values` (nearest rank).
template <class T>
T percentile(std::vector<T> values, double p) {
  std::sort(values.begin(), values.end());
  const auto rank = static_cast<std::size_t>(std::max(1.0, std::ceil(p / 100.0 * static_cast<double>(values.size()))));
  return values[std::min(rank, values.size()) - 1];
}

inline double ms(jaus::rt::Duration d) { return std::chrono::duration<double, std::milli>(d).count(); }

}  // namespace jausctl::test
