// The default backend of the visual sensor: the configured cameras, each on a
// simulated pan/tilt/zoom mount, each showing the test pattern
// (test_pattern.hpp) or playing a directory of images (image_directory.hpp).
//
// Time: the mounts read the injected clock and move lazily, whenever they are
// asked or told anything, from the last time up to now (their motion is
// piecewise linear, so this is exact for any gap); the frame shown is frame
// number floor(t * frame rate), t from construction. So under VirtualTime
// everything is deterministic, and nothing needs a timer. A command takes
// effect from the moment it arrives.
//
// Motion: a position command goes to its target at the axis' max_rate; a
// rate command moves at its rate (at most max_rate) until the axis' limit,
// where it stays, or a new command. Targets are clipped to [min, max];
// NaN and infinities are ignored. An axis that is not movable never moves.
// Mounts start at home (0 clipped to [min, max]).
#pragma once

#include <memory>

#include "jaus/base/time.hpp"
#include "jaus/components/camera.hpp"

namespace jaus::components {

class SimulatedCameras final : public Cameras {
 public:
  SimulatedCameras(VisualSensorConfig config, const rt::Clock& clock);
  ~SimulatedCameras() override;
  SimulatedCameras(const SimulatedCameras&) = delete;
  SimulatedCameras& operator=(const SimulatedCameras&) = delete;

  const std::vector<CameraConfig>& configs() const override;
  void command_mount(std::uint8_t camera_id, const MountCommand& command) override;
  void hold(std::uint8_t camera_id) override;
  MountState mount_state(std::uint8_t camera_id) override;
  // The test pattern in the requested format (PNG or JPEG) and size, or the
  // directory's file of this frame as it is. An unknown camera, a format
  // other than PNG/JPEG or an unreadable directory is an error.
  Expected<Image> capture(std::uint8_t camera_id, const ImageRequest& request) override;
  // The same frame (the one shown now), encoded or read by whoever runs the
  // job: the test pattern's job holds the frame number and the request; a
  // directory's shares the directory behind a lock with capture().
  CaptureJob capture_job(std::uint8_t camera_id, const ImageRequest& request) override;

  // The frame number a camera at `frame_rate_fps` shows now.
  std::uint64_t frame_number(std::uint16_t frame_rate_fps) const;

 private:
  struct Camera;
  Camera* find(std::uint8_t camera_id);

  VisualSensorConfig config_;
  const rt::Clock& clock_;
  rt::TimePoint start_;
  std::vector<std::unique_ptr<Camera>> cameras_;
};

}  // namespace jaus::components
