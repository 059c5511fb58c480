// Seeded fault injection for the simulator's link: corrupt or drop frames.
// Latency and disconnects are timed by the server that owns this.
#pragma once

#include <chrono>
#include <cstdint>
#include <random>
#include <span>
#include <vector>

namespace jaus::clearpath::sim {

struct FaultConfig {
  double corrupt_rate = 0;  // probability a frame (or received chunk) gets one byte flipped
  double drop_rate = 0;     // probability an outgoing frame is not sent
  std::chrono::milliseconds latency{0};            // added to every outgoing frame
  std::chrono::milliseconds disconnect_every{0};   // 0 = never
  std::chrono::milliseconds disconnect_for{1500};
  // A one-way line: from this long after the start, the platform ignores every
  // frame it receives (no ACK, no action: its watchdog stops its wheels) while
  // it keeps sending its subscribed data. 0 = never.
  std::chrono::milliseconds deaf_after{0};
  unsigned seed = 1;
};

class FaultInjector {
 public:
  explicit FaultInjector(const FaultConfig& config) : config_(config), rng_(config.seed) {}

  bool drop() { return config_.drop_rate > 0 && chance(config_.drop_rate); }
  // Flips one bit of one byte, sometimes. Returns whether it did.
  bool maybe_corrupt(std::span<std::uint8_t> bytes) {
    if (bytes.empty() || config_.corrupt_rate <= 0 || !chance(config_.corrupt_rate)) return false;
    const auto at = std::uniform_int_distribution<std::size_t>(0, bytes.size() - 1)(rng_);
    bytes[at] = static_cast<std::uint8_t>(bytes[at] ^ (1u << std::uniform_int_distribution<int>(0, 7)(rng_)));
    return true;
  }
  const FaultConfig& config() const { return config_; }

 private:
  bool chance(double p) { return std::uniform_real_distribution<double>(0, 1)(rng_) < p; }
  FaultConfig config_;
  std::mt19937 rng_;
};

}  // namespace jaus::clearpath::sim
