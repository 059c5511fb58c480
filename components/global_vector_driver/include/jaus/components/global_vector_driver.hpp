// The global vector driver (component 34): Set Global Vector 0x0407 (speed,
// altitude, heading, roll, pitch: presence bits 0-4) and Query/Report Global
// Vector 0x2407/0x4407. It follows the speed and the heading (from north,
// clockwise) with the vector driver's loops (vector_driver.hpp); altitude,
// roll and pitch, which a ground vehicle cannot follow, are stored and
// echoed, as absent fields keep what was commanded before.
#pragma once

#include <optional>

#include "jaus/components/vector_driver.hpp"
#include "jaus/messages/platform_messages.hpp"

namespace jaus::components {

namespace global_vector_field {
inline constexpr std::uint8_t kSpeed = 1u << 0;
inline constexpr std::uint8_t kAltitude = 1u << 1;
inline constexpr std::uint8_t kHeading = 1u << 2;
inline constexpr std::uint8_t kRoll = 1u << 3;
inline constexpr std::uint8_t kPitch = 1u << 4;
inline constexpr std::uint8_t kAll = 0x1F;
}  // namespace global_vector_field

class GlobalVectorDriver final : public VectorDriver {
 public:
  GlobalVectorDriver(rt::ComponentConfig config, rt::Environment env, PoseSource& pose, VectorDriverOptions options);

  // The commanded vector: speed always, the other fields once commanded
  // (the heading also once the vehicle's was taken).
  msg::ReportGlobalVector report() const;

 private:
  void on_set(const msg::SetGlobalVector& message);
  void forget_command() override;

  std::optional<double> altitude_m_, roll_rad_, pitch_rad_;
};

}  // namespace jaus::components
