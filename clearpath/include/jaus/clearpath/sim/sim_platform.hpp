// The simulated platform's protocol side, sans-I/O: bytes from the host in,
// ACKs and data out; tick() advances the vehicle and emits subscriptions.
// Time is passed in, so tests run it under a virtual clock.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "jaus/base/time.hpp"
#include "jaus/clearpath/codec.hpp"
#include "jaus/clearpath/frame_parser.hpp"
#include "jaus/clearpath/sim/vehicle_model.hpp"

namespace jaus::clearpath::sim {

// 115200 baud 8N1: ten bit times per byte.
inline constexpr std::size_t kSerialBytesPerSecond = 115200 / 10;

struct PlatformConfig {
  VehicleConfig vehicle;
  // Budget for subscriptions; 0 = unlimited (UDP/TCP). Serial: kSerialBytesPerSecond.
  std::size_t bandwidth_bytes_per_second = 0;
  // Share of the budget subscriptions may use, leaving room for ACKs and replies.
  double bandwidth_share = 0.8;
  std::uint16_t max_frequency_hz = 100;
  std::size_t max_subscriptions = 12;
  std::string name = "Clearpath1";
  std::string model = "SIM-HUSKY";
  std::uint32_t serial = 4242;
};

struct PlatformCounters {
  std::uint64_t frames_in = 0;
  std::uint64_t commands_applied = 0;
  std::uint64_t acks_out = 0;
  std::uint64_t data_out = 0;
  std::uint64_t refused = 0;  // ACKs with a non-zero result
  std::uint64_t parse_errors = 0;
};

// What happened on the platform, for measuring stops (clearpath-sim --events).
// `at` is the platform's time: when the frame or input came in, or the physics
// step at which the wheels reached zero or the watchdog fired.
struct PlatformEvent {
  enum class Kind {
    zero_command,    // a zero motion command after a non-zero one
    wheels_stopped,  // both wheel speeds reached zero after moving
    safety,          // the word Safety Status (0x8010) reports changed; see flags
    input,           // a hardware input was set or released; see input and on
  } kind;
  rt::TimePoint at;
  std::uint16_t flags = 0;  // safety: the new word
  HardwareInput input = HardwareInput::estop;
  bool on = false;
};

class SimPlatform {
 public:
  explicit SimPlatform(PlatformConfig config, rt::TimePoint start);

  std::vector<std::uint8_t> receive(std::span<const std::uint8_t> bytes, rt::TimePoint now);
  std::vector<std::uint8_t> tick(rt::TimePoint now);
  // A physical input set (on) or released; the vehicle first advances to now.
  void press(HardwareInput input, bool on, rt::TimePoint now);
  // Called synchronously, from receive(), tick() and press(), for every event.
  void on_event(std::function<void(const PlatformEvent&)> callback) { on_event_ = std::move(callback); }

  const VehicleModel& vehicle() const { return vehicle_; }
  const PlatformCounters& counters() const { return counters_; }
  const ParserCounters& parser_counters() const { return parser_.counters(); }
  std::size_t subscription_count() const { return subscriptions_.size(); }
  std::uint32_t clock_ms(rt::TimePoint now) const;

  // Data reply for a request (nullopt if this platform lacks it). Public for tests.
  std::optional<AnyMessage> reply_to(const AnyMessage& request, rt::TimePoint now) const;

 private:
  struct SubscriptionKey {
    std::uint16_t type;
    std::uint8_t selector;  // mount (0x4400) or joint (0x5012), else 0
    auto operator<=>(const SubscriptionKey&) const = default;
  };
  struct Subscription {
    AnyMessage request;
    std::uint16_t rate_hz;
    std::size_t frame_bytes;
    rt::TimePoint next_due;
  };
  struct Settings {
    std::string name;
    double max_speed_fwd, max_speed_rev, max_accel_fwd, max_accel_rev;
    MotorControlConstants diff_left, diff_right, ack_speed, ack_heading;
  };

  void handle(const Frame& frame, rt::TimePoint now, std::vector<std::uint8_t>& out);
  std::uint16_t apply_command(const AnyMessage& command, rt::TimePoint now);
  std::uint16_t handle_request(const AnyMessage& request, rt::TimePoint now, bool& reply_now);
  bool supports(std::uint16_t type) const;
  void append(std::vector<std::uint8_t>& out, std::uint16_t type, std::uint32_t timestamp, const AnyMessage& message);
  void advance(rt::TimePoint now);
  Settings current_settings() const;
  void apply_settings(const Settings& s);
  double seconds(rt::TimePoint now) const;
  void note_motion_command(const AnyMessage& command, rt::TimePoint now);
  void note_state(rt::TimePoint at);
  void emit(PlatformEvent event) const;

  PlatformConfig config_;
  rt::TimePoint start_;
  rt::TimePoint simulated_until_;
  std::int64_t clock_offset_ms_ = 0;
  VehicleModel vehicle_;
  FrameParser parser_;
  std::map<SubscriptionKey, Subscription> subscriptions_;
  MotorControlConstants diff_left_, diff_right_, ack_speed_, ack_heading_;
  std::string name_;
  Settings stored_;
  Settings factory_;
  PlatformCounters counters_;
  std::function<void(const PlatformEvent&)> on_event_;
  std::uint16_t reported_safety_ = 0;   // the word last reported as an event
  bool wheels_moving_ = false;
  bool last_motion_nonzero_ = false;    // the last motion command asked for motion
};

}  // namespace jaus::clearpath::sim
