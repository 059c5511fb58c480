// rt::ControlClient alone, under virtual time: what it sends, when it holds
// control, and each way control ends (refused, never answered, rejected,
// the target leaving Ready, the target falling silent).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "jaus/base/virtual_time.hpp"
#include "jaus/messages/core_messages.hpp"
#include "jaus/runtime/lifecycle.hpp"
#include "jaus/runtime/control_client.hpp"
#include "jaus/runtime/stop_counter.hpp"
#include "jaus/wire/message.hpp"

namespace jaus::test {
namespace {

using namespace std::chrono_literals;
using rt::ControlClient;

const Address kTarget{1, 1, 33, 1};
const Address kOwner{1, 1, 45, 1};

class NoOutbox final : public rt::Outbox {
 public:
  void send(const Header&, std::span<const std::uint8_t>) override {}
};

class ControlClientTest : public ::testing::Test {
 protected:
  ControlClientTest()
      : env_{time_, time_, outbox_},
        client_(env_, ControlClient::Options{},
                ControlClient::Io{
                    .request = [this](const Address& to,
                                      const msg::RequestComponentControl& m) { sent_.push_back("request " + to.to_string() + " " + std::to_string(m.authority)); },
                    .release = [this](const Address& to, const msg::ReleaseComponentControl&) { sent_.push_back("release " + to.to_string()); },
                    .query_status = [this](const Address&, const msg::QueryComponentStatus&) { ++status_queries_; },
                }) {}

  void acquire() {
    client_.acquire(
        kTarget, 7, [this] { ++granted_; }, [this](const std::string& why) { lost_.push_back(why); });
  }
  template <class M>
  bool deliver(const M& message, const Address& from = kTarget) {
    std::vector<std::uint8_t> payload(512);
    auto size = wire::encode_payload(message, payload);
    EXPECT_TRUE(size);
    payload.resize(*size);
    Header h;
    h.command_code = M::code;
    h.source = from;
    h.destination = kOwner;
    h.data_size = static_cast<std::uint16_t>(payload.size());
    return client_.on_message(h, payload);
  }
  msg::ReportComponentStatus status(msg::PrimaryStatus s, std::uint64_t stops = 0) {
    msg::ReportComponentStatus r;
    r.primary_status = static_cast<std::uint8_t>(s);
    r.secondary_status = rt::stop_counter::bits(stops);
    return r;
  }

  rt::VirtualTime time_;
  NoOutbox outbox_;
  rt::Environment env_;
  ControlClient client_;
  std::vector<std::string> sent_;
  int status_queries_ = 0;
  int granted_ = 0;
  std::vector<std::string> lost_;
};

TEST_F(ControlClientTest, HeldOnlyOnceConfirmedAndTheTargetSaysReady) {
  acquire();
  ASSERT_EQ(sent_, std::vector<std::string>{"request 1.1.33.1 7"});
  EXPECT_EQ(client_.state(), ControlClient::State::requesting);
  EXPECT_TRUE(deliver(msg::ConfirmComponentControl{{msg::control_response::kAccepted}}));
  EXPECT_EQ(client_.state(), ControlClient::State::granted_waiting_ready);
  EXPECT_EQ(granted_, 0);
  EXPECT_EQ(status_queries_, 1);  // asked at once
  EXPECT_TRUE(deliver(status(msg::PrimaryStatus::ready)));
  EXPECT_TRUE(client_.held());
  EXPECT_EQ(granted_, 1);
  // Then the status is asked every period.
  time_.advance(500ms);
  EXPECT_GE(status_queries_, 5);
  EXPECT_TRUE(lost_.empty());
}

TEST_F(ControlClientTest, MessagesFromAnotherComponentAreNotItsBusiness) {
  acquire();
  EXPECT_FALSE(deliver(msg::ConfirmComponentControl{{msg::control_response::kAccepted}}, Address{1, 1, 34, 1}));
  EXPECT_EQ(client_.state(), ControlClient::State::requesting);
}

TEST_F(ControlClientTest, ARefusalIsALossWithoutRelease) {
  acquire();
  deliver(msg::ConfirmComponentControl{{msg::control_response::kNotAccepted}});
  EXPECT_EQ(client_.state(), ControlClient::State::released);
  ASSERT_EQ(lost_.size(), 1u);
  EXPECT_NE(lost_[0].find("refused"), std::string::npos) << lost_[0];
  EXPECT_EQ(sent_.size(), 1u);  // no release for what was never ours
  EXPECT_EQ(client_.counters().refused, 1u);
}

TEST_F(ControlClientTest, ARequestNeverAnsweredIsRepeatedThenGivenUp) {
  acquire();
  time_.advance(5s);
  ASSERT_EQ(lost_.size(), 1u);
  EXPECT_NE(lost_[0].find("did not answer"), std::string::npos) << lost_[0];
  EXPECT_EQ(client_.counters().requests_sent, 3u);
  // Released too: a confirmation lost on its way back may have granted it.
  EXPECT_EQ(sent_.back(), "release 1.1.33.1");
}

TEST_F(ControlClientTest, TakenOverByRejectComponentControl) {
  acquire();
  deliver(msg::ConfirmComponentControl{{msg::control_response::kAccepted}});
  deliver(status(msg::PrimaryStatus::ready));
  deliver(msg::RejectComponentControl{});
  EXPECT_EQ(client_.state(), ControlClient::State::released);
  ASSERT_EQ(lost_.size(), 1u);
  EXPECT_NE(lost_[0].find("Reject"), std::string::npos) << lost_[0];
  EXPECT_EQ(sent_.size(), 1u);  // not ours any more: nothing to release
  EXPECT_EQ(client_.counters().lost, 1u);
}

// Safety: a target that left Ready (an operator's Set Emergency) is a loss,
// so whoever clears it later does not find this owner still commanding.
TEST_F(ControlClientTest, TheTargetLeavingReadyIsALossAndControlIsGivenBack) {
  acquire();
  deliver(msg::ConfirmComponentControl{{msg::control_response::kAccepted}});
  deliver(status(msg::PrimaryStatus::ready));
  deliver(status(msg::PrimaryStatus::emergency));
  EXPECT_FALSE(client_.held());
  ASSERT_EQ(lost_.size(), 1u);
  EXPECT_NE(lost_[0].find("Emergency"), std::string::npos) << lost_[0];
  EXPECT_EQ(sent_.back(), "release 1.1.33.1");
  // Ready again later changes nothing: the client is released.
  EXPECT_FALSE(deliver(status(msg::PrimaryStatus::ready)));
  EXPECT_EQ(granted_, 1);
}

// Issue 42: Set then Clear Emergency between two queries. The target is
// Ready at both, but its stop counter moved: the stop happened, and the
// owner loses control as if it had seen it (and gives it back).
TEST_F(ControlClientTest, AStopBetweenTwoReportsIsALossThoughBothSayReady) {
  acquire();
  deliver(msg::ConfirmComponentControl{{msg::control_response::kAccepted}});
  deliver(status(msg::PrimaryStatus::ready, 4));  // stops before the hold are not ours
  ASSERT_TRUE(client_.held());
  time_.advance(100ms);
  deliver(status(msg::PrimaryStatus::ready, 4));
  ASSERT_TRUE(client_.held());
  time_.advance(100ms);
  deliver(status(msg::PrimaryStatus::ready, 5));
  EXPECT_FALSE(client_.held());
  ASSERT_EQ(lost_.size(), 1u);
  EXPECT_EQ(lost_[0], "1.1.33.1 stopped and went back to Ready between two status reports (stop counter 4 -> 5)");
  EXPECT_EQ(sent_.back(), "release 1.1.33.1");
  EXPECT_EQ(client_.counters().lost, 1u);
}

// The counter wraps at 4096 (12 bits): a wrap is a move like any other.
TEST_F(ControlClientTest, AStopCounterThatWrapsIsAMoveToo) {
  acquire();
  deliver(msg::ConfirmComponentControl{{msg::control_response::kAccepted}});
  deliver(status(msg::PrimaryStatus::ready, 4095));
  ASSERT_TRUE(client_.held());
  deliver(status(msg::PrimaryStatus::ready, 4096));
  EXPECT_FALSE(client_.held());
  ASSERT_EQ(lost_.size(), 1u);
  EXPECT_NE(lost_[0].find("4095 -> 0"), std::string::npos) << lost_[0];
}

TEST_F(ControlClientTest, GrantedOnATargetThatIsNotReadyIsALoss) {
  acquire();
  deliver(msg::ConfirmComponentControl{{msg::control_response::kAccepted}});
  deliver(status(msg::PrimaryStatus::standby));
  EXPECT_EQ(granted_, 0);
  ASSERT_EQ(lost_.size(), 1u);
  EXPECT_NE(lost_[0].find("Standby"), std::string::npos) << lost_[0];
}

TEST_F(ControlClientTest, ASilentTargetIsALoss) {
  acquire();
  deliver(msg::ConfirmComponentControl{{msg::control_response::kAccepted}});
  deliver(status(msg::PrimaryStatus::ready));
  time_.advance(1500ms);
  ASSERT_EQ(lost_.size(), 1u);
  EXPECT_NE(lost_[0].find("silent"), std::string::npos) << lost_[0];
}

TEST_F(ControlClientTest, ReleaseSendsReleaseAndCallsNoListener) {
  acquire();
  deliver(msg::ConfirmComponentControl{{msg::control_response::kAccepted}});
  deliver(status(msg::PrimaryStatus::ready));
  client_.release();
  client_.release();  // idempotent
  EXPECT_EQ(sent_.back(), "release 1.1.33.1");
  EXPECT_EQ(std::count(sent_.begin(), sent_.end(), "release 1.1.33.1"), 1);
  EXPECT_TRUE(lost_.empty());
  const int queries = status_queries_;
  time_.advance(2s);
  EXPECT_EQ(status_queries_, queries);  // nothing more is sent
}

}  // namespace
}  // namespace jaus::test
