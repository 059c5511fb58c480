#include "jaus/console/panels/pose_panel.hpp"

#include "jaus/messages/all.hpp"

namespace jaus::console {

namespace {

// Presence vectors: x, y, yaw (bits 0, 1, 6) and latitude, longitude (0, 1).
constexpr std::uint32_t kLocalPoseFields = 0x43;
constexpr std::uint32_t kGlobalPoseFields = 0x03;

}  // namespace

void PosePanel::follow(const jaus::Address& a, std::string_view view) {
  if (view == jaus::rt::operator_view::kLocalPose) {
    const auto on_pose = [this, a](const jaus::Header&, const jaus::msg::ReportLocalPose& p) {
      PoseFrame frame{a, p.x_m.value_or(0), p.y_m.value_or(0), p.yaw_rad.value_or(0), {}, {}};
      if (auto ll = latitude_longitude_.find(node_of(a)); ll != latitude_longitude_.end()) {
        frame.latitude = ll->second.first;
        frame.longitude = ll->second.second;
      }
      pages().to_all(frame);
    };
    subscribe<jaus::msg::ReportLocalPose>(a, kLocalPoseFields, on_pose);
  } else if (view == jaus::rt::operator_view::kGlobalPose) {
    const auto on_position = [this, a](const jaus::Header&, const jaus::msg::ReportGlobalPose& p) {
      if (p.latitude_deg && p.longitude_deg) latitude_longitude_[node_of(a)] = {*p.latitude_deg, *p.longitude_deg};
    };
    subscribe<jaus::msg::ReportGlobalPose>(a, kGlobalPoseFields, on_position);
  }
}

}  // namespace jaus::console
