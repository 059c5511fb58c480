// The Clearpath backend of the visual sensor's cameras: each mapped camera's
// pan/tilt/zoom is a Clearpath pan-tilt-zoom mount; its images still come
// from an inner image source (the component's SimulatedCameras: the Clearpath
// protocol carries no images), which configs() and capture() delegate to. A
// camera with no mapping is the inner source's, mount and all.
//
// Units. JAUS side (camera.hpp): pan in rad, positive right; tilt in rad,
// positive up; both 0 at the camera's home direction; zoom in percent of the
// lens range, 0 widest, 100 narrowest. Clearpath side (0x0400 / 0x8400): pan
// and tilt in degrees, [-180, 180], in the mount's own sense; zoom a factor,
// [0, 320], 0 meaning "this mount has no zoom". For one mapping:
//   mount pan  (deg) = pan_offset_deg  + pan_sign  * JAUS pan  (rad -> deg)
//   mount tilt (deg) = tilt_offset_deg + tilt_sign * JAUS tilt (rad -> deg)
//   zoom factor      = zoom_min_factor + (zoom_max_factor - zoom_min_factor) * zoom % / 100
//                      (0 when both factors are 0: no zoom)
// and back the same way for the mount's reports.
//
// Commands (0x0400 Set Pan Tilt Zoom: all three axes at once, so an axis a
// command leaves out keeps its current target):
// - Position mode: the target, clipped to the camera's configured limits
//   (CameraConfig) and to the mount's +-180 deg, is sent once; the mount
//   moves at its own speed (Clearpath has no speed field).
// - Rate mode is integrated: Clearpath has no rate command, so the rate
//   (clipped to the axis' max_rate) is integrated on the runtime's scheduler
//   into a position target sent every 1 / rate_hz, from where the mount was
//   measured when the rate command arrived, until the axis' limit (where the
//   axis stays, in position mode), a new command or hold().
// - hold(): rate motion ends and the mount's last measured position (0x8400)
//   is sent as its target.
// - Before the first 0x8400 of a mount since the platform came up, and while
//   it is not alive, a mount command is dropped and logged (an axis left out
//   of a command would have no known target); losing the platform ends rate
//   motion, and mount_state() keeps reporting the last 0x8400.
// Each mount's commands go out one at a time with ACK (Client::send), newest
// target first: a waiting target is replaced by a newer one, so a retried
// old target never overtakes a new one. A refused or failed command is logged
// (one line with the reason) and ends that mount's rate motion.
//
// State: mount_state() converts the latest 0x8400 of the camera's mount
// (subscribed per mount, request 0x4400 at data_rate_hz); moving = an axis is
// in rate mode, or the measured pan/tilt is farther than tolerance_deg (zoom:
// zoom_tolerance) from the target. Before any data: all zero, not moving.
//
// Time: every timer is on the injected rt::Scheduler and clock
// (PlatformConnection::clock()). Nothing throws.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "jaus/base/expected.hpp"
#include "jaus/base/time.hpp"
#include "jaus/bridge/platform_connection.hpp"
#include "jaus/components/camera.hpp"

namespace jaus::bridge {

// Where one JAUS camera's mount is on the platform, and how its axes map.
struct ClearpathMountConfig {
  std::uint8_t camera_id = 1;  // the JAUS camera (CameraConfig::id)
  std::uint8_t mount = 0;      // the Clearpath mount index (0x0400, 0x4400, 0x8400)
  double pan_sign = 1;         // +1: mount pan grows with JAUS pan (turning right); -1: the other way
  double tilt_sign = 1;        // +1: mount tilt grows with JAUS tilt (looking up); -1: the other way
  double pan_offset_deg = 0;   // mount pan at JAUS pan 0 (the camera's home), [-180, 180]
  double tilt_offset_deg = 0;  // mount tilt at JAUS tilt 0, [-180, 180]
  // Zoom factor at JAUS zoom 0 % (widest) and 100 % (narrowest), each in
  // (0, 320]; both 0: the mount has no zoom (0 is sent, 0 % reported); equal
  // (the default, 1x): a fixed zoom (zoom commands are ignored, 0 % reported).
  double zoom_min_factor = 1;
  double zoom_max_factor = 1;
};

struct ClearpathCamerasConfig {
  std::vector<ClearpathMountConfig> mounts;  // a camera at most once, a mount at most once
  std::uint16_t data_rate_hz = 20;           // 0x4400 subscription per mount, 1..100 Hz
  double rate_hz = 20;                       // rate mode: targets sent per second, (0, 1000]
  double tolerance_deg = 0.5;                // mount_state().moving: pan/tilt off target by more (> 0)
  double zoom_tolerance = 0.05;              // ... zoom factor off target by more (> 0)
};

// Whether `config` can drive `cameras` (the inner source's configs()): every
// camera_id is one of them, no camera or mount twice, signs +-1, offsets in
// [-180, 180] deg, zoom factors both 0 or both in (0, 320], the rates and
// tolerances in range, and each movable pan/tilt axis' limits reachable
// within the mount's +-180 deg. The error names the first offending entry.
Expected<void> check_clearpath_cameras_config(const std::vector<components::CameraConfig>& cameras,
                                              const ClearpathCamerasConfig& config);

struct ClearpathCamerasCounters {
  std::uint64_t commands_sent = 0;     // 0x0400 handed to the client
  std::uint64_t commands_failed = 0;   // refused by the platform, unanswered, or link down
  std::uint64_t commands_dropped = 0;  // mount commands not sent: no data yet, platform not alive
  std::uint64_t mount_data = 0;        // 0x8400 received for a mapped mount
};

class ClearpathCameras final : public components::Cameras {
 public:
  // `images` serves configs() and capture() (and the mounts of unmapped
  // cameras); it must outlive this. Subscribes to every mapped mount at once
  // (the client keeps subscriptions across reconnects). An invalid `config`
  // (check_clearpath_cameras_config against images.configs()) is the error,
  // and no cameras: none exist in an invalid state.
  static Expected<std::unique_ptr<ClearpathCameras>> make(PlatformConnection& platform, rt::Scheduler& scheduler,
                                                          components::Cameras& images, ClearpathCamerasConfig config);
  ~ClearpathCameras() override;
  ClearpathCameras(const ClearpathCameras&) = delete;
  ClearpathCameras& operator=(const ClearpathCameras&) = delete;

  const std::vector<components::CameraConfig>& configs() const override;
  void command_mount(std::uint8_t camera_id, const components::MountCommand& command) override;
  void hold(std::uint8_t camera_id) override;
  components::MountState mount_state(std::uint8_t camera_id) override;
  Expected<components::Image> capture(std::uint8_t camera_id, const components::ImageRequest& request) override;

  const ClearpathCamerasConfig& config() const;
  const ClearpathCamerasCounters& counters() const;

 private:
  struct State;
  // `config` checked (make).
  ClearpathCameras(PlatformConnection& platform, rt::Scheduler& scheduler, components::Cameras& images,
                   ClearpathCamerasConfig config);
  std::shared_ptr<State> state_;  // shared with the client's callbacks, which hold it weakly
};

}  // namespace jaus::bridge
