#include <gtest/gtest.h>

#include "jaus/runtime/lifecycle.hpp"

namespace jaus::rt {
namespace {

using E = LifecycleEvent;
using S = PrimaryStatus;

// Drives a fresh lifecycle into `state`.
void reach(Lifecycle& l, S state) {
  switch (state) {
    case S::initialize: return;
    case S::ready: ASSERT_TRUE(l.process(E::init_succeeded)); return;
    case S::failure: ASSERT_TRUE(l.process(E::init_failed)); return;
    case S::standby:
      ASSERT_TRUE(l.process(E::init_succeeded));
      ASSERT_TRUE(l.process(E::standby));
      return;
    case S::emergency:
      ASSERT_TRUE(l.process(E::init_succeeded));
      ASSERT_TRUE(l.process(E::emergency_set));
      return;
    case S::shutdown: ASSERT_TRUE(l.process(E::shutdown)); return;
  }
}

struct Case {
  S from;
  E event;
  std::optional<S> to;  // empty: refused, state unchanged
};

class LifecycleTransitions : public ::testing::TestWithParam<Case> {};

TEST_P(LifecycleTransitions, FollowTheTable) {
  Lifecycle l;
  reach(l, GetParam().from);
  ASSERT_EQ(l.state(), GetParam().from);
  const bool accepted = l.process(GetParam().event);
  EXPECT_EQ(accepted, GetParam().to.has_value()) << to_string(GetParam().from) << " + " << to_string(GetParam().event);
  EXPECT_EQ(l.state(), GetParam().to.value_or(GetParam().from));
}

const std::vector<Case> kCases = {
    // Initialisation.
    {S::initialize, E::init_succeeded, S::ready},
    {S::initialize, E::init_failed, S::failure},
    {S::ready, E::init_succeeded, std::nullopt},
    // Standby only from Ready, Resume only from Standby.
    {S::ready, E::standby, S::standby},
    {S::standby, E::resume, S::ready},
    {S::ready, E::resume, std::nullopt},
    {S::initialize, E::standby, std::nullopt},
    {S::failure, E::standby, std::nullopt},
    {S::emergency, E::standby, std::nullopt},
    {S::emergency, E::resume, std::nullopt},
    {S::standby, E::standby, std::nullopt},
    // Emergency from every state but Shutdown.
    {S::initialize, E::emergency_set, S::emergency},
    {S::ready, E::emergency_set, S::emergency},
    {S::standby, E::emergency_set, S::emergency},
    {S::failure, E::emergency_set, S::emergency},
    {S::shutdown, E::emergency_set, std::nullopt},
    {S::ready, E::emergency_cleared, std::nullopt},
    // Reset from every state but Shutdown.
    {S::initialize, E::reset, S::initialize},
    {S::ready, E::reset, S::initialize},
    {S::standby, E::reset, S::initialize},
    {S::failure, E::reset, S::initialize},
    {S::emergency, E::reset, S::initialize},
    {S::shutdown, E::reset, std::nullopt},
    // Shutdown from every state; final.
    {S::initialize, E::shutdown, S::shutdown},
    {S::ready, E::shutdown, S::shutdown},
    {S::standby, E::shutdown, S::shutdown},
    {S::failure, E::shutdown, S::shutdown},
    {S::emergency, E::shutdown, S::shutdown},
    {S::shutdown, E::shutdown, std::nullopt},
    {S::shutdown, E::init_succeeded, std::nullopt},
};

INSTANTIATE_TEST_SUITE_P(Table, LifecycleTransitions, ::testing::ValuesIn(kCases));

TEST(Lifecycle, EmergencyReturnsToTheStateItInterrupted) {
  for (S interrupted : {S::ready, S::standby, S::initialize, S::failure}) {
    Lifecycle l;
    reach(l, interrupted);
    ASSERT_TRUE(l.process(E::emergency_set));
    ASSERT_EQ(l.state(), S::emergency);
    ASSERT_TRUE(l.process(E::emergency_cleared));
    EXPECT_EQ(l.state(), interrupted) << to_string(interrupted);
  }
}

// Issue 27, failure 5: Standby, then the platform link drops and returns:
// Standby again, never Ready (a streaming controller would drive on).
TEST(Lifecycle, AFaultReturnsToTheStateItInterrupted) {
  for (S interrupted : {S::ready, S::standby}) {
    Lifecycle l;
    reach(l, interrupted);
    ASSERT_TRUE(l.process(E::failure_detected));
    ASSERT_EQ(l.state(), S::failure);
    ASSERT_TRUE(l.process(E::failure_cleared));
    EXPECT_EQ(l.state(), interrupted) << to_string(interrupted);
  }
}

TEST(Lifecycle, AFaultInterruptedByAnEmergencyStillReturnsToItsStandby) {
  Lifecycle l;
  reach(l, S::standby);
  ASSERT_TRUE(l.process(E::failure_detected));
  ASSERT_TRUE(l.process(E::emergency_set));
  ASSERT_TRUE(l.process(E::emergency_cleared));
  ASSERT_EQ(l.state(), S::failure);
  ASSERT_TRUE(l.process(E::failure_cleared));
  EXPECT_EQ(l.state(), S::standby);
}

}  // namespace
}  // namespace jaus::rt
