// Forward kinematics against poses computed by hand, the Jacobian against
// finite differences, and inverse kinematics round trips.
#include <gtest/gtest.h>

#include <cmath>

#include "arms.hpp"
#include "jaus/components/kinematics.hpp"

namespace jaus::test {
namespace {

using namespace components::kinematics;

void expect_near(const Vec3& a, const Vec3& b, double tol = 1e-9) {
  EXPECT_NEAR(a.x, b.x, tol);
  EXPECT_NEAR(a.y, b.y, tol);
  EXPECT_NEAR(a.z, b.z, tol);
}

void expect_orientation(const Rotation& r, const Quaternion& q, double tol = 1e-9) {
  EXPECT_NEAR(norm(rotation_error(r, to_rotation(q))), 0, tol);
}

TEST(Kinematics, QuaternionsAndRotationsRoundTrip) {
  const Quaternion q{0.5, 0.5, -0.5, 0.5};
  const Quaternion back = to_quaternion(to_rotation(q));
  EXPECT_NEAR(back.d, 0.5, 1e-12);
  EXPECT_NEAR(back.a, 0.5, 1e-12);
  EXPECT_NEAR(back.b, -0.5, 1e-12);
  EXPECT_NEAR(back.c, 0.5, 1e-12);
  // Rotation by pi about x: the same rotation whatever the sign.
  expect_orientation(rot_x(kPi), {0, 1, 0, 0});
  expect_orientation(rot_z(kPi / 2), {std::cos(kPi / 4), 0, 0, std::sin(kPi / 4)});
  // The error is the rotation vector from one to the other.
  expect_near(rotation_error(Rotation{}, rot_z(0.3)), {0, 0, 0.3}, 1e-12);
  expect_near(rotation_error(rot_x(0.2), rot_x(-0.1)), {-0.3, 0, 0}, 1e-12);
}

TEST(Kinematics, PlanarArmByHand) {
  const ArmKinematics arm(planar_arm());
  const Vec3 tool{0.5, 0, 0};
  // Stretched along x: the end-effector frame at the elbow (1, 0, 0), the tool 0.5 m further.
  expect_near(arm.end_effector_frame({0, 0}).origin, {1, 0, 0});
  expect_near(arm.tool_pose({0, 0}, tool).position, {1.5, 0, 0});
  // Shoulder at 90 deg: along y, the end effector turned 90 deg about z.
  Pose p = arm.tool_pose({kPi / 2, 0}, tool);
  expect_near(p.position, {0, 1.5, 0});
  expect_orientation(p.orientation, {std::cos(kPi / 4), 0, 0, std::sin(kPi / 4)});
  // Elbow back by 90 deg: the tool points along x again from (0, 1, 0).
  p = arm.tool_pose({kPi / 2, -kPi / 2}, tool);
  expect_near(p.position, {0.5, 1, 0});
  expect_orientation(p.orientation, {1, 0, 0, 0});
}

TEST(Kinematics, TheBaseFrameTakesTheArmIntoTheVehicleFrame) {
  auto config = planar_arm();
  config.base_x_m = 0.2;
  config.base_z_m = -0.3;
  config.base_quaternion_d = 0;  // turned over: pi about x (base z up in a z-down vehicle frame)
  config.base_quaternion_a = 1;
  const ArmKinematics arm(config);
  // (0, 1.5, 0) in the base frame -> (0.2, -1.5, -0.3) in the vehicle frame.
  const Pose p = arm.tool_pose({kPi / 2, 0}, {0.5, 0, 0});
  expect_near(p.position, {0.2, -1.5, -0.3});
  expect_orientation(p.orientation, to_quaternion(rot_x(kPi) * rot_z(kPi / 2)));
}

TEST(Kinematics, ScaraWithAPrismaticJointByHand) {
  const ArmKinematics arm(scara_arm());
  // Straight out: 0.8 m along x at 0.4 m, z flipped down, the quill 0.1 m down.
  Pose p = arm.tool_pose({0, 0, 0.1}, {});
  expect_near(p.position, {0.8, 0, 0.3});
  expect_orientation(p.orientation, {0, 1, 0, 0});
  // Both revolute joints at 90 deg: first link along y, second along -x; quill 0.2 m down.
  p = arm.tool_pose({kPi / 2, kPi / 2, 0.2}, {});
  expect_near(p.position, {-0.3, 0.5, 0.2});
  expect_orientation(p.orientation, {0, 0, 1, 0});  // pi about y
}

TEST(Kinematics, SixJointArmByHand) {
  const ArmKinematics arm(puma_arm());
  // Corke's p560 at qz: T = [I | (0.4521, -0.15005, 0.4318)].
  Pose p = arm.tool_pose({0, 0, 0, 0, 0, 0}, {});
  expect_near(p.position, {0.4521, -0.15005, 0.4318});
  expect_orientation(p.orientation, {1, 0, 0, 0});
  // The waist at 90 deg turns all of it about the base z.
  p = arm.tool_pose({kPi / 2, 0, 0, 0, 0, 0}, {});
  expect_near(p.position, {0.15005, 0.4521, 0.4318});
  expect_orientation(p.orientation, {std::cos(kPi / 4), 0, 0, std::sin(kPi / 4)});
  // The shoulder at 90 deg: the upper arm up, the forearm back along -x; the
  // end effector turned -90 deg about y; a tool 0.1 m along its z lies along -x.
  p = arm.tool_pose({0, kPi / 2, 0, 0, 0, 0}, {0, 0, 0.1});
  expect_near(p.position, {-0.5318, -0.15005, 0.4521});
  expect_orientation(p.orientation, {std::cos(kPi / 4), 0, -std::sin(kPi / 4), 0});
}

TEST(Kinematics, JacobianMatchesFiniteDifferences) {
  for (const auto& config : {puma_arm(), scara_arm()}) {
    const ArmKinematics arm(config);
    const std::vector<double> q = config.joints.size() == 6 ? std::vector<double>{0.3, -0.4, 0.5, 0.2, -0.7, 0.9}
                                                            : std::vector<double>{0.3, -0.4, 0.15};
    const Vec3 tool{0.05, -0.02, 0.1};
    const Jacobian j = arm.jacobian(q, tool);
    const Pose at = arm.tool_pose(q, tool);
    const double h = 1e-6;
    for (std::size_t i = 0; i < q.size(); ++i) {
      auto moved = q;
      moved[i] += h;
      const Pose next = arm.tool_pose(moved, tool);
      const Vec3 dp = (1 / h) * (next.position - at.position);
      const Vec3 dw = (1 / h) * rotation_error(at.orientation, next.orientation);
      SCOPED_TRACE("joint " + std::to_string(i + 1));
      expect_near({j[i][0], j[i][1], j[i][2]}, dp, 1e-5);
      expect_near({j[i][3], j[i][4], j[i][5]}, dw, 1e-5);
    }
  }
}

TEST(Kinematics, InverseOfForwardIsThePoseAgainOnASixJointArm) {
  const ArmKinematics arm(puma_arm());
  const Vec3 tool{0, 0, 0.1};
  const std::vector<std::vector<double>> configurations = {
      {0.3, -0.4, 0.5, 0.2, -0.7, 0.9}, {-1.2, 0.8, -0.3, 1.5, 0.4, -2.0}, {2.0, -1.0, 1.0, -0.5, 1.2, 0.1}};
  for (const auto& q : configurations) {
    const Pose target = arm.tool_pose(q, tool);
    // From the zero pose, far from the answer.
    const auto solved = arm.inverse(target, tool, std::vector<double>(6, 0.0));
    ASSERT_TRUE(solved) << solved.error().message();
    const Pose reached = arm.tool_pose(*solved, tool);
    EXPECT_LE(norm(reached.position - target.position), 1e-3);
    EXPECT_LE(norm(rotation_error(reached.orientation, target.orientation)), 1e-3);
    for (std::size_t i = 0; i < 6; ++i) {
      EXPECT_GE((*solved)[i], -3.14159);
      EXPECT_LE((*solved)[i], 3.14159);
    }
  }
}

TEST(Kinematics, InverseOnAThreeJointArmWithAPrismaticJoint) {
  const ArmKinematics arm(scara_arm());
  const Pose target = arm.tool_pose({0.7, -1.1, 0.25}, {});
  const auto solved = arm.inverse(target, {}, {0, 0, 0.1});
  ASSERT_TRUE(solved) << solved.error().message();
  const Pose reached = arm.tool_pose(*solved, {});
  EXPECT_LE(norm(reached.position - target.position), 1e-3);
  EXPECT_LE(norm(rotation_error(reached.orientation, target.orientation)), 1e-3);
  EXPECT_GE((*solved)[2], 0);
  EXPECT_LE((*solved)[2], 0.3);
}

TEST(Kinematics, UnreachablePosesAreErrors) {
  const ArmKinematics arm(puma_arm());
  Pose far;
  far.position = {3, 0, 0};  // the arm reaches under 1 m
  EXPECT_FALSE(arm.inverse(far, {}, std::vector<double>(6, 0.0)));
  // A SCARA cannot tilt its tool.
  const ArmKinematics scara(scara_arm());
  Pose tilted = scara.tool_pose({0.2, 0.3, 0.1}, {});
  tilted.orientation = tilted.orientation * rot_x(0.3);
  EXPECT_FALSE(scara.inverse(tilted, {}, {0, 0, 0.1}));
  // Beyond the quill's stroke (0.3 m down from 0.4 m: z under 0.1 m is out of reach).
  Pose low = scara.tool_pose({0.2, 0.3, 0.1}, {});
  low.position.z = 0.05;
  EXPECT_FALSE(scara.inverse(low, {}, {0, 0, 0.1}));
}

TEST(Kinematics, JointRatesGiveTheTwist) {
  const ArmKinematics arm(puma_arm());
  const std::vector<double> q{0.3, -0.4, 0.5, 0.2, -0.7, 0.9};
  const Vec3 linear{0.05, -0.02, 0.01}, angular{0.1, 0, -0.2};
  const JointRates rates = arm.joint_rates(q, {}, linear, angular);
  EXPECT_LT(rates.residual, 1e-6);
  // A 2-joint planar arm cannot move out of its plane.
  const ArmKinematics planar(planar_arm());
  EXPECT_GT(planar.joint_rates({0.3, 0.3}, {0.5, 0, 0}, {0, 0, 0.1}, {}).residual, 0.09);
}

}  // namespace
}  // namespace jaus::test
