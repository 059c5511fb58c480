// Components of the kinds the per-kind cases test (primitive driver, pose
// sensor, visual sensor, manipulator), each broken in one way that one case
// must catch, and otherwise as small as the cases allow. They live on the
// broken node (broken_components.hpp), each at its own address:
//   3.1.53.1 driver that executes Set Wrench Effort from anyone
//   3.1.54.1 driver that stores no effort (reports zero)
//   3.1.55.1 driver that keeps its effort through a stop
//   3.1.56.1 driver that resumes the latched effort when back in Ready
//   3.1.57.1 pose sensor whose time stamp never advances
//   3.1.58.1 pose sensor that echoes the presence vector of a query
//   3.1.59.1 pose sensor whose service connections report another latitude
//   3.1.60.1 visual sensor that ignores Select Camera
//   3.1.61.1 visual sensor that takes Select Camera from anyone
//   3.1.62.1 visual sensor that sends PNG images labelled JPEG, which it does not advertise
//   3.1.63.1 manipulator that executes the joints within limits of a command that has one out of range
//   3.1.64.1 manipulator that takes Set Joint Velocities from anyone
//   3.1.65.1 manipulator that keeps moving through a stop
//   3.1.66.1 manipulator whose Report Joint Velocities lists one joint too many
//   3.1.73.1 driver that keeps its effort through a Reset
//   3.1.74.1 driver that keeps its effort when a higher authority takes control over
//   3.1.75.1 manipulator that keeps moving when its controller releases control
#pragma once

#include <cmath>
#include <string_view>
#include <vector>

#include "jaus/messages/all.hpp"
#include "jaus/runtime/component.hpp"

namespace jaus::conform::test {

inline const Address kDriverObeysAnyone{3, 1, 53, 1};
inline const Address kDriverForgetsEffort{3, 1, 54, 1};
inline const Address kDriverKeepsEffortOnStop{3, 1, 55, 1};
inline const Address kDriverResumesLatchedEffort{3, 1, 56, 1};
inline const Address kSensorFrozenTime{3, 1, 57, 1};
inline const Address kSensorEchoesQueryPresence{3, 1, 58, 1};
inline const Address kSensorScElsewhere{3, 1, 59, 1};
inline const Address kCamerasIgnoreSelection{3, 1, 60, 1};
inline const Address kCamerasObeyAnyone{3, 1, 61, 1};
inline const Address kCamerasMislabelFormat{3, 1, 62, 1};
inline const Address kArmExecutesPartly{3, 1, 63, 1};
inline const Address kArmObeysAnyone{3, 1, 64, 1};
inline const Address kArmKeepsMovingOnStop{3, 1, 65, 1};
inline const Address kArmMiscountsJoints{3, 1, 66, 1};
inline const Address kDriverKeepsEffortOnReset{3, 1, 73, 1};
inline const Address kDriverKeepsEffortOnTakeover{3, 1, 74, 1};
inline const Address kArmKeepsMovingOnRelease{3, 1, 75, 1};

// The reason the runtime gives command_stop() when control changes hands or
// is released (component.cpp): the flaws below that keep going on one stop
// path alone tell the paths apart by it.
inline constexpr std::string_view kTakeoverStop = "control changed hands";
inline constexpr std::string_view kReleaseStop = "control released";

enum class DriverFlaw {
  obeys_anyone,
  forgets_effort,
  keeps_effort_on_stop,
  resumes_latched_effort,
  keeps_effort_on_reset,
  keeps_effort_on_takeover
};

class BrokenDriver final : public rt::Component {
 public:
  BrokenDriver(rt::ComponentConfig config, rt::Environment env, DriverFlaw flaw)
      : Component(std::move(config), std::move(env)), flaw_(flaw) {
    const bool anyone = flaw == DriverFlaw::obeys_anyone;
    handle<msg::SetWrenchEffort>(anyone ? Access::anyone : Access::controller, !anyone,
                                 [this](const Header&, const msg::SetWrenchEffort& m) {
                                   if (flaw_ == DriverFlaw::forgets_effort) return;
                                   effort_ = m.propulsive_linear_effort_x_percent.value_or(effort_);
                                   latched_ = effort_;
                                 });
    handle<msg::QueryWrenchEffort>(Access::anyone, false, [this](const Header& h, const msg::QueryWrenchEffort& q) {
      auto report = this->report();
      wire::mask_presence(report, q.presence_vector);
      send(h.source, report);
    });
    provide<msg::ReportWrenchEffort>(0x0001, [this] { return report(); });
  }

 protected:
  void command_stop(std::string_view why) override {
    if (flaw_ == DriverFlaw::keeps_effort_on_stop) return;
    if (flaw_ == DriverFlaw::keeps_effort_on_reset && state() == rt::PrimaryStatus::initialize) return;
    if (flaw_ == DriverFlaw::keeps_effort_on_takeover && why == kTakeoverStop) return;
    effort_ = 0;
  }
  void state_changed(rt::PrimaryStatus, rt::PrimaryStatus after) override {
    if (flaw_ == DriverFlaw::resumes_latched_effort && after == rt::PrimaryStatus::ready) effort_ = latched_;
  }

 private:
  msg::ReportWrenchEffort report() const {
    msg::ReportWrenchEffort r;
    r.propulsive_linear_effort_x_percent = effort_;
    return r;
  }

  DriverFlaw flaw_;
  double effort_ = 0;
  double latched_ = 0;
};

enum class SensorFlaw { frozen_time, echoes_query_presence, sc_elsewhere };

// Latitude .. yaw and the time stamp, no attitude RMS.
class BrokenPoseSensor final : public rt::Component {
 public:
  static constexpr std::uint32_t kAvailable = 0x17F;

  BrokenPoseSensor(rt::ComponentConfig config, rt::Environment env, SensorFlaw flaw)
      : Component(std::move(config), std::move(env)), flaw_(flaw), started_(this->env().clock.now()) {
    handle<msg::QueryGlobalPose>(Access::anyone, false, [this](const Header& h, const msg::QueryGlobalPose& q) {
      auto report = sample();
      if (flaw_ == SensorFlaw::echoes_query_presence) report.attitude_rms_rad = 0.1;  // then not ANDed
      wire::mask_presence(report, q.presence_vector);
      send(h.source, report);
    });
    provide<msg::ReportGlobalPose>(kAvailable, [this] {
      auto report = sample();
      if (flaw_ == SensorFlaw::sc_elsewhere) *report.latitude_deg += 0.01;
      return report;
    });
  }

 private:
  msg::ReportGlobalPose sample() {
    msg::ReportGlobalPose p;
    p.latitude_deg = 45.5;
    p.longitude_deg = -73.6;
    p.elevation_m = 30;
    p.position_rms_m = 1;
    p.roll_rad = 0;
    p.pitch_rad = 0;
    p.yaw_rad = 1;
    const auto ms = flaw_ == SensorFlaw::frozen_time
                        ? 0
                        : std::chrono::duration_cast<std::chrono::milliseconds>(env().clock.now() - started_).count();
    p.time_stamp = TimeStamp{static_cast<std::uint16_t>(ms % 1000), static_cast<std::uint8_t>(ms / 1000 % 60),
                             static_cast<std::uint8_t>(ms / 60'000 % 60), 0, 1};
    return p;
  }

  SensorFlaw flaw_;
  rt::TimePoint started_;
};

enum class CamerasFlaw { ignores_selection, obeys_anyone, mislabels_format };

// Two cameras, PNG only.
class BrokenCameras final : public rt::Component {
 public:
  BrokenCameras(rt::ComponentConfig config, rt::Environment env, CamerasFlaw flaw)
      : Component(std::move(config), std::move(env)), flaw_(flaw) {
    const bool anyone = flaw == CamerasFlaw::obeys_anyone;
    handle<msg::SelectCamera>(anyone ? Access::anyone : Access::controller, !anyone,
                              [this](const Header&, const msg::SelectCamera& m) {
                                if (flaw_ != CamerasFlaw::ignores_selection && m.camera_id >= 1 && m.camera_id <= 2)
                                  selected_ = m.camera_id;
                              });
    handle<msg::QueryCameraCount>(Access::anyone, false, [this](const Header& h, const msg::QueryCameraCount&) {
      send(h.source, msg::ReportCameraCount{{2}});
    });
    handle<msg::QuerySelectedCamera>(Access::anyone, false, [this](const Header& h, const msg::QuerySelectedCamera&) {
      send(h.source, msg::ReportSelectedCamera{{selected_}});
    });
    handle<msg::QueryCameraFormatOptions>(Access::anyone, false,
                                          [this](const Header& h, const msg::QueryCameraFormatOptions& q) {
                                            msg::ReportCameraFormatOptions r;
                                            r.camera_id = q.camera_id;
                                            r.image_format_1 = kPng;
                                            send(h.source, r);
                                          });
    handle<msg::QueryImage>(Access::anyone, false, [this](const Header& h, const msg::QueryImage&) {
      msg::ReportImage image;
      image.camera_id = selected_;
      image.image_format = flaw_ == CamerasFlaw::mislabels_format ? kJpeg : kPng;
      image.data = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n', 'I', 'E', 'N', 'D', 0xAE, 0x42, 0x60, 0x82};
      send(h.source, image);
    });
  }

 private:
  static constexpr std::uint8_t kJpeg = 7;
  static constexpr std::uint8_t kPng = 11;
  CamerasFlaw flaw_;
  std::uint8_t selected_ = 1;
};

enum class ArmFlaw { executes_partly, obeys_anyone, keeps_moving_on_stop, miscounts_joints, keeps_moving_on_release };

// Three revolute joints, 1 rad/s each, moved by velocity; positions advance
// with the node's clock when asked for.
class BrokenArm final : public rt::Component {
 public:
  static constexpr std::size_t kJoints = 3;
  static constexpr double kMaxVelocity = 1.0;

  BrokenArm(rt::ComponentConfig config, rt::Environment env, ArmFlaw flaw)
      : Component(std::move(config), std::move(env)), flaw_(flaw), last_(this->env().clock.now()) {
    const bool anyone = flaw == ArmFlaw::obeys_anyone;
    handle<msg::SetJointVelocities>(
        anyone ? Access::anyone : Access::controller, !anyone, [this](const Header&, const msg::SetJointVelocities& m) {
          if (m.velocities_rps.size() != kJoints) return;
          advance();
          bool over = false;
          for (double v : m.velocities_rps) over = over || std::fabs(v) > kMaxVelocity;
          if (over && flaw_ != ArmFlaw::executes_partly) return;  // refused whole
          for (std::size_t j = 0; j < kJoints; ++j)
            velocities_[j] = std::fabs(m.velocities_rps[j]) > kMaxVelocity ? 0 : m.velocities_rps[j];
        });
    handle<msg::SetJointPositions>(Access::controller, true, [this](const Header&, const msg::SetJointPositions& m) {
      if (m.positions_rad.size() != kJoints) return;
      positions_ = m.positions_rad;  // there at once
      velocities_.assign(kJoints, 0.0);
      last_ = this->env().clock.now();
    });
    handle<msg::QueryManipulatorSpecifications>(
        Access::anyone, false,
        [this](const Header& h, const msg::QueryManipulatorSpecifications&) { send(h.source, specifications()); });
    handle<msg::QueryJointPositions>(Access::anyone, false, [this](const Header& h, const msg::QueryJointPositions&) {
      advance();
      send(h.source, msg::ReportJointPositions{{positions_}});
    });
    handle<msg::QueryJointVelocities>(Access::anyone, false, [this](const Header& h, const msg::QueryJointVelocities&) {
      auto listed = velocities_;
      if (flaw_ == ArmFlaw::miscounts_joints) listed.push_back(0);
      send(h.source, msg::ReportJointVelocities{{listed}});
    });
  }

 protected:
  void command_stop(std::string_view why) override {
    advance();
    if (flaw_ == ArmFlaw::keeps_moving_on_stop) return;
    if (flaw_ == ArmFlaw::keeps_moving_on_release && why == kReleaseStop) return;
    velocities_.assign(kJoints, 0.0);
  }

 private:
  void advance() {
    const double dt = std::chrono::duration<double>(env().clock.now() - last_).count();
    last_ = env().clock.now();
    for (std::size_t j = 0; j < kJoints; ++j) positions_[j] += velocities_[j] * dt;
  }
  static msg::ReportManipulatorSpecifications specifications() {
    msg::ReportManipulatorSpecifications s;
    s.joint_count = kJoints;
    s.last_joint_max_rad_or_m = 3;
    s.last_joint_max_velocity_rps_or_mps = kMaxVelocity;
    msg::ManipulatorJointSpec joint;
    joint.link_length_m = 0.3;
    joint.max_rad_or_m = 3;
    joint.max_velocity_rps_or_mps = kMaxVelocity;
    s.joints.assign(kJoints - 1, joint);
    return s;
  }

  ArmFlaw flaw_;
  rt::TimePoint last_;
  std::vector<double> positions_ = std::vector<double>(kJoints, 0.0);
  std::vector<double> velocities_ = std::vector<double>(kJoints, 0.0);
};

}  // namespace jaus::conform::test
