// A program started for a test (jausd, jausctl), its stderr and stdout in a
// file, stopped with a signal and waited for with a deadline. Its stdin is the
// test's, or with Stdin::pipe a pipe the test writes to (write_stdin).
#pragma once

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>
#include <thread>
#include <algorithm>
#include <vector>

extern char** environ;

namespace jaus::test {

class ChildProcess {
 public:
  enum class Stdin { inherit, pipe };

  // `environment`: "NAME=value" entries that replace or add to this process's own.
  ChildProcess(const std::vector<std::string>& argv, std::string output_file, Stdin in = Stdin::inherit,
               const std::vector<std::string>& environment = {})
      : output_(std::move(output_file)) {
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    int pipe_fds[2] = {-1, -1};
    // Close-on-exec: only the dup2'd copy (fd 0) reaches the child, and no later child holds the write end.
    if (in == Stdin::pipe && ::pipe2(pipe_fds, O_CLOEXEC) == 0) {
      // A child that exited must not kill the test with SIGPIPE: write_stdin() returns false instead.
      ::signal(SIGPIPE, SIG_IGN);
      posix_spawn_file_actions_adddup2(&actions, pipe_fds[0], 0);
      stdin_fd_ = pipe_fds[1];
    }
    posix_spawn_file_actions_addopen(&actions, 1, output_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_adddup2(&actions, 1, 2);
    std::vector<char*> args;
    for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    std::vector<std::string> env_entries;
    for (char** e = environ; *e; ++e) {
      const std::string entry(*e);
      const auto name = entry.substr(0, entry.find('=') + 1);
      const bool replaced = std::any_of(environment.begin(), environment.end(),
                                        [&](const std::string& o) { return o.rfind(name, 0) == 0; });
      if (!replaced) env_entries.push_back(entry);
    }
    env_entries.insert(env_entries.end(), environment.begin(), environment.end());
    std::vector<char*> env;
    for (auto& e : env_entries) env.push_back(e.data());
    env.push_back(nullptr);
    if (posix_spawn(&pid_, args[0], &actions, nullptr, args.data(), env.data()) != 0) pid_ = 0;
    posix_spawn_file_actions_destroy(&actions);
    if (pipe_fds[0] >= 0) ::close(pipe_fds[0]);
  }
  ~ChildProcess() {
    close_stdin();
    if (running()) {
      signal(SIGKILL);
      wait(std::chrono::seconds(5));
    }
  }
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;

  bool started() const { return pid_ != 0; }
  bool running() const { return pid_ != 0 && !exit_code_; }
  void signal(int number) const {
    if (pid_ != 0) ::kill(pid_, number);
  }
  // The exit code (128 + signal when killed), or nothing if still running at the deadline.
  std::optional<int> wait(std::chrono::milliseconds deadline) {
    const auto until = std::chrono::steady_clock::now() + deadline;
    while (!exit_code_ && pid_ != 0) {
      int status = 0;
      const pid_t r = ::waitpid(pid_, &status, WNOHANG);
      if (r == pid_) {
        exit_code_ = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
        break;
      }
      if (std::chrono::steady_clock::now() > until) break;
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return exit_code_;
  }
  // Writes all of text to the child's stdin (Stdin::pipe only); false if it
  // has no pipe or the child no longer reads (exited, closed its stdin).
  bool write_stdin(std::string_view text) {
    while (!text.empty() && stdin_fd_ >= 0) {
      const ssize_t n = ::write(stdin_fd_, text.data(), text.size());
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) return false;
      text.remove_prefix(static_cast<std::size_t>(n));
    }
    return text.empty();
  }
  // End of input for the child (it reads EOF).
  void close_stdin() {
    if (stdin_fd_ >= 0) ::close(stdin_fd_);
    stdin_fd_ = -1;
  }
  std::string output() const {
    std::ifstream in(output_);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  }
  bool output_contains(const std::string& text) const { return output().find(text) != std::string::npos; }
  // Whether text appears in the output within `within`. A running jausd
  // writes its log through a queue to a logging thread (apps/jausd/logging.cpp):
  // a line about what just happened may reach the file a moment later.
  bool output_shows(const std::string& text, std::chrono::milliseconds within = std::chrono::seconds(3)) const {
    const auto until = std::chrono::steady_clock::now() + within;
    while (!output_contains(text)) {
      if (std::chrono::steady_clock::now() > until) return false;
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    return true;
  }

 private:
  std::string output_;
  pid_t pid_ = 0;
  std::optional<int> exit_code_;
  int stdin_fd_ = -1;  // write end of the child's stdin pipe
};

}  // namespace jaus::test
