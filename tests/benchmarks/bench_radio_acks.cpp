// Commands that must arrive, over a field radio and over a LAN, under
// virtual time (issue 45, step 1): an OCU's node and a vehicle's node on a
// jaus::testing memory network. The radio: 100-200 ms each way (a round trip
// of 300 ms +- 100 ms), packets overtaking each other, 20 % lost each way in
// fades of 150 ms on average (600 ms between them); the LAN: 1 ms each way,
// nothing lost. For each
// retransmission policy, Set Emergency sent `tries` times, each once the
// last was settled and 200 ms later: how many were acknowledged, the time to
// the ACK (p50 / p99 / max), and how many copies each cost on the air.
//
// Policies: the fixed pace before issue 45 (every 50 ms, 10 times), a
// command's (MustArrivePolicy{}: the measured round trip, backing off, 3 s)
// and a stop's (MustArrivePolicy::emergency(): the measured round trip
// without backing off, 10 s).
//
//   bench_radio_acks [tries] [seed]     defaults: 200 tries, seed 45
//
// Deterministic: the same figures for a seed on every machine. A figure, not
// a test: docs/deployment.md quotes it.
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <optional>
#include <vector>

#include "bench_support.hpp"
#include "jaus/base/virtual_time.hpp"
#include "jaus/messages/core_messages.hpp"
#include "jaus/node/node.hpp"
#include "jaus/ocu/must_arrive.hpp"
#include "jaus/testing/memory_link.hpp"

namespace {

using namespace std::chrono_literals;
using jaus::rt::Duration;

const jaus::Address kTarget{1, 1, 33, 1};
const jaus::Address kOcu{2, 1, 40, 1};

struct LinkProfile {
  const char* name;
  Duration least_one_way;
  Duration jitter;       // up to this much more each way
  Duration mean_good{};  // between fades
  Duration mean_fade{};  // zero: nothing lost
};

struct Policy {
  const char* name;
  jaus::node::AckPolicy ack;
};

// Any component: the node ACKs a message once one has taken it.
class Target final : public jaus::rt::Component {
 public:
  Target(jaus::rt::ComponentConfig config, jaus::rt::Environment env) : Component(std::move(config), std::move(env)) {}
};

struct Outcome {
  std::vector<double> ack_ms;
  int unacknowledged = 0;
  std::uint64_t copies = 0;
  std::optional<Duration> smoothed;  // the round trip the OCU's node measured
  Duration timeout{};
};

Outcome run(const LinkProfile& link, const Policy& policy, int tries, std::uint32_t seed) {
  jaus::rt::VirtualTime time;
  jaus::testing::MemoryNetwork network(time, time, link.least_one_way);
  network.set_jitter(link.jitter, seed);
  auto& vehicle_link = network.attach(kTarget.subsystem, kTarget.node);
  auto& ocu_link = network.attach(kOcu.subsystem, kOcu.node);
  jaus::node::NodeConfig vehicle_config;
  vehicle_config.subsystem = kTarget.subsystem;
  vehicle_config.node = kTarget.node;
  jaus::node::Node vehicle(vehicle_config, time, time, vehicle_link);
  vehicle_link.deliver_to(vehicle);
  jaus::rt::ComponentConfig target;
  target.address = kTarget;
  target.name = "target";
  vehicle.add_as(std::make_unique<Target>(target, vehicle.environment()));
  jaus::node::NodeConfig ocu_config;
  ocu_config.subsystem = kOcu.subsystem;
  ocu_config.node = kOcu.node;
  jaus::node::Node ocu(ocu_config, time, time, ocu_link);
  ocu_link.deliver_to(ocu);
  if (link.mean_fade > Duration::zero()) ocu_link.set_burst_loss(link.mean_good, link.mean_fade, seed);

  Outcome outcome;
  ocu_link.on_transmit([&](const jaus::Header& h, std::span<const std::uint8_t>) {
    outcome.copies += h.command_code == jaus::msg::SetEmergency::code;
  });
  std::vector<std::uint8_t> payload(jaus::kMaxPayloadSize);
  payload.resize(*jaus::wire::encode_payload(jaus::msg::SetEmergency{{1}}, payload));
  jaus::Header header;
  header.command_code = jaus::msg::SetEmergency::code;
  header.priority = jaus::priority::kSafetyCritical;
  header.source = kOcu;
  header.destination = kTarget;
  for (int i = 0; i < tries; ++i) {
    const auto start = time.now();
    std::optional<jaus::node::AckResolution> resolved;
    jaus::rt::TimePoint resolved_at{};
    ocu.send_acknowledged(header, payload, policy.ack, [&](const jaus::node::AckResolution& r) {
      resolved = r;
      resolved_at = time.now();
    });
    while (!resolved && time.now() - start < 60s) time.advance(10ms);
    if (resolved && resolved->outcome == jaus::node::AckOutcome::acknowledged)
      outcome.ack_ms.push_back(std::chrono::duration<double, std::milli>(resolved_at - start).count());
    else
      ++outcome.unacknowledged;
    time.advance(200ms);
  }
  if (const auto* measured = ocu.acks().round_trip(jaus::Address{kTarget.subsystem, kTarget.node, 0, 0})) {
    outcome.smoothed = measured->smoothed();
    outcome.timeout = measured->timeout();
  }
  return outcome;
}

double ms(Duration d) { return std::chrono::duration<double, std::milli>(d).count(); }

}  // namespace

int main(int argc, char** argv) {
  const int tries = argc > 1 ? std::max(1, std::atoi(argv[1])) : 200;
  const auto seed = static_cast<std::uint32_t>(argc > 2 ? std::strtoul(argv[2], nullptr, 10) : 45);
  const LinkProfile links[] = {
      {"LAN, 1 ms each way, no loss", 1ms, 0ms},
      {"radio, 100-200 ms each way, 20 % lost in fades of 150 ms", 100ms, 100ms, 600ms, 150ms},
  };
  const Policy policies[] = {
      {"fixed 50 ms x 10 (before)", jaus::node::AckPolicy{50ms, 10}},
      {"command (measured, backing off, 3 s)", jaus::ocu::MustArrivePolicy{}},
      {"stop (measured, 10 s)", jaus::ocu::MustArrivePolicy::emergency()},
  };
  std::printf("Set Emergency x %d, seed %u\n", tries, seed);
  for (const auto& link : links) {
    std::printf("\n%s\n", link.name);
    std::printf("  %-38s %8s %8s %8s %8s %8s %11s\n", "policy", "acked", "p50 ms", "p99 ms", "max ms", "copies",
                "RTT / RTO");
    for (const auto& policy : policies) {
      const Outcome o = run(link, policy, tries, seed);
      const auto f = jaus::bench::figures(o.ack_ms);
      char rtt[32] = "-";
      if (o.smoothed) std::snprintf(rtt, sizeof rtt, "%.0f / %.0f", ms(*o.smoothed), ms(o.timeout));
      std::printf("  %-38s %4zu/%-3d %8.0f %8.0f %8.0f %8.2f %11s\n", policy.name, f.count, tries, f.p50, f.p99, f.max,
                  static_cast<double>(o.copies) / tries, rtt);
    }
  }
  return 0;
}
