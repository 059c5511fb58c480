#include "jaus/bridge/clearpath_cameras.hpp"

#include "command_stream.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <deque>
#include <functional>
#include <numbers>
#include <set>
#include <sstream>
#include <utility>

namespace jaus::bridge {

namespace cp = clearpath;
using components::AxisCommand;
using components::AxisMode;
using components::CameraConfig;
using components::MountAxis;
using components::MountCommand;
using components::MountState;

using detail::CommandStream;
using detail::number_text;
using detail::outcome_text;

namespace {

constexpr double kDegPerRad = 180.0 / std::numbers::pi;
constexpr double kMountLimitDeg = 180.0;  // 0x0400 pan and tilt range
constexpr double kMaxZoomFactor = 320.0;  // 0x0400 zoom range
constexpr auto kDropLogInterval = std::chrono::seconds(1);

// One axis of a mapped mount, in JAUS units (rad, or percent for zoom).
struct AxisState {
  double min = 0, max = 0, max_rate = 0;  // the camera's limits within the mount's range
  bool movable = false;
  AxisMode mode = AxisMode::position;
  double target = 0;
  double rate = 0;  // rate mode, units per second

  // Rate mode, integrated over `seconds`: at a limit the axis stays there, in
  // position mode. A target outside the limits (the mount was there) only
  // moves back toward them.
  void integrate(double seconds) {
    if (mode != AxisMode::rate || seconds <= 0) return;
    const double next = target + rate * seconds;
    if (rate > 0 && next >= max) {
      target = std::max(target, max);
      mode = AxisMode::position;
    } else if (rate < 0 && next <= min) {
      target = std::min(target, min);
      mode = AxisMode::position;
    } else {
      target = next;
    }
  }

  void command(const AxisCommand& c, double measured) {
    if (!movable || !std::isfinite(c.value)) return;
    if (c.mode == AxisMode::position) {
      mode = AxisMode::position;
      target = std::clamp(c.value, min, max);
      rate = 0;
      return;
    }
    const double r = std::clamp(c.value, -max_rate, max_rate);
    if (mode != AxisMode::rate) target = measured;  // rate motion starts where the mount is
    if (r == 0) {
      mode = AxisMode::position;
      target = measured;
      rate = 0;
      return;
    }
    mode = AxisMode::rate;
    rate = r;
  }

  void hold(double measured) {
    mode = AxisMode::position;
    target = measured;
    rate = 0;
  }
};

// JAUS rad <-> mount degrees for one axis.
struct AngleMap {
  double sign = 1, offset_deg = 0;
  double to_mount(double rad) const { return offset_deg + sign * rad * kDegPerRad; }
  double from_mount(double deg) const { return sign * (deg - offset_deg) / kDegPerRad; }
};

// JAUS zoom percent <-> zoom factor.
struct ZoomMap {
  double min_factor = 1, max_factor = 1;
  bool has_zoom() const { return min_factor != 0 || max_factor != 0; }
  double to_mount(double percent) const {
    if (!has_zoom()) return 0;
    return min_factor + (max_factor - min_factor) * percent / 100;
  }
  double from_mount(double factor) const {
    if (!has_zoom() || max_factor == min_factor) return 0;
    return (factor - min_factor) / (max_factor - min_factor) * 100;
  }
};

// The JAUS range of a pan/tilt axis the mount can reach: [lo, hi] of the
// camera's limits within the mount's +-180 deg (lo > hi: none).
std::pair<double, double> reachable(const MountAxis& axis, const AngleMap& map) {
  double a = map.from_mount(-kMountLimitDeg), b = map.from_mount(kMountLimitDeg);
  if (a > b) std::swap(a, b);
  return {std::max(axis.min, a), std::min(axis.max, b)};
}

std::string mount_label(const ClearpathMountConfig& m) {
  return "camera " + std::to_string(m.camera_id) + " (Clearpath mount " + std::to_string(m.mount) + ")";
}

}  // namespace

Expected<void> check_clearpath_cameras_config(const std::vector<CameraConfig>& cameras,
                                              const ClearpathCamerasConfig& config) {
  const auto bad = [](std::string why) -> Expected<void> {
    return unexpected(make_error(ErrorCode::invalid_argument, std::move(why)));
  };
  if (config.data_rate_hz < 1 || config.data_rate_hz > 100)
    return bad("Clearpath cameras: data_rate_hz " + std::to_string(config.data_rate_hz) + " outside 1..100");
  if (!(config.rate_hz > 0 && config.rate_hz <= 1000))
    return bad("Clearpath cameras: rate_hz " + number_text(config.rate_hz) + " outside (0, 1000]");
  if (!(config.tolerance_deg > 0) || !std::isfinite(config.tolerance_deg))
    return bad("Clearpath cameras: tolerance_deg " + number_text(config.tolerance_deg) + " must be > 0");
  if (!(config.zoom_tolerance > 0) || !std::isfinite(config.zoom_tolerance))
    return bad("Clearpath cameras: zoom_tolerance " + number_text(config.zoom_tolerance) + " must be > 0");
  std::set<std::uint8_t> ids, mounts;
  for (const ClearpathMountConfig& m : config.mounts) {
    const std::string label = mount_label(m);
    const auto camera = std::find_if(cameras.begin(), cameras.end(),
                                     [&](const CameraConfig& c) { return c.id == m.camera_id; });
    if (camera == cameras.end()) return bad(label + ": no such camera");
    if (!ids.insert(m.camera_id).second) return bad(label + ": camera mapped twice");
    if (!mounts.insert(m.mount).second) return bad(label + ": mount used by another camera");
    if (m.pan_sign != 1 && m.pan_sign != -1) return bad(label + ": pan_sign " + number_text(m.pan_sign) + " is not +1 or -1");
    if (m.tilt_sign != 1 && m.tilt_sign != -1)
      return bad(label + ": tilt_sign " + number_text(m.tilt_sign) + " is not +1 or -1");
    if (!(std::abs(m.pan_offset_deg) <= kMountLimitDeg))
      return bad(label + ": pan_offset_deg " + number_text(m.pan_offset_deg) + " outside [-180, 180]");
    if (!(std::abs(m.tilt_offset_deg) <= kMountLimitDeg))
      return bad(label + ": tilt_offset_deg " + number_text(m.tilt_offset_deg) + " outside [-180, 180]");
    const bool no_zoom = m.zoom_min_factor == 0 && m.zoom_max_factor == 0;
    const auto factor_ok = [](double f) { return f > 0 && f <= kMaxZoomFactor; };
    if (!no_zoom && !(factor_ok(m.zoom_min_factor) && factor_ok(m.zoom_max_factor)))
      return bad(label + ": zoom factors " + number_text(m.zoom_min_factor) + ", " + number_text(m.zoom_max_factor) +
                 " must both be 0 (no zoom) or both in (0, 320]");
    const auto check_reach = [&](const char* name, const MountAxis& axis, const AngleMap& map) -> Expected<void> {
      if (!axis.movable()) return {};
      const auto [lo, hi] = reachable(axis, map);
      if (lo < hi) return {};
      return bad(label + ": " + name + " limits [" + number_text(axis.min) + ", " + number_text(axis.max) +
                 "] rad are beyond the mount's +-180 deg with this sign and offset");
    };
    if (auto ok = check_reach("pan", camera->pan, AngleMap{m.pan_sign, m.pan_offset_deg}); !ok) return ok;
    if (auto ok = check_reach("tilt", camera->tilt, AngleMap{m.tilt_sign, m.tilt_offset_deg}); !ok) return ok;
  }
  return {};
}

struct ClearpathCameras::State {
  struct Mapped {
    ClearpathMountConfig map;
    AngleMap pan_map, tilt_map;
    ZoomMap zoom_map;
    AxisState pan, tilt, zoom;
    bool have_data = false;        // a 0x8400 ever: mount_state() reports the latest
    bool fresh = false;            // a 0x8400 since the platform (last) came up: commands may go
    cp::PanTiltZoomData measured;  // the latest 0x8400 of this mount, in its units
    rt::TimePoint integrated_at{};
    std::optional<rt::TimePoint> last_drop_log;
    std::unique_ptr<CommandStream> stream;

    double measured_pan() const { return pan_map.from_mount(measured.pan); }
    double measured_tilt() const { return tilt_map.from_mount(measured.tilt); }
    double measured_zoom() const { return zoom_map.from_mount(measured.zoom); }
    bool in_rate() const {
      return pan.mode == AxisMode::rate || tilt.mode == AxisMode::rate || zoom.mode == AxisMode::rate;
    }
  };

  State(PlatformConnection& p, rt::Scheduler& s, components::Cameras& i, ClearpathCamerasConfig c)
      : platform(p), scheduler(s), images(i), config(std::move(c)) {}

  ~State() {
    if (timer != rt::kNoTimer) scheduler.cancel(timer);
  }

  PlatformConnection& platform;
  rt::Scheduler& scheduler;
  components::Cameras& images;
  ClearpathCamerasConfig config;
  std::vector<std::unique_ptr<Mapped>> mapped;
  ClearpathCamerasCounters counters;
  rt::TimerId timer = rt::kNoTimer;

  rt::TimePoint now() const { return platform.clock().now(); }
  rt::Duration period() const {
    return std::chrono::duration_cast<rt::Duration>(std::chrono::duration<double>(1.0 / config.rate_hz));
  }

  Mapped* find(std::uint8_t camera_id) {
    for (auto& m : mapped)
      if (m->map.camera_id == camera_id) return m.get();
    return nullptr;
  }
  Mapped* find_mount(std::uint8_t mount) {
    for (auto& m : mapped)
      if (m->map.mount == mount) return m.get();
    return nullptr;
  }

  void build(const std::vector<CameraConfig>& cameras) {
    for (const ClearpathMountConfig& map : config.mounts) {
      const auto camera = std::find_if(cameras.begin(), cameras.end(),
                                       [&](const CameraConfig& c) { return c.id == map.camera_id; });
      auto m = std::make_unique<Mapped>();
      m->map = map;
      m->pan_map = AngleMap{map.pan_sign, map.pan_offset_deg};
      m->tilt_map = AngleMap{map.tilt_sign, map.tilt_offset_deg};
      m->zoom_map = ZoomMap{map.zoom_min_factor, map.zoom_max_factor};
      const auto axis = [](const MountAxis& limits, std::pair<double, double> range) {
        AxisState a;
        a.movable = limits.movable() && range.first < range.second;
        a.min = range.first;
        a.max = range.second;
        a.max_rate = limits.max_rate;
        return a;
      };
      m->pan = axis(camera->pan, reachable(camera->pan, m->pan_map));
      m->tilt = axis(camera->tilt, reachable(camera->tilt, m->tilt_map));
      m->zoom = axis(camera->zoom, {camera->zoom.min, camera->zoom.max});
      // A mount without zoom, or with one factor at both ends, has no zoom to move.
      m->zoom.movable = m->zoom.movable && m->zoom_map.min_factor != m->zoom_map.max_factor;
      Mapped* raw = m.get();
      m->stream = std::make_unique<CommandStream>(
          platform.client(), counters.commands_sent,
          [this, raw](const cp::AnyMessage&, const cp::CommandOutcome& outcome) { failed(*raw, outcome); });
      mapped.push_back(std::move(m));
    }
  }

  void failed(Mapped& m, const cp::CommandOutcome& outcome) {
    ++counters.commands_failed;
    const bool was_moving = m.in_rate();
    if (was_moving) {
      // Safety: a stream of targets the platform does not take ends here.
      for (AxisState* a : {&m.pan, &m.tilt, &m.zoom})
        if (a->mode == AxisMode::rate) a->hold(a->target);
    }
    platform.log(rt::LogLevel::warn, mount_label(m.map) + ": Set Pan Tilt Zoom not applied (" +
                                         outcome_text(outcome) + ")" + (was_moving ? "; rate motion ended" : ""));
  }

  void drop(Mapped* m, std::uint8_t camera_id, const std::string& why) {
    ++counters.commands_dropped;
    if (m != nullptr) {
      const rt::TimePoint t = now();
      if (m->last_drop_log && t - *m->last_drop_log < kDropLogInterval) return;  // one line a second
      m->last_drop_log = t;
    }
    platform.log(rt::LogLevel::warn, (m ? mount_label(m->map) : "camera " + std::to_string(camera_id)) +
                                         ": mount command dropped: " + why);
  }

  // Rate axes integrated up to now.
  void advance(Mapped& m) {
    const rt::TimePoint t = now();
    const double seconds = std::chrono::duration<double>(t - m.integrated_at).count();
    m.integrated_at = t;
    m.pan.integrate(seconds);
    m.tilt.integrate(seconds);
    m.zoom.integrate(seconds);
  }

  void send(Mapped& m) {
    cp::SetPanTiltZoom c;
    c.mount = m.map.mount;
    c.pan = std::clamp(m.pan_map.to_mount(m.pan.target), -kMountLimitDeg, kMountLimitDeg);
    c.tilt = std::clamp(m.tilt_map.to_mount(m.tilt.target), -kMountLimitDeg, kMountLimitDeg);
    c.zoom = std::clamp(m.zoom_map.to_mount(m.zoom.target), 0.0, kMaxZoomFactor);
    m.stream->post(c, true);
  }

  void command(Mapped* m, std::uint8_t camera_id, const MountCommand& command) {
    if (!platform.alive()) return drop(m, camera_id, "the Clearpath platform is not alive");
    if (!m->fresh) return drop(m, camera_id, "no pan/tilt/zoom data (0x8400) from the mount yet");
    advance(*m);
    if (command.pan) m->pan.command(*command.pan, m->measured_pan());
    if (command.tilt) m->tilt.command(*command.tilt, m->measured_tilt());
    if (command.zoom) m->zoom.command(*command.zoom, m->measured_zoom());
    send(*m);
    if (m->in_rate()) start_timer();
  }

  void hold(Mapped& m) {
    if (!m.have_data) {  // nothing was ever sent to it: nothing to stop
      for (AxisState* a : {&m.pan, &m.tilt, &m.zoom}) a->hold(a->target);
      return;
    }
    m.pan.hold(m.measured_pan());
    m.tilt.hold(m.measured_tilt());
    m.zoom.hold(m.measured_zoom());
    // Not since the platform came up: it holds its last target; nothing goes out.
    if (!m.fresh || !platform.alive()) return;
    m.stream->clear();
    cp::SetPanTiltZoom c;  // exactly where it was measured, in its own units
    c.mount = m.map.mount;
    c.pan = m.measured.pan;
    c.tilt = m.measured.tilt;
    c.zoom = m.zoom_map.has_zoom() ? m.measured.zoom : 0.0;
    m.stream->post(c, true);
  }

  void start_timer() {
    if (timer != rt::kNoTimer) return;
    timer = scheduler.call_at(now() + period(), [this] { tick(); });
  }

  void tick() {
    timer = rt::kNoTimer;
    bool again = false;
    for (auto& m : mapped) {
      if (!m->in_rate()) continue;
      advance(*m);
      send(*m);
      again = again || m->in_rate();
    }
    if (again) start_timer();
  }

  void on_data(const cp::PanTiltZoomData& d) {
    Mapped* m = find_mount(d.mount);
    if (m == nullptr) return;
    ++counters.mount_data;
    m->measured = d;
    m->have_data = true;
    if (!m->fresh) {  // the targets start where the mount is
      m->fresh = true;
      m->integrated_at = now();
      m->pan.hold(m->measured_pan());
      m->tilt.hold(m->measured_tilt());
      m->zoom.hold(m->measured_zoom());
    }
  }

  void on_alive(bool alive) {
    if (alive) return;  // commands wait for the mounts' next data
    bool moving = false;
    for (auto& m : mapped) {
      moving = moving || m->in_rate();
      m->fresh = false;
      m->stream->clear();
      if (m->have_data) {  // what is known of it is where it was last measured
        m->pan.hold(m->measured_pan());
        m->tilt.hold(m->measured_tilt());
        m->zoom.hold(m->measured_zoom());
      }
    }
    if (timer != rt::kNoTimer) scheduler.cancel(timer);
    timer = rt::kNoTimer;
    if (moving) platform.log(rt::LogLevel::warn, "camera mounts: Clearpath platform lost; rate motion ended");
  }

  MountState state(const Mapped& m) const {
    if (!m.have_data) return {};
    MountState s{m.measured_pan(), m.measured_tilt(), m.measured_zoom(), m.in_rate()};
    const auto off = [](bool movable, double target, double measured, double tolerance) {
      return movable && std::abs(target - measured) > tolerance;
    };
    s.moving = s.moving ||
               off(m.pan.movable, m.pan_map.to_mount(m.pan.target), m.measured.pan, config.tolerance_deg) ||
               off(m.tilt.movable, m.tilt_map.to_mount(m.tilt.target), m.measured.tilt, config.tolerance_deg) ||
               off(m.zoom.movable, m.zoom_map.to_mount(m.zoom.target), m.measured.zoom, config.zoom_tolerance);
    return s;
  }
};

Expected<std::unique_ptr<ClearpathCameras>> ClearpathCameras::make(PlatformConnection& platform,
                                                                   rt::Scheduler& scheduler, components::Cameras& images,
                                                                   ClearpathCamerasConfig config) {
  if (auto ok = check_clearpath_cameras_config(images.configs(), config); !ok) return unexpected(ok.error());
  return std::unique_ptr<ClearpathCameras>(new ClearpathCameras(platform, scheduler, images, std::move(config)));
}

ClearpathCameras::ClearpathCameras(PlatformConnection& platform, rt::Scheduler& scheduler,
                                   components::Cameras& images, ClearpathCamerasConfig config)
    : state_(std::make_shared<State>(platform, scheduler, images, std::move(config))) {
  State& s = *state_;
  s.build(images.configs());
  std::weak_ptr<State> weak = state_;
  platform.on_data(cp::PanTiltZoomData::kType, [weak](const cp::Envelope& e) {
    const auto self = weak.lock();
    if (!self) return;
    if (const auto* d = e.message.get_if<cp::PanTiltZoomData>()) self->on_data(*d);
  });
  platform.on_alive([weak](bool alive) {
    if (const auto self = weak.lock()) self->on_alive(alive);
  });
  for (const auto& m : s.mapped) {
    cp::RequestPanTiltZoom request;
    request.subscription = s.config.data_rate_hz;
    request.mount = m->map.mount;
    const std::string label = mount_label(m->map);
    platform.client().subscribe(request, [weak, label](const cp::CommandOutcome& outcome) {
      const auto self = weak.lock();
      if (!self || outcome.ok()) return;
      self->platform.log(rt::LogLevel::warn, label + ": pan/tilt/zoom subscription (0x4400) not applied (" +
                                                 detail::subscription_outcome_text(outcome) + ")");
    });
  }
}

ClearpathCameras::~ClearpathCameras() = default;

const std::vector<CameraConfig>& ClearpathCameras::configs() const { return state_->images.configs(); }

void ClearpathCameras::command_mount(std::uint8_t camera_id, const MountCommand& command) {
  State& s = *state_;
  State::Mapped* m = s.find(camera_id);
  if (m == nullptr) return s.images.command_mount(camera_id, command);  // unmapped: the inner source's
  s.command(m, camera_id, command);
}

void ClearpathCameras::hold(std::uint8_t camera_id) {
  State& s = *state_;
  if (State::Mapped* m = s.find(camera_id)) return s.hold(*m);
  s.images.hold(camera_id);
}

MountState ClearpathCameras::mount_state(std::uint8_t camera_id) {
  State& s = *state_;
  if (const State::Mapped* m = s.find(camera_id)) return s.state(*m);
  return s.images.mount_state(camera_id);
}

Expected<components::Image> ClearpathCameras::capture(std::uint8_t camera_id,
                                                      const components::ImageRequest& request) {
  return state_->images.capture(camera_id, request);
}

const ClearpathCamerasConfig& ClearpathCameras::config() const { return state_->config; }
const ClearpathCamerasCounters& ClearpathCameras::counters() const { return state_->counters; }

}  // namespace jaus::bridge
