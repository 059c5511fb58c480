#include "jaus/console/panels/camera_panel.hpp"

#include <vector>

#include "jaus/messages/all.hpp"

namespace jaus::console {

namespace {

std::string image_format_name(std::uint8_t code) {
  for (const auto& f : jaus::msg::kImageFormats)
    if (f.value == code) return std::string(f.name);
  return "format " + std::to_string(code);
}

}  // namespace

void CameraPanel::on_frame(PageId page, const CameraFrame& frame) {
  const auto& target = frame.target;
  if (frame.watch) watch(target, page);
  else unwatch(target, page);
  if (frame.pan_deg || frame.tilt_deg) {
    const auto percent = [](std::optional<double> deg, double full_scale) -> std::optional<double> {
      if (!deg || !(full_scale > 0)) return std::nullopt;
      return within(*deg / full_scale * 100, -100, 100);
    };
    jaus::msg::SetCameraPose pose{};
    pose.camera_id = options().camera_id;
    pose.mode_indicator = 0;  // position, not rate
    pose.y_angular_percent = percent(frame.pan_deg, options().camera_pan_full_scale_deg);
    pose.x_angular_percent = percent(frame.tilt_deg, options().camera_tilt_full_scale_deg);
    control_.as_controller(page, target, [this, target, pose] { session().send(target, pose); });
  }
}

void CameraPanel::watch(const jaus::Address& target, PageId page) {
  auto& camera = cameras_[target];
  camera.watchers.insert(page);
  if (camera.subscription) return;
  camera.subscription = session().component().subscribe<jaus::msg::ReportImage>(
      target, options().report_rate_hz, 0, [this, target](const jaus::Header&, const jaus::msg::ReportImage& r) {
        auto it = cameras_.find(target);
        if (it == cameras_.end()) return;
        const auto text =
            format_frame(ImageFrame{target, image_format_name(r.image_format), base64(r.data), ++it->second.frames});
        for (PageId watcher : it->second.watchers) pages().send(watcher, text);
      });
  pages().event(EventLevel::info, "watching " + target.to_string());
}

void CameraPanel::unwatch(const jaus::Address& target, PageId page) {
  auto it = cameras_.find(target);
  if (it == cameras_.end()) return;
  it->second.watchers.erase(page);
  if (!it->second.watchers.empty()) return;
  if (it->second.subscription) session().component().unsubscribe(*it->second.subscription);
  cameras_.erase(it);
  pages().event(EventLevel::info, "no page watches " + target.to_string() + ": its images stop");
}

void CameraPanel::page_closed(PageId page) {
  std::vector<jaus::Address> watched;
  for (const auto& [target, camera] : cameras_)
    if (camera.watchers.count(page)) watched.push_back(target);
  for (const auto& target : watched) unwatch(target, page);
}

void CameraPanel::shutdown() {
  for (auto& [target, camera] : cameras_)
    if (camera.subscription) session().component().unsubscribe(*camera.subscription);
  cameras_.clear();
  Panel::shutdown();
}

}  // namespace jaus::console
