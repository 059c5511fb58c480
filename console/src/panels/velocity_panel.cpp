#include "jaus/console/panels/velocity_panel.hpp"

#include "jaus/messages/all.hpp"

namespace jaus::console {

namespace {

// Presence vector: x, y and yaw rate (bits 0, 1, 6).
constexpr std::uint32_t kVelocityFields = 0x43;

}  // namespace

void VelocityPanel::follow(const jaus::Address& a, std::string_view /*view*/) {
  subscribe<jaus::msg::ReportVelocityState>(
      a, kVelocityFields, [this, a](const jaus::Header&, const jaus::msg::ReportVelocityState& v) {
        pages().to_all(
            VelocityFrame{a, v.velocity_x_mps.value_or(0), v.velocity_y_mps.value_or(0), v.yaw_rate_rps.value_or(0)});
      });
}

}  // namespace jaus::console
