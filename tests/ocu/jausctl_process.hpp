// The built jausctl binary as a child process, for the tests that run it:
// arguments and stdin in; exit code, stdout and stderr (files, no pipe to
// keep drained) out.
#pragma once

#include <gtest/gtest.h>

#include <chrono>
#include <csignal>
#include <cstdlib>
#include <fcntl.h>
#include <fstream>
#include <spawn.h>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>
#include <vector>

extern char** environ;

namespace jausctl::test {

struct Result {
  int exit_code = -1;
  std::string out;
  std::string err;
};

inline std::string read_file(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// jausctl as a child process; stdout and stderr go to files (no pipe to keep drained).
class Jausctl {
 public:
  // `state_home`: the XDG_STATE_HOME it keeps its operator ID in; by default
  // a directory of its own (a fresh ID, never the user's), so tests running
  // at once never share one.
  explicit Jausctl(const std::vector<std::string>& args, const std::string& stdin_text = "",
                   const std::string& state_home = "") {
    char dir_template[] = "/tmp/jausctl_cli_XXXXXX";
    dir_ = mkdtemp(dir_template);
    { std::ofstream(dir_ + "/in") << stdin_text; }
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 0, (dir_ + "/in").c_str(), O_RDONLY, 0);
    posix_spawn_file_actions_addopen(&actions, 1, (dir_ + "/out").c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
    posix_spawn_file_actions_addopen(&actions, 2, (dir_ + "/err").c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
    std::vector<std::string> all{JAUSCTL_PATH};
    all.insert(all.end(), args.begin(), args.end());
    std::vector<char*> argv;
    for (auto& a : all) argv.push_back(a.data());
    argv.push_back(nullptr);
    std::vector<std::string> env_entries;
    for (char** e = environ; *e; ++e)
      if (std::string(*e).rfind("XDG_STATE_HOME=", 0) != 0) env_entries.emplace_back(*e);
    env_entries.push_back("XDG_STATE_HOME=" + (state_home.empty() ? dir_ + "/state" : state_home));
    std::vector<char*> env;
    for (auto& e : env_entries) env.push_back(e.data());
    env.push_back(nullptr);
    if (posix_spawn(&pid_, JAUSCTL_PATH, &actions, nullptr, argv.data(), env.data()) != 0) pid_ = -1;
    posix_spawn_file_actions_destroy(&actions);
  }
  ~Jausctl() {
    if (pid_ > 0) {
      kill(pid_, SIGKILL);
      waitpid(pid_, nullptr, 0);
    }
    std::system(("rm -rf " + dir_).c_str());
  }

  bool started() const { return pid_ > 0; }
  std::string out() const { return read_file(dir_ + "/out"); }
  // Waits (up to 20 s: an ASan binary starting on a loaded machine) until stdout holds `text`.
  bool wait_for_output(const std::string& text) const {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
    while (out().find(text) == std::string::npos) {
      if (std::chrono::steady_clock::now() > deadline) return false;
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    return true;
  }
  void signal(int sig) const { kill(pid_, sig); }
  Result finish() {
    Result r;
    int status = 0;
    if (waitpid(pid_, &status, 0) == pid_ && WIFEXITED(status)) r.exit_code = WEXITSTATUS(status);
    pid_ = -1;
    r.out = out();
    r.err = read_file(dir_ + "/err");
    return r;
  }

 private:
  std::string dir_;
  pid_t pid_ = -1;
};

inline Result run(const std::vector<std::string>& args, const std::string& stdin_text = "") {
  Jausctl child(args, stdin_text);
  EXPECT_TRUE(child.started());
  return child.finish();
}

}  // namespace jausctl::test
