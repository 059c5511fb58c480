// What the console follows is what the kinds say (rt::ComponentKind::
// operator_views, issue 44), never an ID it knows: a kind of the test's own,
// at an ID no built-in kind has, is followed for its view; a component whose
// ID no kind has is in the tree and nothing of it is followed; the page is
// told the views by ID in its welcome.
#include "console_node.hpp"
#include "jaus/components/velocity_state_sensor_kind.hpp"
#include "jaus/console/kind_views.hpp"

namespace jaus::test {
namespace {

constexpr std::uint8_t kSpeedometerId = 200;  // the test kind's, no built-in kind's
constexpr std::uint8_t kNobodysId = 201;      // no kind's at all
const Address kSpeedometer{1, 1, kSpeedometerId, 1};
const Address kNobodys{1, 1, kNobodysId, 1};

// A velocity state sensor under a kind of its own, showing "velocity".
rt::ComponentKind speedometer_kind() {
  auto kind = components::velocity_state_sensor_kind();
  kind.name = "test_speedometer";
  kind.default_id = kSpeedometerId;
  kind.default_node_authority = std::nullopt;
  kind.operator_views = {rt::operator_view::kVelocity};
  return kind;
}

// The test's kind, known to the host for the life of a test.
struct SpeedometerKindAdded {
  SpeedometerKindAdded() { EXPECT_TRUE(host::add_component_kind(speedometer_kind())); }
  ~SpeedometerKindAdded() { host::remove_component_kind("test_speedometer"); }
  SpeedometerKindAdded(const SpeedometerKindAdded&) = delete;
  SpeedometerKindAdded& operator=(const SpeedometerKindAdded&) = delete;
};

class OperatorViewsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(node.wait_ready());
    node.console().page_opened(1);
    node.run_for(3s);  // discovery, the first reports
  }

  std::size_t velocities_from(const Address& source) const {
    std::size_t n = 0;
    for (const auto& v : node.frames(1, "velocity"))
      if (v["source"] == source.to_string()) ++n;
    return n;
  }

  SpeedometerKindAdded kind_added;
  // The speedometer, and a velocity state sensor at an ID no kind has.
  ConsoleNode node{{host::ComponentSpec{"test_speedometer", kSpeedometerId, 1, 0, "", {}, 0, {}},
                    host::ComponentSpec{"velocity_state_sensor", kNobodysId, 1, 0, "", {}, 0, {}}}};
};

TEST_F(OperatorViewsTest, AKindOfItsOwnIsFollowedForItsViewNotItsId) {
  EXPECT_TRUE(node.console().followed().count(kSpeedometer));
  EXPECT_GE(velocities_from(kSpeedometer), 4u) << "Report Velocity State at 5 Hz, as for the built-in sensor";
  EXPECT_EQ(node.find(kSpeedometer)->service_connections().active(), 1u);
}

TEST_F(OperatorViewsTest, AComponentOfAnIdNoKindHasIsListedAndNothingOfItIsFollowed) {
  const auto trees = node.frames(1, "tree");
  ASSERT_FALSE(trees.empty());
  bool listed = false;
  for (const auto& s : trees.back()["subsystems"])
    for (const auto& n : s["nodes"])
      for (const auto& c : n["components"]) listed = listed || c["address"] == kNobodys.to_string();
  EXPECT_TRUE(listed);
  EXPECT_TRUE(console::views_of(kNobodysId).empty());
  EXPECT_FALSE(node.console().followed().count(kNobodys));
  EXPECT_EQ(velocities_from(kNobodys), 0u);
  EXPECT_EQ(node.find(kNobodys)->service_connections().active(), 0u) << "no service connection asked for";
}

TEST_F(OperatorViewsTest, TheWelcomeTellsThePageTheViewsOfEveryKnownId) {
  const auto welcome = node.frames(1, "welcome");
  ASSERT_EQ(welcome.size(), 1u);
  const auto& views = welcome.front()["views"];
  EXPECT_EQ(views[std::to_string(kSpeedometerId)], nlohmann::json::array({"velocity"}));
  EXPECT_EQ(views.count(std::to_string(kNobodysId)), 0u);
  // The built-in kinds' own (their folders say them): the drive and the stop at the primitive driver.
  EXPECT_EQ(views["33"], nlohmann::json::array({"drive", "emergency"}));
  EXPECT_EQ(views["46"], nlohmann::json::array({"waypoints"}));
  EXPECT_EQ(views.size(), console::views_by_id().size());
}

}  // namespace
}  // namespace jaus::test
