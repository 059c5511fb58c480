// The visual sensor cases (Part 3, environment sensor subgroup): the camera
// count and the selection its controller makes, a non-controller's
// selection ignored, and an image delivered whole in a format the camera
// advertises. Each selects back the camera it found selected.
#include <algorithm>

#include "case_support.hpp"
#include "jaus/messages/environment_messages.hpp"
#include "state_support.hpp"

namespace jaus::conform {

namespace {

using namespace detail;

// How many cameras the selection case tries at most (each is two messages).
constexpr int kCamerasTried = 4;
constexpr std::uint8_t kFormatOptionFields = 0x7F;  // Report Camera Format Options, bits 0..6

std::string unless_visual_sensor(const ComponentUnderTest& component) {
  if (auto why = unless_accepts(component, msg::QueryCameraCount::code, "Query Camera Count (0x2801)"); !why.empty())
    return why;
  return unless_accepts(component, msg::QuerySelectedCamera::code, "Query Selected Camera (0x2804)");
}

std::string unless_selects(const ComponentUnderTest& component) {
  if (auto why = unless_visual_sensor(component); !why.empty()) return why;
  return unless_accepts(component, msg::SelectCamera::code, "Select Camera (0x0802)");
}

std::string unless_images(const ComponentUnderTest& component) {
  if (auto why = unless_visual_sensor(component); !why.empty()) return why;
  if (auto why = unless_accepts(component, msg::QueryImage::code, "Query Image (0x2807)"); !why.empty()) return why;
  return unless_accepts(component, msg::QueryCameraFormatOptions::code, "Query Camera Format Options (0x2806)");
}

Expected<int> camera_count(CaseContext& c) {
  auto report = ask<msg::ReportCameraCount>(c, msg::QueryCameraCount{});
  if (!report) return unexpected(report.error());
  return report->camera_count;
}

Expected<int> selected_camera(CaseContext& c) {
  auto report = ask<msg::ReportSelectedCamera>(c, msg::QuerySelectedCamera{});
  if (!report) return unexpected(report.error());
  return report->camera_id;
}

void select(CaseContext& c, int camera) { send(c, msg::SelectCamera{{static_cast<std::uint8_t>(camera)}}); }

// Part 3, Report Camera Count: the IDs are 1 .. count; the selected one is one of them.
CaseOutcome count_and_selection(CaseContext& c) {
  auto count = camera_count(c);
  if (!count) return fail(count.error().message());
  if (*count < 1) return fail("Report Camera Count gives 0 cameras (1..255)");
  auto found = selected_camera(c);
  if (!found) return fail(found.error().message());
  if (*found < 1 || *found > *count)
    return fail("selected camera " + std::to_string(*found) + " is not one of 1.." + std::to_string(*count));
  if (!c.component.accepts(msg::SelectCamera::code))
    return pass(std::to_string(*count) + " cameras, camera " + std::to_string(*found) +
                " selected; it takes no Select Camera");
  auto state = primary_status(c);
  if (!state) return fail(state.error().message());
  if (*state != msg::PrimaryStatus::ready)
    return skip("in " + state_text(*state) + ": cameras are selected in Ready (count and selection read)");
  ControlHeld control(c);
  if (!control.granted()) return skip("control not granted (" + control.why() + ")");
  std::string failure;
  const int tried = std::min(*count, kCamerasTried);
  for (int camera = 1; camera <= tried && failure.empty(); ++camera) {
    select(c, camera);
    auto now = selected_camera(c);
    if (!now)
      failure = "after Select Camera " + std::to_string(camera) + ", " + now.error().message();
    else if (*now != camera)
      failure = "Select Camera " + std::to_string(camera) + " from its controller, then camera " +
                std::to_string(*now) + " reported selected";
  }
  select(c, *found);  // as found
  if (!failure.empty()) return fail(failure);
  return pass(std::to_string(*count) + " cameras; cameras 1.." + std::to_string(tried) +
              " selected and reported in turn; camera " + std::to_string(*found) + " selected again");
}

// Select Camera from a non-controller changes nothing.
CaseOutcome non_controller_ignored(CaseContext& c) {
  auto count = camera_count(c);
  if (!count) return fail(count.error().message());
  if (*count < 2) return skip("one camera: a selection would change nothing visible");
  auto controller = current_controller(c);
  if (!controller) return fail(controller.error().message());
  if (*controller == c.session.self()) return skip("the runner controls it");
  auto found = selected_camera(c);
  if (!found) return fail(found.error().message());
  const int other = *found == 1 ? 2 : 1;
  select(c, other);
  auto after = selected_camera(c);
  if (!after) return fail("after Select Camera from a non-controller, " + after.error().message());
  if (*after != *found) {
    ControlHeld control(c);
    if (control.granted()) select(c, *found);
    return fail("Select Camera " + std::to_string(other) + " from a non-controller (controller " +
                controller->to_string() + ") executed: camera " + std::to_string(*after) + " selected" +
                (control.granted() ? "; selected back" : ""));
  }
  return pass("Select Camera " + std::to_string(other) + " from a non-controller: camera " + std::to_string(*found) +
              " still selected");
}

struct KnownFormat {
  std::uint8_t code;
  const char* name;
  std::vector<std::uint8_t> starts, ends;  // file signature; what a whole file ends with (empty: unchecked)
};

const std::vector<KnownFormat>& known_formats() {
  static const std::vector<KnownFormat> formats{
      {7, "JPEG", {0xFF, 0xD8}, {0xFF, 0xD9}},
      {8, "GIF", {'G', 'I', 'F', '8'}, {0x3B}},
      {11, "PNG", {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'}, {'I', 'E', 'N', 'D', 0xAE, 0x42, 0x60, 0x82}},
      {12, "BMP", {'B', 'M'}, {}},
  };
  return formats;
}

std::string format_text(std::uint8_t code) {
  for (const auto& f : known_formats())
    if (f.code == code) return std::string(f.name) + " (" + std::to_string(code) + ")";
  return "format " + std::to_string(code);
}

// Query Image gets the selected camera's frame, whole, in one of the formats
// Report Camera Format Options advertises for it; a frame over one packet
// comes as a large data set. Part 3 leaves the image data's layout open: it
// is read as the common one (camera ID, format, the file).
CaseOutcome image_in_advertised_format(CaseContext& c) {
  auto camera = selected_camera(c);
  if (!camera) return fail(camera.error().message());
  msg::QueryCameraFormatOptions query_formats;
  query_formats.presence_vector = kFormatOptionFields;
  query_formats.camera_id = static_cast<std::uint8_t>(*camera);
  auto formats = ask<msg::ReportCameraFormatOptions>(c, query_formats);
  if (!formats) return fail(formats.error().message());
  std::vector<std::uint8_t> advertised;
  for (const auto& f :
       {formats->image_format_1, formats->image_format_2, formats->image_format_3, formats->image_format_4})
    if (f && *f != 0) advertised.push_back(*f);
  if (advertised.empty()) return fail("Report Camera Format Options advertises no image format");
  std::size_t packets = 0;
  bool large = false;
  const auto watcher = c.session.watch([&](const Header& h) {
    if (h.command_code != msg::ReportImage::code || h.source != c.target()) return;
    ++packets;
    large = large || h.data_flag != DataFlag::single;
  });
  auto image = ask<msg::ReportImage>(c, msg::QueryImage{});
  c.session.unlisten(watcher);
  if (!image) return fail(image.error().message());
  if (image->camera_id != *camera)
    return fail("Report Image from camera " + std::to_string(image->camera_id) + ", camera " + std::to_string(*camera) +
                " selected");
  if (std::find(advertised.begin(), advertised.end(), image->image_format) == advertised.end())
    return fail("Report Image in " + format_text(image->image_format) +
                ", which Report Camera Format Options does "
                "not advertise");
  const std::size_t size = image->data.size() + 2;
  if (size > kMaxPayloadSize && !large)
    return fail(std::to_string(size) + " bytes, more than one packet holds, but no large data set seen");
  const auto& data = image->data;
  for (const auto& f : known_formats()) {
    if (f.code != image->image_format) continue;
    if (data.size() < f.starts.size() || !std::equal(f.starts.begin(), f.starts.end(), data.begin()))
      return fail("Report Image says " + format_text(f.code) + " but its data does not start like one");
    if (!f.ends.empty() && (data.size() < f.ends.size() || !std::equal(f.ends.rbegin(), f.ends.rend(), data.rbegin())))
      return fail("the " + format_text(f.code) + " image of " + std::to_string(data.size()) +
                  " bytes does not end like a whole one");
  }
  return pass(format_text(image->image_format) + " from camera " + std::to_string(*camera) + ", " +
              std::to_string(data.size()) + " bytes" +
              (large ? " in a large data set of " + std::to_string(packets) + " packets" : " in one packet"));
}

}  // namespace

std::span<const ConformanceCase> visual_sensor_cases() {
  static const std::vector<ConformanceCase> list{
      {"visual.count_and_selection",
       "the camera count is 1..255, the selected camera one of them, and its controller's selection is reported",
       "Part 3, Code 4801h Report Camera Count, Code 0802h Select Camera, Code 4804h Report Selected Camera",
       unless_visual_sensor, count_and_selection},
      {"visual.non_controller_ignored", "Select Camera from a non-controller changes nothing",
       "Part 3, Code 000Dh Request Component Control (commands are the controller's), Code 4804h Report Selected "
       "Camera",
       unless_selects, non_controller_ignored},
      {"visual.image_format",
       "Query Image gets the selected camera's image, whole, in a format it advertises (a large data set when large)",
       "Part 3, Code 2807h Query Image, Code 4807h Report Image, Code 4806h Report Camera Format Options; "
       "docs/wire-format.md: Large data sets; docs/components.md Report Image layout",
       unless_images, image_in_advertised_format},
  };
  return list;
}

}  // namespace jaus::conform
