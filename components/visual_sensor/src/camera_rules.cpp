#include "jaus/components/camera_rules.hpp"

#include <algorithm>
#include <numbers>
#include <set>
#include <string>

#include "jaus/components/camera.hpp"

namespace jaus::components {

namespace {

bool printable(std::string_view text) {
  return std::all_of(text.begin(), text.end(), [](char ch) { return ch >= 0x20 && ch < 0x7F; });
}

Expected<void> refuse(std::string what) { return unexpected(make_error(ErrorCode::invalid_argument, std::move(what))); }

}  // namespace

Expected<void> check_cameras_config(const VisualSensorConfig& config) {
  using image_format::kJpeg;
  using image_format::kPng;
  if (config.cameras.empty() || config.cameras.size() > 255) return refuse("'cameras' must list 1..255 cameras");
  std::set<int> ids;
  for (const auto& c : config.cameras) {
    const std::string who = "camera " + std::to_string(c.id) + " (" + c.name + "): ";
    if (c.id == 0) return refuse(who + "'id' must be 1..255");
    if (!ids.insert(c.id).second) return refuse("duplicate camera id " + std::to_string(c.id));
    if (c.name.empty() || c.name.size() > 15 || !printable(c.name))
      return refuse(who + "'name' must be 1..15 printable ASCII characters");
    if (c.description.size() > 50 || !printable(c.description))
      return refuse(who + "'description' must be at most 50 printable ASCII characters");
    for (const auto& [axis, name] : {std::pair{&c.pan, "pan"}, std::pair{&c.tilt, "tilt"}, std::pair{&c.zoom, "zoom"}})
      if (axis->min > axis->max || axis->max_rate < 0)
        return refuse(who + "'" + name + "' needs min <= max and a max rate >= 0");
    if (c.zoom.min < 0 || c.zoom.max > 100) return refuse(who + "'zoom' is a percent of the lens range, 0..100");
    if (!(c.narrowest_horizontal_fov_rad > 0 && c.narrowest_horizontal_fov_rad <= c.widest_horizontal_fov_rad &&
          c.widest_horizontal_fov_rad <= std::numbers::pi))
      return refuse(who + "'field_of_view_deg' needs 0 < narrowest <= widest <= 180");
    if (c.min_width > c.width || c.width > c.max_width || c.min_height > c.height || c.height > c.max_height)
      return refuse(who + "'width' and 'height' must be within min_width..max_width and min_height..max_height");
    if (c.min_frame_rate_fps > c.frame_rate_fps || c.frame_rate_fps > c.max_frame_rate_fps)
      return refuse(who + "'frame_rate_fps' must be within min_frame_rate_fps..max_frame_rate_fps");
    if (c.image_formats.empty() || c.image_formats.size() > 4)
      return refuse(who + "'formats' must list 1..4 of png, jpeg");
    std::set<std::uint8_t> formats;
    for (auto f : c.image_formats)
      if ((f != kPng && f != kJpeg) || !formats.insert(f).second)
        return refuse(who + "'formats' must list png and/or jpeg, once each");
  }
  return {};
}

}  // namespace jaus::components
