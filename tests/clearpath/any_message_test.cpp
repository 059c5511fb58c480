// AnyMessage, the Clearpath message set's tagged union: it owns exactly one
// message, whatever is copied, moved or assigned over it (the sanitizers see
// every leak or double destruction), and says which one it holds.
#include <gtest/gtest.h>

#include <string>
#include <variant>

#include "jaus/clearpath/messages.hpp"

namespace jaus::clearpath {
namespace {

SetPlatformName named(const std::string& name) { return SetPlatformName{name, false}; }

SetAbsoluteJoints joints(int count) {
  SetAbsoluteJoints m;
  for (int i = 0; i < count; ++i) m.joints.push_back(AbsoluteJointTarget{static_cast<std::uint8_t>(i), 0.5 * i});
  return m;
}

TEST(AnyMessage, DefaultHoldsAnAckAndSaysWhichMessageItHolds) {
  const AnyMessage none;
  EXPECT_TRUE(none.holds<Ack>());
  EXPECT_EQ(none.index(), 0u);
  const AnyMessage name = named("husky");
  EXPECT_TRUE(name.holds<SetPlatformName>());
  EXPECT_FALSE(name.holds<Ack>());
  EXPECT_EQ(name.index(), kMessageIndex<SetPlatformName>);
  ASSERT_NE(name.get_if<SetPlatformName>(), nullptr);
  EXPECT_EQ(name.get_if<SetPlatformName>()->name, "husky");
  EXPECT_EQ(name.get_if<SetVelocity>(), nullptr);
  EXPECT_EQ(name_of(name), "set_platform_name");
  EXPECT_EQ(type_of(name), SetPlatformName::kType);
}

TEST(AnyMessage, GetOfAnotherTypeThrowsAsStdGetDoes) {
  AnyMessage m = named("husky");
  EXPECT_EQ(m.get<SetPlatformName>().name, "husky");
  EXPECT_THROW((void)m.get<SetVelocity>(), std::bad_variant_access);
  const AnyMessage& c = m;
  EXPECT_THROW((void)c.get<Ack>(), std::bad_variant_access);
}

TEST(AnyMessage, CopiesAreEqualAndIndependent) {
  AnyMessage original = joints(3);
  AnyMessage copy = original;
  EXPECT_EQ(copy, original);
  copy.get<SetAbsoluteJoints>().joints.pop_back();
  EXPECT_NE(copy, original);
  EXPECT_EQ(original.get<SetAbsoluteJoints>().joints.size(), 3u);
}

TEST(AnyMessage, MovesTakeTheMessageAndLeaveAValidOneBehind) {
  AnyMessage from = joints(4);
  AnyMessage to = std::move(from);
  EXPECT_EQ(to.get<SetAbsoluteJoints>().joints.size(), 4u);
  EXPECT_TRUE(from.holds<SetAbsoluteJoints>());  // NOLINT(bugprone-use-after-move): moved-from, still a message
  from = named("reused");
  EXPECT_EQ(from.get<SetPlatformName>().name, "reused");
}

TEST(AnyMessage, AssignmentAcrossTypesReplacesTheMessage) {
  AnyMessage m = named(std::string(200, 'x'));  // a heap-allocated string
  const AnyMessage other = joints(2);
  m = other;  // copy over another type
  EXPECT_EQ(m, other);
  SetVelocity velocity;
  velocity.translational = 0.5;
  m = AnyMessage(velocity);  // move over another type
  EXPECT_TRUE(m.holds<SetVelocity>());
  m = named("same type");
  m = AnyMessage(named("same type, again"));
  EXPECT_EQ(m.get<SetPlatformName>().name, "same type, again");
  auto& self = m;
  m = self;  // self-assignment changes nothing
  m = std::move(self);
  EXPECT_EQ(m.get<SetPlatformName>().name, "same type, again");
}

TEST(AnyMessage, EqualityComparesTypeThenFields) {
  EXPECT_EQ(AnyMessage(named("a")), AnyMessage(named("a")));
  EXPECT_NE(AnyMessage(named("a")), AnyMessage(named("b")));
  EXPECT_NE(AnyMessage(RequestEcho{}), AnyMessage(RequestPlatformInfo{}));  // same fields, other type
}

TEST(AnyMessage, VisitCallsWithTheHeldMessageAndReturnsItsResult) {
  AnyMessage m = joints(5);
  const std::size_t count = visit(
      [](const auto& message) -> std::size_t {
        if constexpr (requires { message.joints; }) return message.joints.size();
        return 0;
      },
      m);
  EXPECT_EQ(count, 5u);
  visit(
      [](auto& message) {
        if constexpr (requires { message.joints; }) message.joints.clear();
      },
      m);
  EXPECT_TRUE(m.get<SetAbsoluteJoints>().joints.empty());
  // Every message of the catalogue, made by type, visits as itself.
  for (const auto& info : message_catalogue()) {
    const auto made = make_message(info.type);
    ASSERT_TRUE(made);
    EXPECT_EQ(type_of(*made), info.type);
    EXPECT_EQ(name_of(*made), info.name);
  }
}

}  // namespace
}  // namespace jaus::clearpath
