#include "jaus/host/model_platform.hpp"

#include <boost/asio/post.hpp>

namespace jaus::host {

ModelPlatform::ModelPlatform(SimulationSettings simulation, PlatformEnvironment environment)
    : simulation_(std::move(simulation)), environment_(std::move(environment)) {}

ModelPlatform::~ModelPlatform() { stop(); }

Expected<void> ModelPlatform::provide(std::string_view interface, rt::Backends& backends) {
  if (interface == components::Drive::kInterface || interface == components::PoseSource::kInterface) {
    if (!vehicle_) vehicle_ = std::make_unique<components::SimulatedVehicle>(simulation_.vehicle, environment_.clock);
    backends.offer<components::Drive>(vehicle_.get());
    backends.offer<components::PoseSource>(vehicle_.get());
  } else if (interface == components::Cameras::kInterface || interface == components::FrameWorker::kInterface) {
    if (!cameras_) {
      cameras_ = std::make_unique<components::SimulatedCameras>(simulation_.cameras, environment_.clock);
      if (environment_.io != nullptr) {
        // boost::asio::post (not AsioRuntime::post, which is the loop's
        // alone) brings each frame back from the thread.
        auto thread = std::make_unique<components::ThreadFrameWorker>(
            [io = environment_.io](std::function<void()> fn) { boost::asio::post(*io, std::move(fn)); });
        frame_thread_ = thread.get();
        frame_worker_ = std::move(thread);
      } else {
        frame_worker_ = std::make_unique<components::ScheduledFrameWorker>(environment_.scheduler, environment_.clock);
      }
    }
    backends.offer<components::Cameras>(cameras_.get());
    backends.offer<components::Cameras>("camera_images", cameras_.get());
    backends.offer<components::FrameWorker>(frame_worker_.get());
  } else if (interface == components::ManipulatorArm::kInterface) {
    if (!arm_) arm_ = std::make_unique<components::SimulatedArm>(simulation_.arm, environment_.clock);
    backends.offer<components::ManipulatorArm>(arm_.get());
  }
  // Anything else this platform does not have: the kind that needs it says so.
  return {};
}

void ModelPlatform::stop() {
  if (frame_thread_ != nullptr) frame_thread_->stop();
}

const PlatformKind& model_platform_kind() {
  static const PlatformKind kind{
      .name = "model",
      .written = "model",
      .options = {},
      .check = {},
      .make = [](const PlatformSettings&, const SimulationSettings& simulation,
                 PlatformEnvironment environment) -> Expected<std::unique_ptr<Platform>> {
        return std::unique_ptr<Platform>(std::make_unique<ModelPlatform>(simulation, std::move(environment)));
      }};
  return kind;
}

}  // namespace jaus::host
