// The operator's kept ID and its lock (jaus/ocu/operator_identity.hpp,
// issue 49): chosen once and kept; one process at a time acts as it; a stop
// is never refused for it.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <unistd.h>

#include "jaus/ocu/operator_identity.hpp"

namespace jausctl::test {
namespace {

namespace fs = std::filesystem;
using jaus::ocu::IdUse;

class OperatorIdentityTest : public ::testing::Test {
 protected:
  void SetUp() override {
    char dir_template[] = "/tmp/jaus_operator_id_XXXXXX";
    dir = mkdtemp(dir_template);
    if (const char* old = std::getenv("XDG_STATE_HOME")) saved = old;
    ::setenv("XDG_STATE_HOME", dir.c_str(), 1);
  }
  void TearDown() override {
    if (saved) ::setenv("XDG_STATE_HOME", saved->c_str(), 1);
    else ::unsetenv("XDG_STATE_HOME");
    fs::remove_all(dir);
  }
  fs::path dir;
  std::optional<std::string> saved;
};

TEST_F(OperatorIdentityTest, TheIdIsChosenOnceAndKeptInTheStateDirectory) {
  ASSERT_EQ(jaus::ocu::operator_state_directory(), dir / "jaus");
  auto first = jaus::ocu::load_operator_id(dir / "jaus");
  ASSERT_TRUE(first) << first.error().message();
  EXPECT_EQ(first->subsystem, 254);
  EXPECT_EQ(first->component, 40);
  EXPECT_EQ(first->instance, 1);
  std::ifstream in(dir / "jaus" / "operator-id");
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, first->to_string());
  auto again = jaus::ocu::load_operator_id(dir / "jaus");
  ASSERT_TRUE(again);
  EXPECT_EQ(*again, *first);
}

TEST_F(OperatorIdentityTest, AnEditedIdIsUsedAndABadOneIsAnErrorNamingTheFile) {
  fs::create_directories(dir / "jaus");
  std::ofstream(dir / "jaus" / "operator-id") << "254.77.40.2\n";
  auto id = jaus::ocu::choose_operator_id(std::nullopt, IdUse::holds);
  ASSERT_TRUE(id) << id.error().message();
  EXPECT_EQ(id->address, (jaus::Address{254, 77, 40, 2}));
  EXPECT_EQ(id->note, "");
  std::ofstream(dir / "jaus" / "operator-id") << "254.77.1.1\n";
  const auto bad = jaus::ocu::choose_operator_id(std::nullopt, IdUse::holds);
  ASSERT_FALSE(bad);
  EXPECT_EQ(bad.error().code, jaus::ErrorCode::invalid_argument);
  EXPECT_NE(bad.error().message().find((dir / "jaus" / "operator-id").string()), std::string::npos);
}

// While one process acts as an ID: a second is refused control, shares it for
// a command (a stop is never refused), and looks as a fresh ID of its own node.
TEST_F(OperatorIdentityTest, WhileAnIdIsInUseControlIsRefusedACommandSharesItALookIsAFreshId) {
  const jaus::Address kept{254, 9, 40, 1};
  auto holder = jaus::ocu::choose_operator_id(kept, IdUse::holds);
  ASSERT_TRUE(holder) << holder.error().message();
  ASSERT_TRUE(holder->lock);

  const auto change = jaus::ocu::choose_operator_id(kept, IdUse::holds);
  ASSERT_FALSE(change);
  EXPECT_EQ(change.error().code, jaus::ErrorCode::refused);
  EXPECT_EQ(change.error().message(),
            "254.9.40.1 is in use by another process (pid " + std::to_string(::getpid()) +
                "): two processes acting as one ID get each other's replies; wait for it to end, or give another ID "
                "with --as");

  const auto share = jaus::ocu::choose_operator_id(kept, IdUse::shares);
  ASSERT_TRUE(share);
  EXPECT_EQ(share->address, kept);
  EXPECT_TRUE(share->shared);
  EXPECT_FALSE(share->lock);
  EXPECT_EQ(share->note, "254.9.40.1 is in use by another process (pid " + std::to_string(::getpid()) +
                             "): shared with it (only this command's own ACK is read as its answer)");

  const auto look = jaus::ocu::choose_operator_id(kept, IdUse::looks);
  ASSERT_TRUE(look);
  EXPECT_NE(look->address.node, kept.node) << "its own node: the other's replies never come to it";
  EXPECT_EQ(look->note, "");

  holder->lock.reset();  // the process ends: the kernel releases it
  EXPECT_TRUE(jaus::ocu::choose_operator_id(kept, IdUse::holds));
}

TEST_F(OperatorIdentityTest, WithoutAStateDirectoryEachRunIsAFreshIdAndSaysSo) {
  ::unsetenv("XDG_STATE_HOME");
  const std::string home = std::getenv("HOME") ? std::getenv("HOME") : "";
  ::unsetenv("HOME");
  EXPECT_FALSE(jaus::ocu::operator_state_directory());
  const auto id = jaus::ocu::choose_operator_id(std::nullopt, IdUse::shares);
  if (!home.empty()) ::setenv("HOME", home.c_str(), 1);
  ASSERT_TRUE(id);
  EXPECT_EQ(id->address.subsystem, 254);
  EXPECT_NE(id->note.find("for this run only (clear it with --as " + id->address.to_string() + ")"), std::string::npos)
      << id->note;
}

}  // namespace
}  // namespace jausctl::test
