// Driving over a field radio with a camera streaming, under virtual time
// (issue 45, step 2; the scenario: tests/support/radio_drive.hpp): radios of
// 256 and 64 kbit/s each way, 100-200 ms each way (a round trip of 300 ms
// +- 100 ms), 20 % lost in fades of 150 ms on average, a 32 KiB buffer in
// each radio. Printed per radio, with and without the vehicle's send
// budget (node/budgeted_link.hpp, set a little under the radio's rate):
// Set Emergency acknowledged and the time to its ACK, control lost (Reject
// Component Control), the efforts' latency to the vehicle's node, and the
// frames the operator received whole with the longest gap between two.
//
//   bench_radio_link [seconds] [seed] [--log]     defaults: 300 s, seed 45
//
// --log prints the vehicle's warnings (a control lost, a stop) with their
// virtual time.
//
// Deterministic: the same figures for a seed on every machine. A figure, not
// a test: docs/deployment.md quotes it.
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

#include "bench_support.hpp"
#include "radio_drive.hpp"

using namespace jaus::test_support::radio;

int main(int argc, char** argv) {
  const int seconds = argc > 1 ? std::max(10, std::atoi(argv[1])) : 300;
  const auto seed = static_cast<std::uint32_t>(argc > 2 ? std::strtoul(argv[2], nullptr, 10) : 45);
  const bool log = argc > 3 && std::string_view(argv[3]) == "--log";
  struct Radio {
    const char* name;
    std::uint64_t bits_per_second;
  };
  const Radio radios[] = {{"256 kbit/s", 256'000}, {"64 kbit/s", 64'000}};
  std::printf("%d s of driving at 10 Hz with a camera streaming, Set Emergency every 3 s, seed %u\n", seconds, seed);
  std::printf("radio: 100-200 ms each way, 20 %% lost in fades of 150 ms, 32 KiB buffer\n");
  for (const auto& radio : radios) {
    std::printf("\n%s\n", radio.name);
    std::printf("  %-22s %9s %8s %8s %6s %9s %9s %8s %8s %9s\n", "vehicle's send budget", "stops", "p50 ms",
                "p99 ms", "lost", "effort", "p99 ms", "frames", "max gap", "overflow");
    for (const std::uint64_t budget : {std::uint64_t{0}, radio.bits_per_second * 9 / 10}) {
      DriveOptions options;
      options.radio.bits_per_second = radio.bits_per_second;
      options.budget_bits_per_second = budget;
      options.length = std::chrono::seconds(seconds);
      options.seed = seed;
      if (log)
        options.vehicle_log = [](jaus::rt::LogLevel level, const std::string& line) {
          if (level >= jaus::rt::LogLevel::warn) std::printf("    vehicle: %s\n", line.c_str());
        };
      const Outcome o = drive_over_radio(options);
      const auto stops = jaus::bench::figures(o.emergency_ack_ms);
      const auto efforts = jaus::bench::figures(o.effort_ms);
      char name[32];
      if (budget == 0)
        std::snprintf(name, sizeof name, "none");
      else
        std::snprintf(name, sizeof name, "%llu kbit/s", static_cast<unsigned long long>(budget / 1000));
      std::printf("  %-22s %4zu/%-4d %8.0f %8.0f %6d %4zu/%-4d %9.0f %8zu %7.1f s %9llu\n", name, stops.count,
                  o.emergencies, stops.p50, stops.p99, o.control_lost, efforts.count, o.efforts_sent, efforts.p99,
                  o.frames.size(), longest_gap_s(o.frames), static_cast<unsigned long long>(o.radio_overflowed));
      if (!o.frames.empty())
        std::printf("  %-22s frames of %llu bytes on average; %s\n", "",
                    static_cast<unsigned long long>(o.frame_bytes / o.frames.size()),
                    o.budget.empty() ? "no budget" : o.budget.c_str());
    }
  }
  return 0;
}
