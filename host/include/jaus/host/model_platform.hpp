// The `model` platform: the components' own simulated vehicle, cameras and
// arm, called directly (no protocol), on the host's clock. The visual
// sensor's frames are encoded off the loop: on a thread of the platform's own
// when the host has an io_context to post results back to, on the scheduler
// otherwise (an attached host, under virtual time).
#pragma once

#include <memory>

#include "jaus/components/frame_worker.hpp"
#include "jaus/components/simulated_arm.hpp"
#include "jaus/components/simulated_cameras.hpp"
#include "jaus/components/simulated_vehicle.hpp"
#include "jaus/host/platform.hpp"
#include "jaus/host/platform_kinds.hpp"

namespace jaus::host {

class ModelPlatform final : public Platform {
 public:
  ModelPlatform(SimulationSettings simulation, PlatformEnvironment environment);
  ~ModelPlatform() override;
  ModelPlatform(const ModelPlatform&) = delete;
  ModelPlatform& operator=(const ModelPlatform&) = delete;

  Expected<void> provide(std::string_view interface, rt::Backends& backends) override;
  void stop() override;  // the frame thread ends, dropping what is queued

  // Each made once a component needs it; nullptr until then.
  components::SimulatedVehicle* vehicle() { return vehicle_.get(); }
  components::SimulatedCameras* cameras() { return cameras_.get(); }
  components::FrameWorker* frame_worker() { return frame_worker_.get(); }
  components::SimulatedArm* arm() { return arm_.get(); }

 private:
  SimulationSettings simulation_;
  PlatformEnvironment environment_;
  std::unique_ptr<components::SimulatedVehicle> vehicle_;
  std::unique_ptr<components::SimulatedCameras> cameras_;
  std::unique_ptr<components::SimulatedArm> arm_;
  // After the cameras: destroyed (its thread joined) before they go.
  std::unique_ptr<components::FrameWorker> frame_worker_;
  components::ThreadFrameWorker* frame_thread_ = nullptr;  // frame_worker_, when it is a thread
};

// The kind `model` (written `model`, no options): a ModelPlatform.
const PlatformKind& model_platform_kind();

}  // namespace jaus::host
