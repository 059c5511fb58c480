// A command to a wildcard address (jaus/ocu/wildcard_command.hpp, issue 49)
// under virtual time: it reaches every component of the subsystem, found or
// not yet, and says which confirmed it; to nobody, nobody confirmed it.
#include "jaus/messages/core_messages.hpp"
#include "jaus/ocu/wildcard_command.hpp"
#include "lossy_fixture.hpp"

namespace jausctl::test {
namespace {

using jaus::Address;
using jaus::msg::ClearEmergency;
using jaus::msg::PrimaryStatus;
using jaus::msg::SetEmergency;
using ocu::Arrival;

const Address kSubsystem1{1, 255, 255, 255};
const std::vector<Address> kEveryComponent{kTargetManager, kCommunicator, kPoseSensor};

class WildcardCommandTest : public LossyOcuTest {
 protected:
  bool everything_in_emergency() const {
    return target->communicator().state() == PrimaryStatus::emergency &&
           target->pose_sensor().state() == PrimaryStatus::emergency;
  }
};

TEST_F(WildcardCommandTest, EveryComponentOfTheSubsystemConfirmsASetEmergencyToIt) {
  auto ocu = open_lossy_ocu();
  ASSERT_TRUE(ocu);
  const auto result = ocu::send_to_every_member(*ocu, kSubsystem1, SetEmergency{{1}}, jaus::priority::kSafetyCritical);
  EXPECT_EQ(result.confirmed(), kEveryComponent);
  EXPECT_TRUE(result.unconfirmed().empty());
  EXPECT_FALSE(result.interrupted);
  EXPECT_TRUE(everything_in_emergency());
  EXPECT_GE(result.broadcasts, 1u);
  // Finished once all answered and nothing new came for the settle time, well before look_for.
  EXPECT_LT(result.elapsed, ocu::WildcardPolicy{}.look_for);
}

// The fresh start: the vehicle comes up after the stop was given. The
// broadcast goes on until it is heard, so the vehicle stops as soon as it is up.
TEST_F(WildcardCommandTest, AVehicleThatStartsWhileItRunsIsStoppedAndConfirmsIt) {
  target.reset();
  auto ocu = open_lossy_ocu();
  ASSERT_TRUE(ocu);
  time.call_at(time.now() + 700ms, [this] { start_target({}); });
  const auto result = ocu::send_to_every_member(*ocu, kSubsystem1, SetEmergency{{1}}, jaus::priority::kSafetyCritical);
  ASSERT_TRUE(target);
  EXPECT_EQ(result.confirmed(), kEveryComponent);
  EXPECT_TRUE(everything_in_emergency());
  EXPECT_GT(result.broadcasts, 10u) << "repeated while nobody answered";
}

TEST_F(WildcardCommandTest, ASubsystemWithNobodyIsConfirmedByNobodyAfterLookFor) {
  auto ocu = open_lossy_ocu();
  ASSERT_TRUE(ocu);
  ocu::WildcardPolicy policy;
  policy.look_for = 2s;
  const auto result = ocu::send_to_every_member(*ocu, Address{9, 255, 255, 255}, SetEmergency{{1}},
                                                jaus::priority::kSafetyCritical, policy);
  EXPECT_TRUE(result.members.empty());
  EXPECT_TRUE(result.confirmed().empty());
  EXPECT_EQ(result.elapsed, 2s);
  EXPECT_EQ(result.broadcasts, 40u);  // every 50 ms from 0 to 1.95 s
  EXPECT_EQ(target->communicator().state(), PrimaryStatus::ready) << "another subsystem's stop";
}

TEST_F(WildcardCommandTest, AtThirtyPercentLossEveryComponentStillStopsAndConfirms) {
  auto ocu = open_lossy_ocu();
  ASSERT_TRUE(ocu);
  lose(0.3, 0.3, 49);
  const auto result = ocu::send_to_every_member(*ocu, kSubsystem1, SetEmergency{{1}}, jaus::priority::kSafetyCritical);
  EXPECT_EQ(result.confirmed(), kEveryComponent);
  EXPECT_TRUE(everything_in_emergency());
}

// A clear is not a stop: no broadcast, each component gets its own copy once
// and confirms it; the holds of this OCU go.
TEST_F(WildcardCommandTest, AClearGoesToEachComponentOnlyAndEachConfirmsIt) {
  auto ocu = open_lossy_ocu();
  ASSERT_TRUE(ocu);
  ASSERT_EQ(ocu::send_to_every_member(*ocu, kSubsystem1, SetEmergency{{1}}).confirmed(), kEveryComponent);
  const auto result = ocu::send_to_every_member(*ocu, kSubsystem1, ClearEmergency{{1}});
  EXPECT_EQ(result.broadcasts, 0u);
  EXPECT_EQ(result.confirmed(), kEveryComponent);
  EXPECT_TRUE(run_until([&] { return target->communicator().state() == PrimaryStatus::ready; }));
  EXPECT_EQ(target->pose_sensor().state(), PrimaryStatus::ready);
}

// Only what the address names: 1.1.35.255 is the communicator's instances.
TEST_F(WildcardCommandTest, OnlyTheComponentsTheAddressNamesAreMembers) {
  auto ocu = open_lossy_ocu();
  ASSERT_TRUE(ocu);
  const auto result = ocu::send_to_every_member(*ocu, Address{1, 1, 35, 255}, SetEmergency{{1}});
  EXPECT_EQ(result.confirmed(), std::vector<Address>{kCommunicator});
}

TEST_F(WildcardCommandTest, AStopRequestEndsItInterrupted) {
  auto ocu = open_lossy_ocu();
  ASSERT_TRUE(ocu);
  time.call_at(time.now() + 200ms, [&] { ocu->request_stop(); });
  const auto result = ocu::send_to_every_member(*ocu, Address{9, 255, 255, 255}, SetEmergency{{1}});
  EXPECT_TRUE(result.interrupted);
  EXPECT_LT(result.elapsed, 1s);
}

// jausctl's words: which confirmed it; none, and it says so and fails.
TEST_F(WildcardCommandTest, JausctlSaysHowManyConfirmedAndFailsWhenNoneDid) {
  auto ocu = open_lossy_ocu();
  ASSERT_TRUE(ocu);
  ASSERT_EQ(ocu::run_emergency(*ocu, kSubsystem1, true, 1s, io()), kExitOk) << err.str();
  EXPECT_EQ(out.str().rfind("Set Emergency to 1.255.255.255 by 254.1.40.1: confirmed by 3 components (1.1.1.1, "
                            "1.1.35.1, 1.1.38.1) in ",
                            0),
            0u)
      << out.str();
  out.str("");
  EXPECT_EQ(ocu::run_emergency(*ocu, Address{9, 255, 255, 255}, true, 1s, io()), kExitFailure);
  EXPECT_EQ(out.str(), "");
  EXPECT_EQ(err.str(),
            "jausctl emergency: Set Emergency to 9.255.255.255 by 254.1.40.1: no component confirmed it within 3.0 s "
            "(none answered; broadcast 60 times): it may NOT have stopped; stop it another way (its own stop button, "
            "the radio's)\n");
}

TEST_F(WildcardCommandTest, JausctlSendOfStandbyToAWildcardSaysWhoConfirmed) {
  auto ocu = open_lossy_ocu();
  ASSERT_TRUE(ocu);
  auto prepared = ocu::prepare_message(ocu::Json::parse(R"({"name":"Standby"})"), jaus::wire::Dialect::ra);
  ASSERT_TRUE(prepared) << prepared.error().message();
  ASSERT_EQ(ocu::run_send(*ocu, kSubsystem1, *prepared, 1s, io()), kExitOk) << err.str();
  EXPECT_EQ(out.str().rfind("Standby to 1.255.255.255 by 254.1.40.1: confirmed by 3 components", 0), 0u) << out.str();
}

}  // namespace
}  // namespace jausctl::test
