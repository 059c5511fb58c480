#include "jaus/components/visual_sensor.hpp"

#include <algorithm>
#include <set>

#include "jaus/wire/describe.hpp"

namespace jaus::components {

using namespace rt;

namespace {

// Every field of Report Camera Pose (name, origin, direction cosines).
constexpr std::uint32_t kPoseReportFields = 0x03FF;
// Report Camera Capabilities: description, FOVs, resolutions, frame rates
// (bits 0-10), imagery and audio control (13, 14); no shutter.
constexpr std::uint32_t kCapabilitiesReportFields = 0x67FF;
// Report Camera Format Options: up to four image formats (bits 2-5), no audio.
constexpr std::uint32_t kFormatReportFields = 0x3C;
// Set Camera Capabilities fields acted on: the FOVs (bits 0, 1, through the
// zoom), the resolution (2, 3), the frame rate (7).
constexpr std::uint32_t kFovFields = 0x0003;
constexpr std::uint32_t kCapabilitiesCommandFields = 0x008C;
// Set Camera Format Options: the image format (bit 1).
constexpr std::uint32_t kFormatCommandFields = 0x02;

// Images flow in Ready and in Emergency: a stop holds the mounts, not the
// picture, so the operator sees what the stop left (issue 45). Standby (the
// operator asked for rest) and every other state pause them.
bool images_flow(PrimaryStatus state) { return state == PrimaryStatus::ready || state == PrimaryStatus::emergency; }

std::string id_text(std::uint8_t id) { return std::to_string(id); }

// The pipeline keeps capturing, one frame period apart, this long after the
// last request for a frame: streams slower than the frame rate get a recent frame.
constexpr Duration kKeepCapturing = std::chrono::seconds(2);
// Query Image per requesting node: the frame rate, with a burst of this many (jitter).
constexpr double kQueryBurst = 2;
// Requesting nodes tracked for Query Image; beyond (a flood of sources), new ones are ignored.
constexpr std::size_t kMaxQueryRequesters = 256;
// Query Image senders a capture under way answers at most.
constexpr std::size_t kMaxWaiting = 64;

// The base refuses a requesting node's image streams beyond the option.
ComponentConfig with_image_cap(ComponentConfig config, const VisualSensorOptions& options) {
  config.service_connections.max_per_requester_node[msg::ReportImage::code] = options.image_connections_per_requester;
  return config;
}

}  // namespace

VisualSensor::VisualSensor(ComponentConfig config, Environment env, Cameras& cameras, VisualSensorOptions options)
    : Component(with_image_cap(std::move(config), options), std::move(env)),
      cameras_(cameras),
      options_(options),
      own_worker_(std::make_unique<ScheduledFrameWorker>(this->env().scheduler, this->env().clock)),
      worker_(own_worker_.get()),
      images_(&cameras) {
  using namespace msg;
  std::set<std::uint8_t> ids;
  for (const CameraConfig& c : cameras_.configs())
    if (c.id != 0 && ids.insert(c.id).second) cameras_in_use_.push_back(Camera{&c, initial_settings(c)});
  if (!cameras_in_use_.empty()) selected_ = cameras_in_use_.front().config->id;

  // Commands: the controller's, in Ready only (the base refuses the rest and counts them).
  handle<SelectCamera>(Access::controller, /*ready_only=*/true,
                       [this](const Header& h, const SelectCamera& m) { on_select_camera(h, m); });
  handle<SetCameraPose>(Access::controller, /*ready_only=*/true,
                        [this](const Header& h, const SetCameraPose& m) { on_set_camera_pose(h, m); });
  handle<SetCameraCapabilities>(Access::controller, /*ready_only=*/true,
                                [this](const Header& h, const SetCameraCapabilities& m) { on_set_capabilities(h, m); });
  handle<SetCameraFormatOptions>(Access::controller, /*ready_only=*/true,
                                 [this](const Header& h, const SetCameraFormatOptions& m) { on_set_format(h, m); });

  // Queries: anyone, in any state; images in Ready and Emergency (images_flow).
  handle<QueryCameraCount>(Access::anyone, false, [this](const Header& h, const QueryCameraCount&) {
    send(h.source, ReportCameraCount{{static_cast<std::uint8_t>(cameras_in_use_.size())}});
  });
  handle<QuerySelectedCamera>(Access::anyone, false, [this](const Header& h, const QuerySelectedCamera&) {
    send(h.source, ReportSelectedCamera{{selected_}});
  });
  handle<QueryCameraPose>(Access::anyone, false, [this](const Header& h, const QueryCameraPose& q) {
    if (!queried_camera_exists(h, q.camera_id, QueryCameraPose::name)) return;
    auto report = *camera_pose_report(q.camera_id);
    wire::mask_presence(report, q.presence_vector);
    send(h.source, report);
  });
  handle<QueryCameraCapabilities>(Access::anyone, false, [this](const Header& h, const QueryCameraCapabilities& q) {
    if (!queried_camera_exists(h, q.camera_id, QueryCameraCapabilities::name)) return;
    auto report = *capabilities_report(q.camera_id);
    wire::mask_presence(report, q.presence_vector);
    send(h.source, report);
  });
  handle<QueryCameraFormatOptions>(Access::anyone, false,
                                   [this](const Header& h, const QueryCameraFormatOptions& q) {
                                     if (!queried_camera_exists(h, q.camera_id, QueryCameraFormatOptions::name)) return;
                                     auto report = *format_report(q.camera_id);
                                     wire::mask_presence(report, q.presence_vector);
                                     send(h.source, report);
                                   });
  handle<QueryImage>(Access::anyone, /*ready_only=*/false, [this](const Header& h, const QueryImage&) { on_query_image(h); });

  // The same reports on service connections, for the selected camera.
  provide<ReportCameraCount>(0, [this] {
    return ReportCameraCount{{static_cast<std::uint8_t>(cameras_in_use_.size())}};
  });
  provide<ReportSelectedCamera>(0, [this] { return ReportSelectedCamera{{selected_}}; });
  provide_if<ReportCameraPose>(kPoseReportFields, [this] { return camera_pose_report(selected_); });
  provide_if<ReportCameraCapabilities>(kCapabilitiesReportFields, [this] { return capabilities_report(selected_); });
  provide_if<ReportCameraFormatOptions>(kFormatReportFields, [this] { return format_report(selected_); });
  provide_images();

  // Report Services: the fields each command acts on and each query can get.
  std::uint32_t pose_fields = 0, fov_fields = 0;
  for (const Camera& c : cameras_in_use_) {
    if (c.config->pan.movable()) pose_fields |= pose_field::kYAngular;
    if (c.config->tilt.movable()) pose_fields |= pose_field::kXAngular;
    if (c.config->zoom.movable()) pose_fields |= pose_field::kZLinear;
    if (zoom_for_fov(*c.config, c.config->widest_horizontal_fov_rad)) fov_fields = kFovFields;
  }
  declare_input_presence(SetCameraPose::code, pose_fields);
  declare_input_presence(SetCameraCapabilities::code, kCapabilitiesCommandFields | fov_fields);
  declare_input_presence(SetCameraFormatOptions::code, kFormatCommandFields);
  declare_input_presence(QueryCameraPose::code, kPoseReportFields);
  declare_input_presence(QueryCameraCapabilities::code, kCapabilitiesReportFields);
  declare_input_presence(QueryCameraFormatOptions::code, kFormatReportFields);
}

VisualSensor::~VisualSensor() {
  if (next_capture_ != kNoTimer) env().scheduler.cancel(next_capture_);
}

void VisualSensor::use_frame_worker(FrameWorker& worker, Cameras* images) {
  worker_ = &worker;
  images_ = images ? images : &cameras_;
}

// A configuration without a usable camera (none, or IDs 0 or repeated) is a
// failed initialisation: the operator sees Failure, not a sensor with no eyes.
bool VisualSensor::initialize() {
  const auto& configs = cameras_.configs();
  if (cameras_in_use_.empty()) {
    // A controller's Reset runs this again: limited like the rest of what a Reset repeats.
    log_repeated({"camera configurations refused", kNoteworthyBurst}, LogLevel::error,
                 [] { return std::string("no camera configured (IDs 1..255)"); });
    return false;
  }
  if (cameras_in_use_.size() != configs.size()) {
    log_repeated({"camera configurations refused", kNoteworthyBurst}, LogLevel::error,
                 [] { return std::string("camera IDs must be 1..255 and unique"); });
    return false;
  }
  return true;
}

VisualSensor::Camera* VisualSensor::find(std::uint8_t camera_id) {
  for (Camera& c : cameras_in_use_)
    if (c.config->id == camera_id) return &c;
  return nullptr;
}

const VisualSensor::Camera* VisualSensor::find(std::uint8_t camera_id) const {
  return const_cast<VisualSensor*>(this)->find(camera_id);
}

const CameraSettings* VisualSensor::settings(std::uint8_t camera_id) const {
  const Camera* c = find(camera_id);
  return c ? &c->settings : nullptr;
}

VisualSensor::Camera* VisualSensor::commanded_camera(const Header& h, std::uint8_t camera_id, std::string_view what) {
  Camera* c = find(camera_id);
  if (!c) {
    ++sensor_counters_.refused_unknown_camera;
    log_repeated("camera commands for no camera refused", LogLevel::warn, [&] {
      return std::string(what) + " from " + h.source.to_string() + " refused: no camera " + id_text(camera_id);
    });
  }
  return c;
}

bool VisualSensor::queried_camera_exists(const Header& h, std::uint8_t camera_id, std::string_view what) {
  if (find(camera_id)) return true;
  ++sensor_counters_.refused_unknown_camera;
  log_repeated("camera queries for no camera not answered", LogLevel::warn, [&] {
    return std::string(what) + " from " + h.source.to_string() + " for camera " + id_text(camera_id) +
           ", which does not exist: no reply";
  });
  return false;
}

// The image stream's source rate is the selected camera's frame rate; a
// connection keeps the rate it was confirmed with.
void VisualSensor::provide_images() {
  const Camera* c = find(selected_);
  provide_if<msg::ReportImage>(
      0,
      [this]() -> std::optional<msg::ReportImage> {
        if (!images_flow(state())) return std::nullopt;  // Standby pauses the stream
        const auto frame = want_frame();
        if (!frame) return std::nullopt;  // nothing captured yet
        ++sensor_counters_.images_sent;
        return *frame;
      },
      c ? c->settings.frame_rate_fps : 0);
}

std::optional<VisualSensor::FrameKey> VisualSensor::selected_key() const {
  const Camera* c = find(selected_);
  if (!c) return std::nullopt;
  return FrameKey{selected_, c->settings.image_format, c->settings.width, c->settings.height};
}

Duration VisualSensor::frame_period() const {
  const Camera* c = find(selected_);
  const std::uint16_t fps = c ? std::max<std::uint16_t>(c->settings.frame_rate_fps, 1) : 1;
  return std::chrono::duration_cast<Duration>(std::chrono::duration<double>(1.0 / fps));
}

bool VisualSensor::frame_fresh() {
  return frame_ && env().clock.now() - frame_at_ < frame_period();
}

std::shared_ptr<const msg::ReportImage> VisualSensor::want_frame() {
  const auto key = selected_key();
  if (!key) return nullptr;
  if (!(*key == key_)) {
    // Another camera, format or size: the newest frame is not one of it, and
    // the capture under way (if any) will be dropped when it is done.
    key_ = *key;
    frame_.reset();
    capturing_ = false;
    captured_before_ = false;
  }
  wanted_at_ = env().clock.now();
  if (!frame_fresh()) request_capture();
  return frame_;
}

void VisualSensor::request_capture() {
  const TimePoint now = env().clock.now();
  // At most one capture under way, and one per frame period (less an eighth
  // for timer jitter: a stream at the frame rate asks a little early at times).
  const Duration period = frame_period();
  if (capturing_ || (captured_before_ && now - capture_began_ < period - period / 8)) return;
  const Camera* c = find(key_.camera);
  if (!c) return;
  const CameraSettings& s = c->settings;
  CaptureJob job = images_->capture_job(
      key_.camera, ImageRequest{s.image_format, s.width, s.height, s.frame_rate_fps, sensor_counters_.jpeg_quality});
  const FrameKey key = key_;
  const std::uint64_t id = capture_id_ + 1;
  const bool submitted = worker_->submit(
      std::move(job), [this, key, id, alive = std::weak_ptr<char>(alive_)](Expected<Image> image) {
        if (alive.expired()) return;
        capture_done(key, id, std::move(image));
      });
  if (!submitted) {
    // The worker is full (another camera's captures, a slow disk): the newest frame serves meanwhile.
    ++sensor_counters_.captures_refused;
    log_repeated("image captures refused by a full worker", LogLevel::warn,
                 [&] { return "camera " + id_text(key_.camera) + ": frame worker full, newest frame sent again"; });
    return;
  }
  capture_id_ = id;
  capturing_ = true;
  captured_before_ = true;
  capture_began_ = now;
}

void VisualSensor::capture_done(const FrameKey& key, std::uint64_t id, Expected<Image> image) {
  if (id != capture_id_ || !capturing_) return;  // the settings changed meanwhile: not this frame
  capturing_ = false;
  std::optional<std::string> error;
  if (!image)
    error = image.error().message();
  else if (image->data.size() + 2 > kMaxLargeDataSetSize)
    error = std::to_string(image->data.size()) + " bytes, over a large data set's 1 MiB";
  std::vector<Address> waiting;
  waiting.swap(waiting_);
  if (error) {
    ++sensor_counters_.capture_errors;
    // Once per distinct error, and (a controller selecting cameras in turn repeats it) limited.
    if (capture_error_ != error)
      log_repeated({"cameras without images", kNoteworthyBurst}, LogLevel::warn,
                   [&] { return "camera " + id_text(key.camera) + ": no image: " + *error; });
    capture_error_ = error;
  } else {
    if (capture_error_)
      log_repeated({"cameras with images again", kNoteworthyBurst}, LogLevel::info,
                   [&] { return "camera " + id_text(key.camera) + ": images again"; });
    capture_error_.reset();
    if (image->format == image_format::kJpeg)
      sensor_counters_.jpeg_quality = next_jpeg_quality(sensor_counters_.jpeg_quality, image->data.size(),
                                                        env().outbox.link_bits_per_second());
    auto report = std::make_shared<msg::ReportImage>();
    report->camera_id = key.camera;
    report->image_format = image->format;
    report->data = std::move(image->data);
    frame_ = std::move(report);
    frame_at_ = capture_began_;
    ++sensor_counters_.frames_captured;
    // The Query Image senders that waited for it (not when Standby came meanwhile).
    if (images_flow(state()))
      for (const Address& to : waiting) {
        ++sensor_counters_.images_sent;
        send(to, *frame_);
      }
  }
  // Someone wants frames: the next one a frame period after this one began.
  const TimePoint now = env().clock.now();
  if (now - wanted_at_ < kKeepCapturing && next_capture_ == kNoTimer)
    next_capture_ = env().scheduler.call_at(capture_began_ + frame_period(), [this] {
      next_capture_ = kNoTimer;
      if (env().clock.now() - wanted_at_ < kKeepCapturing && images_flow(state()) && selected_key() == key_)
        request_capture();
    });
}

bool VisualSensor::query_allowed(const Address& requester) {
  const TimePoint now = env().clock.now();
  const Camera* c = find(selected_);
  const double rate = c ? std::max<std::uint16_t>(c->settings.frame_rate_fps, 1) : 1;
  const std::pair<std::uint8_t, std::uint8_t> node{requester.subsystem, requester.node};
  auto it = query_buckets_.find(node);
  if (it == query_buckets_.end()) {
    if (query_buckets_.size() >= kMaxQueryRequesters) {
      // Forget the requesters whose bucket has refilled: they are as new.
      std::erase_if(query_buckets_, [&](const auto& entry) {
        return std::chrono::duration<double>(now - entry.second.at).count() * rate >= kQueryBurst;
      });
      if (query_buckets_.size() >= kMaxQueryRequesters) return false;
    }
    it = query_buckets_.emplace(node, QueryBucket{kQueryBurst, now}).first;
  }
  QueryBucket& b = it->second;
  b.tokens = std::min(kQueryBurst, b.tokens + std::chrono::duration<double>(now - b.at).count() * rate);
  b.at = now;
  if (b.tokens < 1) return false;
  b.tokens -= 1;
  return true;
}

void VisualSensor::on_query_image(const Header& h) {
  if (!images_flow(state())) {
    ++sensor_counters_.image_queries_paused;
    log_repeated("Query Image not answered outside Ready and Emergency", LogLevel::warn, [&] {
      return "Query Image from " + h.source.to_string() + " not answered in " + std::string(to_string(state()));
    });
    return;
  }
  if (!query_allowed(h.source)) {
    ++sensor_counters_.image_queries_limited;
    log_repeated("Query Image beyond its requester's rate ignored", LogLevel::warn, [&] {
      return "Query Image from " + h.source.to_string() + " beyond the camera's frame rate: ignored";
    });
    return;
  }
  const auto frame = want_frame();
  if (frame && frame_fresh()) {
    ++sensor_counters_.images_sent;
    send(h.source, *frame);
  } else if (capturing_) {
    // Answered when the capture under way is done (never here: nothing waits).
    if (waiting_.size() < kMaxWaiting && std::find(waiting_.begin(), waiting_.end(), h.source) == waiting_.end())
      waiting_.push_back(h.source);
  } else if (frame) {
    ++sensor_counters_.images_sent;  // no capture possible now: the newest there is
    send(h.source, *frame);
  }
}

std::optional<msg::ReportCameraPose> VisualSensor::camera_pose_report(std::uint8_t camera_id) {
  const Camera* c = find(camera_id);
  if (!c) return std::nullopt;
  msg::ReportCameraPose report;
  static_cast<msg::CameraPoseReportBody&>(report) = to_camera_pose_body(*c->config, cameras_.mount_state(camera_id));
  return report;
}

std::optional<msg::ReportCameraCapabilities> VisualSensor::capabilities_report(std::uint8_t camera_id) const {
  const Camera* c = find(camera_id);
  if (!c) return std::nullopt;
  msg::ReportCameraCapabilities report;
  static_cast<msg::CameraCapabilitiesReportBody&>(report) = to_capabilities_body(*c->config, c->settings);
  return report;
}

std::optional<msg::ReportCameraFormatOptions> VisualSensor::format_report(std::uint8_t camera_id) const {
  const Camera* c = find(camera_id);
  if (!c) return std::nullopt;
  msg::ReportCameraFormatOptions report;
  static_cast<msg::CameraFormatReportBody&>(report) = to_format_body(*c->config, c->settings);
  return report;
}

void VisualSensor::on_select_camera(const Header& h, const msg::SelectCamera& m) {
  if (!commanded_camera(h, m.camera_id, msg::SelectCamera::name)) return;
  if (selected_ != m.camera_id) capture_error_.reset();
  selected_ = m.camera_id;
  ++sensor_counters_.cameras_selected;
  provide_images();
  log_repeated({"cameras selected", kNoteworthyBurst}, LogLevel::info,
               [&] { return "camera " + id_text(selected_) + " selected by " + h.source.to_string(); });
}

void VisualSensor::on_set_camera_pose(const Header& h, const msg::SetCameraPose& m) {
  Camera* c = commanded_camera(h, m.camera_id, msg::SetCameraPose::name);
  if (!c) return;
  const PoseCommand pose = to_mount_command(m, *c->config);
  if (pose.ignored)
    log_repeated("Set Camera Pose bits without an axis ignored", LogLevel::debug, [&] {
      return "Set Camera Pose from " + h.source.to_string() + ": camera " + id_text(m.camera_id) +
             " has no axis for presence bits 0x" + wire::detail::hex_u32(pose.ignored);
    });
  if (pose.command == MountCommand{}) return;
  cameras_.command_mount(m.camera_id, pose.command);
  ++sensor_counters_.poses_set;
}

void VisualSensor::on_set_capabilities(const Header& h, const msg::SetCameraCapabilities& m) {
  Camera* c = commanded_camera(h, m.camera_id, msg::SetCameraCapabilities::name);
  if (!c) return;
  const CameraSettings before = c->settings;
  c->settings = apply_capabilities(m, *c->config, c->settings);
  // The field of view is the zoom's: the horizontal one if given, else the
  // vertical one at the (new) aspect ratio.
  std::optional<double> fov = m.horizontal_fov_rad;
  if (!fov && m.vertical_fov_rad)
    fov = horizontal_from_vertical_fov_rad(*m.vertical_fov_rad, c->settings.width, c->settings.height);
  if (fov) {
    if (const auto zoom = zoom_for_fov(*c->config, *fov)) {
      MountCommand command;
      command.zoom = AxisCommand{AxisMode::position, std::clamp(*zoom, c->config->zoom.min, c->config->zoom.max)};
      cameras_.command_mount(m.camera_id, command);
    } else {
      log_repeated("Set Camera Capabilities of a fixed field of view ignored", LogLevel::debug, [&] {
        return "Set Camera Capabilities: camera " + id_text(m.camera_id) + " cannot change its FOV";
      });
    }
  }
  ++sensor_counters_.capabilities_set;
  if (c->settings.frame_rate_fps != before.frame_rate_fps && m.camera_id == selected_) provide_images();
  log_repeated({"cameras set", kNoteworthyBurst}, LogLevel::info, [&] {
    return "camera " + id_text(m.camera_id) + " set by " + h.source.to_string() + ": " +
           std::to_string(c->settings.width) + "x" + std::to_string(c->settings.height) + " at " +
           std::to_string(c->settings.frame_rate_fps) + " fps";
  });
}

void VisualSensor::on_set_format(const Header& h, const msg::SetCameraFormatOptions& m) {
  Camera* c = commanded_camera(h, m.camera_id, msg::SetCameraFormatOptions::name);
  if (!c) return;
  const auto& formats = c->config->image_formats;
  std::string refusal;
  if (m.audio_format && *m.audio_format != 0)
    refusal = "audio format " + std::to_string(*m.audio_format) + " (this camera has no audio)";
  else if (m.image_format && std::find(formats.begin(), formats.end(), *m.image_format) == formats.end())
    refusal = "image format " + std::to_string(*m.image_format);
  if (!refusal.empty()) {
    ++sensor_counters_.refused_formats;
    log_repeated("Set Camera Format Options refused", LogLevel::warn, [&] {
      return "Set Camera Format Options from " + h.source.to_string() + " refused: camera " + id_text(m.camera_id) +
             " has no " + refusal;
    });
    return;
  }
  if (!m.image_format) return;  // the format option is reserved: nothing else to do
  c->settings.image_format = *m.image_format;
  ++sensor_counters_.formats_set;
  log_repeated({"image formats set", kNoteworthyBurst}, LogLevel::info, [&] {
    return "camera " + id_text(m.camera_id) + " sends image format " + std::to_string(*m.image_format);
  });
}

// Safety: the one place the mounts are told to hold (see the header).
void VisualSensor::command_stop(std::string_view why) {
  for (const Camera& c : cameras_in_use_) cameras_.hold(c.config->id);
  // Every Standby, Emergency, release or takeover holds the mounts: limited (the hold itself is not).
  log_repeated({"camera mounts held", kNoteworthyBurst}, LogLevel::info,
               [&] { return "camera mounts held: " + std::string(why); });
}

}  // namespace jaus::components
