// Access control through the face: one arbitration for both dialects (the RA
// component's), with JSS replies.
#include <algorithm>

#include "face_node.hpp"

namespace jaus::test {
namespace {

namespace msg = jss::msg;
using msg::confirm_control::kControlAccepted;
using msg::confirm_control::kInsufficientAuthority;

TEST(JssFaceAccessControl, RequestQueryAndReleaseControl) {
  FaceNode node;
  EXPECT_EQ(node.request_control(kClientA, kDriver, 5), kControlAccepted);
  const auto report = node.ask<msg::ReportControl>(kClientA, kDriver, msg::QueryControl{});
  ASSERT_TRUE(report.has_value());
  EXPECT_EQ(report->controller, kClientA);
  EXPECT_EQ(report->authority, 5);
  // The RA component's controller is the client's alias.
  ASSERT_TRUE(node.driver().control().controller().has_value());
  EXPECT_EQ(node.driver().control().controller()->address.subsystem, 250);

  const auto released = node.ask<msg::RejectControl>(kClientA, kDriver, msg::ReleaseControl{});
  ASSERT_TRUE(released.has_value());
  EXPECT_EQ(released->response_code, msg::reject_control::kControlReleased);
  node.run_for(20ms);
  EXPECT_FALSE(node.driver().control().controller().has_value());
  const auto after = node.ask<msg::ReportControl>(kClientA, kDriver, msg::QueryControl{});
  ASSERT_TRUE(after.has_value());
  EXPECT_EQ(after->controller, jss::JssId{});
}

TEST(JssFaceAccessControl, AHigherAuthorityPreemptsAndTheOldControllerGetsRejectZero) {
  FaceNode node;
  ASSERT_EQ(node.request_control(kClientA, kDriver, 5), kControlAccepted);
  EXPECT_EQ(node.request_control(kClientB, kDriver, 5), kInsufficientAuthority);
  EXPECT_EQ(node.request_control(kClientB, kDriver, 9), kControlAccepted);
  node.run_for(20ms);
  const auto rejected = node.take<msg::RejectControl>(kClientA, kDriver);
  ASSERT_TRUE(rejected.has_value());
  EXPECT_EQ(rejected->response_code, msg::reject_control::kControlReleased);
  const auto report = node.ask<msg::ReportControl>(kClientA, kDriver, msg::QueryControl{});
  ASSERT_TRUE(report.has_value());
  EXPECT_EQ(report->controller, kClientB);
  EXPECT_EQ(report->authority, 9);
}

TEST(JssFaceAccessControl, ReportAuthorityOfAFreeComponentIsItsOwn) {
  FaceNode node;
  const auto report = node.ask<msg::ReportAuthority>(kClientA, kDriver, msg::QueryAuthority{});
  ASSERT_TRUE(report.has_value());
  EXPECT_EQ(report->authority, node.driver().control().own_authority());
}

TEST(JssFaceAccessControl, ReportTimeoutIsTheControllerTimeout) {
  jss_face::FaceConfig config;
  config.controller_timeout_s = 3;
  FaceNode node(config);
  const auto report = node.ask<msg::ReportTimeout>(kClientA, kDriver, msg::QueryTimeout{});
  ASSERT_TRUE(report.has_value());
  EXPECT_EQ(report->timeout_s, 3);
}

TEST(JssFaceAccessControl, ASilentJssControllerLosesControlAndThePlatformIsStopped) {
  FaceNode node;
  ASSERT_EQ(node.request_control(kClientA, kDriver, 5), kControlAccepted);
  const auto stops_before = node.driver().counters().stops_commanded;
  // Kept by sending within the timeout (as AS5710 says: Request Control again).
  for (int i = 0; i < 4; ++i) {
    node.run_for(2s);
    ASSERT_EQ(node.request_control(kClientA, kDriver, 5), kControlAccepted);
  }
  EXPECT_TRUE(node.driver().control().controller().has_value());
  // The controller check reaches the client as JSS Query Status.
  EXPECT_GT(node.count(kClientA, msg::QueryStatus::code), 0u);
  node.drop(kClientA, msg::RejectControl::code);
  // Silent: control goes after the RA controller timeout (3 s), with Reject 0.
  ASSERT_TRUE(node.run_until([&] { return node.count(kClientA, msg::RejectControl::code) > 0; }, 4s));
  EXPECT_FALSE(node.driver().control().controller().has_value());
  EXPECT_GT(node.driver().counters().stops_commanded, stops_before);
}

TEST(JssFaceAccessControl, AnRaOperatorAndAJssClientSeeOneController) {
  FaceNode node;
  ASSERT_EQ(node.request_control(kClientA, kDriver, 5), kControlAccepted);
  // The RA operator asks at a higher authority: it takes over, the JSS client hears Reject 0.
  node.send_ra(kRaDriver, jaus::msg::RequestComponentControl{{9}});
  ASSERT_TRUE(node.run_until([&] { return node.count(kClientA, msg::RejectControl::code) > 0; }));
  EXPECT_EQ(node.ra_count(jaus::msg::ConfirmComponentControl::code), 1u);
  const auto report = node.ask<msg::ReportControl>(kClientA, kDriver, msg::QueryControl{});
  ASSERT_TRUE(report.has_value());
  EXPECT_EQ(report->controller, (jss::JssId{5, 1, 40}));
  // And the JSS client is refused below it.
  EXPECT_EQ(node.request_control(kClientA, kDriver, 9), kInsufficientAuthority);
}

TEST(JssFaceAccessControl, SetAuthorityFromTheControllerChangesItsAuthorityWithoutReply) {
  FaceNode node;
  ASSERT_EQ(node.request_control(kClientA, kDriver, 5), kControlAccepted);
  node.clear();
  node.send(kClientA, kDriver, msg::SetAuthority{{7}});
  node.run_for(50ms);
  EXPECT_EQ(node.count(kClientA, msg::ConfirmControl::code), 0u);
  EXPECT_EQ(node.driver().control().controller()->authority, 7);
  // Report Authority is the current authority: the controller's.
  const auto current = node.ask<msg::ReportAuthority>(kClientB, kDriver, msg::QueryAuthority{});
  ASSERT_TRUE(current.has_value());
  EXPECT_EQ(current->authority, 7);
  // From another client: ignored.
  node.send(kClientB, kDriver, msg::SetAuthority{{9}});
  node.run_for(50ms);
  EXPECT_EQ(node.driver().control().controller()->authority, 7);
}

TEST(JssFaceAccessControl, OutsideControlFromGetsNotAvailableAndTheLogNamesJssIdAndHost) {
  FaceNode node;
  node.face().locate_clients_with([](const jss::JssId& client) -> std::optional<std::string> {
    if (client == kClientA) return "192.0.2.7:3794";
    return std::nullopt;
  });
  jss::JudpHeader h;
  h.source = kClientA;
  h.destination = kDriver;
  node.receive(jss::make_judp_datagram(h, jss::encode_contents(msg::RequestControl{{5}})), rt::SenderStanding::observer);
  ASSERT_TRUE(node.run_until([&] { return node.count(kClientA, msg::ConfirmControl::code) > 0; }));
  // "Not allowed" is NOT_AVAILABLE (1), not INSUFFICIENT_AUTHORITY (2): a
  // higher authority would not help a client that may not command from where it is.
  EXPECT_EQ(node.take<msg::ConfirmControl>(kClientA, kDriver)->response_code, msg::confirm_control::kNotAvailable);
  EXPECT_FALSE(node.driver().control().controller().has_value());
  EXPECT_EQ(node.counters().refused, 1u);
  EXPECT_EQ(node.counters().messages_to_ra, 0u);  // the face's refusal: no alias slot taken for it
  const auto line = std::find_if(node.log().begin(), node.log().end(), [](const std::string& l) {
    return l.find("Request Control of 1.1.33") != std::string::npos;
  });
  ASSERT_NE(line, node.log().end());
  EXPECT_NE(line->find("JSS client 42.1.1 at 192.0.2.7:3794"), std::string::npos) << *line;
  EXPECT_NE(line->find("outside transport.control_from"), std::string::npos) << *line;
  EXPECT_NE(line->find("Confirm Control 1"), std::string::npos) << *line;

  // From inside control_from the same client gets control; the components
  // name it by its alias, and the face's line ties the alias to its JSS ID and host.
  EXPECT_EQ(node.request_control(kClientA, kDriver, 5), msg::confirm_control::kControlAccepted);
  EXPECT_TRUE(std::any_of(node.log().begin(), node.log().end(), [](const std::string& l) {
    return l.find("JSS client 42.1.1 at 192.0.2.7:3794 (alias 250.1.1.1): new client") != std::string::npos;
  })) << "no line ties the alias to the client";
  // jausd passes the components' lines through the face: each alias in
  // them is followed by the client it stands for (IP addresses, other
  // subsystems and empty slots are left as they are).
  EXPECT_EQ(node.face().name_clients_in("Set Wrench Effort from 250.1.1.1 not executed: controlled by 5.1.40.1"),
            "Set Wrench Effort from 250.1.1.1 (JSS client 42.1.1 at 192.0.2.7:3794) not executed: controlled by 5.1.40.1");
  EXPECT_EQ(node.face().name_clients_in("controlled by 250.1.1.1 (authority 5)"),
            "controlled by 250.1.1.1 (JSS client 42.1.1 at 192.0.2.7:3794) (authority 5)");
  for (const char* untouched : {"node at 250.1.1.1:3794", "250.7.1.1 refused", "2250.1.1.1", "250.1.1.1.5",
                                "no address here", "250.1.1"})
    EXPECT_EQ(node.face().name_clients_in(untouched), std::string(untouched));
}

}  // namespace
}  // namespace jaus::test
