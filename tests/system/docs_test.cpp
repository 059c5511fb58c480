// Docs that run: every shell block of the README and the walk-throughs runs,
// in order, as a reader would type it, against the default node, and does
// what its doc-test marker says (tests/system/doc_blocks.hpp has the
// markers). A command that changed, a flag that went, an output that no
// longer says what the docs promise fails here; so does a block nobody
// marked, and a list of the default node's components that is not the one
// config/jausd.yaml gives.
//
// Where the blocks run: a scratch directory whose build/run/apps/... and
// build/release/apps/... (the paths the docs give) and bin/ (on PATH, for
// the bare `jausd`, `jausctl` ...) point at this build's programs, and
// config/ at the source tree's; in a network namespace of the test's own
// (a loopback of its own), so that the docs' own addresses and port 3794
// are free, whatever else runs on the machine. The default node is
// jausd as ./scripts/run.sh starts it. Every process a block starts, in the
// background too, is stopped at the end of the block.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <net/if.h>
#include <sched.h>
#include <signal.h>
#include <spawn.h>
#include <sys/ioctl.h>
#include <sys/prctl.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <regex>
#include <set>
#include <sstream>
#include <thread>

#include "doc_blocks.hpp"
#include "kept_operator_id.hpp"
#include "jaus/host/component_kinds.hpp"

extern char** environ;

namespace jaus::test::docs {
namespace {

using namespace std::chrono_literals;
namespace fs = std::filesystem;

const fs::path kSource = JAUS_SOURCE_DIR;

// ---- the markers themselves ------------------------------------------------------

TEST(DocMarkers, AreReadWithTheirExpectations) {
  std::istringstream md(
      "text\n"
      "<!-- doc-test: expect-exit=0,2 expect=/ok \\(subsystem/ expect=/b/ stop-after=1.5 node=stopped -->\n"
      "```sh\n"
      "jausd --check-config   # comment\n"
      "# a comment line\n"
      "jausctl control 1.1.33.1 \\\n"
      "  --authority 10\n"
      "```\n"
      "<!-- doc-test: skip (needs a real platform) -->\n\n"
      "```sh\nrm -rf /\n```\n"
      "```sh\nunmarked\n```\n"
      "<!-- doc-test: default-components -->\n"
      "a node manager and\na communicator.\n\n"
      "<!-- doc-test: skip -->\n```sh\nx\n```\n"
      "<!-- doc-test: frobnicate=1 -->\n```sh\nx\n```\n");
  const ParsedDoc doc = parse_doc("t.md", md);
  ASSERT_EQ(doc.blocks.size(), 5u);
  const DocBlock& b = doc.blocks[0];
  EXPECT_EQ(b.where(), "t.md:3");
  EXPECT_EQ(b.language, "sh");
  EXPECT_EQ(b.expect_exit, (std::vector<int>{0, 2}));
  EXPECT_EQ(b.expect, (std::vector<std::string>{"ok \\(subsystem", "b"}));
  EXPECT_EQ(b.stop_after_s, 1.5);
  EXPECT_FALSE(b.node_running);
  EXPECT_EQ(b.commands(),
            (std::vector<std::string>{"jausd --check-config   # comment", "jausctl control 1.1.33.1   --authority 10"}));
  EXPECT_EQ(doc.blocks[1].skip, "needs a real platform");
  EXPECT_FALSE(doc.blocks[2].marked);
  ASSERT_EQ(doc.default_component_lists.size(), 1u);
  EXPECT_EQ(doc.default_component_lists[0].text, " a node manager and a communicator.");
  ASSERT_EQ(doc.errors.size(), 2u);  // the skip without a reason, the unknown directive
  EXPECT_NE(doc.errors[0].find("needs a reason"), std::string::npos) << doc.errors[0];
  EXPECT_NE(doc.errors[1].find("frobnicate"), std::string::npos) << doc.errors[1];
}

// ---- processes -----------------------------------------------------------------

// A command in a process group of its own (what Ctrl-C in a terminal reaches),
// with stdin from /dev/null and its stdout and stderr in a file.
class Command {
 public:
  Command(const std::string& command, const fs::path& output) : output_(output) {
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_addopen(&actions, 1, output.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_adddup2(&actions, 1, 2);
    posix_spawnattr_t attributes;
    posix_spawnattr_init(&attributes);
    posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETPGROUP | POSIX_SPAWN_SETSIGDEF | POSIX_SPAWN_SETSIGMASK);
    posix_spawnattr_setpgroup(&attributes, 0);
    sigset_t all, none;
    sigfillset(&all);
    sigemptyset(&none);
    posix_spawnattr_setsigdefault(&attributes, &all);
    posix_spawnattr_setsigmask(&attributes, &none);
    std::vector<std::string> argv{"/bin/bash", "-c", command};
    std::vector<char*> args;
    for (auto& a : argv) args.push_back(a.data());
    args.push_back(nullptr);
    if (posix_spawn(&pid_, args[0], &actions, &attributes, args.data(), environ) != 0) pid_ = 0;
    posix_spawn_file_actions_destroy(&actions);
    posix_spawnattr_destroy(&attributes);
  }
  ~Command() { stop_group(); }
  Command(const Command&) = delete;
  Command& operator=(const Command&) = delete;

  bool started() const { return pid_ != 0; }
  // The exit code (128 + signal), or nothing if it still runs at the deadline.
  std::optional<int> wait(std::chrono::milliseconds deadline) {
    const auto until = std::chrono::steady_clock::now() + deadline;
    while (!exit_code_ && pid_ != 0) {
      int status = 0;
      if (::waitpid(pid_, &status, WNOHANG) == pid_) {
        exit_code_ = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
        break;
      }
      if (std::chrono::steady_clock::now() > until) break;
      std::this_thread::sleep_for(20ms);
    }
    return exit_code_;
  }
  void interrupt() const { signal_group(SIGINT); }
  // Everything left in its group (what it started with `&`): SIGTERM, then
  // SIGKILL after 10 s. The test is the subreaper: orphans are its children.
  void stop_group() {
    if (pid_ == 0) return;
    signal_group(SIGTERM);
    const auto until = std::chrono::steady_clock::now() + 10s;
    while (group_alive() && std::chrono::steady_clock::now() < until) std::this_thread::sleep_for(20ms);
    if (group_alive()) signal_group(SIGKILL);
    while (group_alive()) std::this_thread::sleep_for(20ms);
    wait(0ms);
  }
  std::string output() const {
    std::ifstream in(output_);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  }

 private:
  void signal_group(int number) const {
    if (pid_ != 0) ::kill(-pid_, number);
  }
  bool group_alive() {
    // Reap what ended (the leader through wait(), orphans here), then look.
    if (!exit_code_) wait(0ms);
    while (true) {
      int status = 0;
      const pid_t r = ::waitpid(-pid_, &status, WNOHANG);
      if (r <= 0) break;
      if (r == pid_ && !exit_code_) exit_code_ = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    }
    return ::kill(-pid_, 0) == 0;
  }

  fs::path output_;
  pid_t pid_ = 0;
  std::optional<int> exit_code_;
};

// ---- the scratch directory and the network namespace ----------------------------------

// A loopback of the test's own: a new network namespace (as root, or in a
// user namespace of its own), lo up. False when the host allows neither.
bool own_network_namespace(std::string& why) {
  static std::optional<bool> done;
  static std::string reason;
  if (done) {
    why = reason;
    return *done;
  }
  const uid_t uid = ::getuid();
  const gid_t gid = ::getgid();
  if (::unshare(CLONE_NEWNET) != 0) {
    if (::unshare(CLONE_NEWUSER | CLONE_NEWNET) != 0) {
      reason = std::string("unshare: ") + std::strerror(errno);
      done = false;
      why = reason;
      return false;
    }
    std::ofstream("/proc/self/setgroups") << "deny";
    std::ofstream("/proc/self/uid_map") << "0 " << uid << " 1";
    std::ofstream("/proc/self/gid_map") << "0 " << gid << " 1";
  }
  const int s = ::socket(AF_INET, SOCK_DGRAM, 0);
  ifreq request{};
  std::strncpy(request.ifr_name, "lo", IFNAMSIZ - 1);
  const bool up = s >= 0 && ::ioctl(s, SIOCGIFFLAGS, &request) == 0 &&
                  (request.ifr_flags |= IFF_UP, ::ioctl(s, SIOCSIFFLAGS, &request) == 0);
  if (s >= 0) ::close(s);
  if (!up) reason = std::string("lo up: ") + std::strerror(errno);
  done = up;
  why = reason;
  return up;
}

class Walkthrough : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string why;
    if (!own_network_namespace(why)) GTEST_SKIP() << "no network namespace of the test's own (" << why << ")";
    ::prctl(PR_SET_CHILD_SUBREAPER, 1);
    scratch_ = fs::temp_directory_path() / ("jaus-docs-" + std::to_string(::getpid()));
    fs::remove_all(scratch_);
    fs::create_directories(scratch_ / "bin");
    fs::create_directory_symlink(kSource / "config", scratch_ / "config");
    const std::map<std::string, std::pair<std::string, std::string>> programs{
        {"jausd", {"jausd", JAUSD_PATH}},
        {"jausctl", {"jausctl", JAUSCTL_PATH}},
        {"clearpath-sim", {"clearpath_sim", CLEARPATH_SIM_PATH}},
        {"jaus-conform", {"jaus_conform", JAUS_CONFORM_PATH}},
        {"jaus-console", {"jaus_console", JAUS_CONSOLE_PATH}}};
    for (const auto& [name, where] : programs) {
      fs::create_symlink(where.second, scratch_ / "bin" / name);
      for (const char* tree : {"build/run/apps", "build/release/apps"}) {
        fs::create_directories(scratch_ / tree / where.first);
        fs::create_symlink(where.second, scratch_ / tree / where.first / name);
      }
    }
    before_ = fs::current_path();
    if (const char* home = std::getenv("HOME")) home_ = home;
    fs::current_path(scratch_);
    const char* path = std::getenv("PATH");
    ::setenv("PATH", ((scratch_ / "bin").string() + ":" + (path ? path : "/usr/bin:/bin")).c_str(), 1);
    // A reader of their own: what the tools keep per user (an OCU identity, ...) goes with the scratch.
    ::setenv("HOME", scratch_.c_str(), 1);
    for (const char* xdg : {"XDG_CONFIG_HOME", "XDG_STATE_HOME", "XDG_CACHE_HOME", "XDG_DATA_HOME", "XDG_RUNTIME_DIR"})
      ::unsetenv(xdg);
    // jausctl's kept ID outside those the docs and this test name with --as
    // (254.1, 254.2, 254.5, 254.7, 254.9, 254.37, 254.99): 254.201.40.1.
    keep_operator_id_outside_named_ones(scratch_ / ".local" / "state", 1);
  }
  void TearDown() override {
    node_.reset();
    if (scratch_.empty()) return;
    fs::current_path(before_);
    if (home_) ::setenv("HOME", home_->c_str(), 1);
    std::error_code ignored;
    fs::remove_all(scratch_, ignored);
  }

  // The default node, as ./scripts/run.sh starts it, Ready to be driven.
  void start_node() {
    if (node_) return;
    node_ = std::make_unique<Command>(
        "exec build/run/apps/jausd/jausd --config config/jausd.yaml --pid-file build/run/jausd.pid",
        scratch_ / "node.log");
    ASSERT_TRUE(node_->started());
    const auto until = std::chrono::steady_clock::now() + 60s;
    while (std::chrono::steady_clock::now() < until) {
      ASSERT_FALSE(node_->wait(0ms)) << "the default node exited:\n" << node_->output();
      Command status("jausctl status 1.1.33.1 --as 254.99.40.1", scratch_ / "node-status.log");
      if (status.wait(20s) == 0 && status.output().find("\"ready\"") != std::string::npos) return;
      std::this_thread::sleep_for(200ms);
    }
    FAIL() << "the default node's primitive driver not Ready within 60 s:\n" << node_->output();
  }
  void stop_node() {
    if (!node_) return;
    node_->interrupt();
    const auto code = node_->wait(20s);
    EXPECT_EQ(code, 0) << "the default node did not stop in order on Ctrl-C:\n" << node_->output();
    node_.reset();
  }

  void run_file(const std::string& relative) {
    const ParsedDoc doc = parse_doc_file((kSource / relative).string(), relative);
    for (const auto& e : doc.errors) ADD_FAILURE() << e;
    check_default_component_lists(doc);
    int run = 0, skipped = 0;
    for (const auto& block : doc.blocks) {
      if (block.language == "sh" && !block.marked) {
        ADD_FAILURE() << block.where() << ": an sh block without a doc-test marker (say what it expects, or skip it and why)";
        continue;
      }
      if (!block.marked || !block.error.empty()) continue;
      if (block.skip) {
        ++skipped;
        continue;
      }
      ++run;
      const auto began = std::chrono::steady_clock::now();
      if (block.language == "sh") run_shell_block(block);
      else if (block.language == "yaml") check_yaml_block(block);
      else ADD_FAILURE() << block.where() << ": a doc-test marker on a '" << block.language << "' block";
      std::cout << block.where() << ": "
                << std::chrono::duration_cast<std::chrono::milliseconds>(std::chrono::steady_clock::now() - began).count()
                << " ms\n";
    }
    stop_node();
    std::cout << relative << ": " << run << " blocks run, " << skipped << " skipped\n";
  }

  void run_shell_block(const DocBlock& block) {
    if (block.node_running) start_node();
    else stop_node();
    if (::testing::Test::HasFatalFailure()) return;
    const auto commands = block.commands();
    if (block.expect_exit.size() != 1 && block.expect_exit.size() != commands.size()) {
      ADD_FAILURE() << block.where() << ": " << block.expect_exit.size() << " exit codes for " << commands.size()
                    << " commands";
      return;
    }
    std::vector<std::unique_ptr<Command>> started;
    std::string output;
    for (std::size_t i = 0; i < commands.size(); ++i) {
      const int expected = block.expect_exit.size() == 1 ? block.expect_exit[0] : block.expect_exit[i];
      auto& command = started.emplace_back(std::make_unique<Command>(
          commands[i], scratch_ / ("block-" + std::to_string(block.line) + "-" + std::to_string(i) + ".log")));
      ASSERT_TRUE(command->started()) << commands[i];
      std::optional<int> code;
      bool interrupted = false;
      static const std::regex background(R"(&\s*(#.*)?$)");
      if (std::regex_search(commands[i], background)) {
        // Left running (stopped at the end of the block); the reader types the next line a moment later.
        code = command->wait(20s);
        std::this_thread::sleep_for(1s);
        EXPECT_EQ(code, 0) << block.where() << ": `" << commands[i] << "`\n" << command->output();
        continue;
      }
      if (block.stop_after_s) {
        code = command->wait(std::chrono::milliseconds(static_cast<int>(*block.stop_after_s * 1000)));
        if (!code) {
          interrupted = true;
          command->interrupt();  // Ctrl-C
          code = command->wait(20s);
        }
      } else {
        code = command->wait(60s);
      }
      const std::string out = command->output();
      if (!code)
        ADD_FAILURE() << block.where() << ": `" << commands[i] << "` still running"
                      << (interrupted ? " 20 s after Ctrl-C" : " after 60 s (if it runs until Ctrl-C, say stop-after=)")
                      << "\n" << out;
      else
        EXPECT_EQ(*code, expected) << block.where() << ": `" << commands[i] << "`"
                                   << (interrupted ? " (ended by Ctrl-C)" : "") << "\n" << out;
    }
    for (auto& command : started) {
      command->stop_group();  // what the block left in the background
      output += command->output();
    }
    for (const auto& pattern : block.expect)
      EXPECT_TRUE(std::regex_search(output, std::regex(pattern)))
          << block.where() << ": nothing in the output matches /" << pattern << "/:\n" << output;
  }

  void check_yaml_block(const DocBlock& block) {
    if (block.excerpt_of) {
      // Every line of the block, in order, among the file's lines without comments.
      std::ifstream in(kSource / *block.excerpt_of);
      std::vector<std::string> file;
      for (std::string l; std::getline(in, l);) {
        // A comment: a line that starts with '#', or from " #" on.
        const auto first = l.find_first_not_of(' ');
        if (first == std::string::npos || l[first] == '#') continue;
        const std::string code = detail::trim(l.substr(0, l.find(" #")));
        if (!code.empty()) file.push_back(code);
      }
      std::size_t at = 0;
      for (const auto& line : block.body) {
        const std::string want = detail::trim(line);
        if (want.empty()) continue;
        while (at < file.size() && file[at] != want) ++at;
        if (at == file.size()) {
          ADD_FAILURE() << block.where() << ": '" << want << "' is not in " << *block.excerpt_of
                        << " (after the block's previous line)";
          break;
        }
        ++at;
      }
    }
    if (block.check_config) {
      const fs::path file = scratch_ / ("block-" + std::to_string(block.line) + ".yaml");
      std::ofstream out(file);
      for (const auto& l : block.body) out << l << "\n";
      out.close();
      Command check("jausd --config " + file.string() + " --check-config", scratch_ / "check-config.log");
      const auto code = check.wait(30s);
      EXPECT_EQ(code, 0) << block.where() << ":\n" << check.output();
      for (const auto& pattern : block.expect)
        EXPECT_TRUE(std::regex_search(check.output(), std::regex(pattern)))
            << block.where() << ": nothing in the output matches /" << pattern << "/:\n" << check.output();
    }
  }

  // The paragraphs marked default-components name every kind of the default
  // list and no other; and that list is jausd's built-in one.
  void check_default_component_lists(const ParsedDoc& doc) {
    std::set<std::string> defaults;
    {
      std::ifstream in(kSource / "config/jausd.yaml");
      const std::regex kind(R"(^\s*- kind: (\w+))");
      std::smatch m;
      for (std::string l; std::getline(in, l);)
        if (std::regex_search(l, m, kind)) defaults.insert(m[1]);
    }
    ASSERT_FALSE(defaults.empty());
    Command builtin("jausd --check-config", scratch_ / "builtin.log");
    ASSERT_EQ(builtin.wait(30s), 0) << builtin.output();
    EXPECT_NE(builtin.output().find(std::to_string(defaults.size()) + " components"), std::string::npos)
        << "config/jausd.yaml lists " << defaults.size() << " components; without a file jausd has:\n"
        << builtin.output();
    for (const auto& p : doc.default_component_lists) {
      std::string text = p.text;
      for (auto& c : text) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
      for (const auto& kind : defaults) {
        std::string words = kind;
        std::replace(words.begin(), words.end(), '_', ' ');
        EXPECT_NE(text.find(words), std::string::npos)
            << p.file << ":" << p.line << ": the default node's components leave out " << words;
      }
      // No built-in kind outside the default list.
      for (const auto& known : host::component_kinds()) {
        std::string words(known.name);
        if (defaults.contains(words)) continue;
        std::replace(words.begin(), words.end(), '_', ' ');
        EXPECT_EQ(text.find(words), std::string::npos)
            << p.file << ":" << p.line << ": " << words << " is not in the default list";
      }
    }
  }

  fs::path scratch_;
  fs::path before_;
  std::optional<std::string> home_;
  std::unique_ptr<Command> node_;
};

TEST_F(Walkthrough, Readme) { run_file("README.md"); }
TEST_F(Walkthrough, TalkToYourNode) { run_file("docs/talk-to-your-node.md"); }
TEST_F(Walkthrough, Configuration) { run_file("docs/configuration.md"); }
TEST_F(Walkthrough, Running) { run_file("docs/running.md"); }

}  // namespace
}  // namespace jaus::test::docs
