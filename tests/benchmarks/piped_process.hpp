// A program a benchmark starts and talks to (clearpath-sim, jausd): its
// standard input a pipe the benchmark writes to, its standard output either a
// pipe read line by line on a thread of its own (each line kept, to be waited
// for) or a file. Stopped with SIGTERM and waited for with a deadline, SIGKILL
// after it. No GoogleTest: a benchmark is a program, not a test.
#pragma once

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <condition_variable>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

extern char** environ;

namespace jaus::bench {

class PipedProcess {
 public:
  // stdout_file empty: stdout is read as lines (lines(), wait_for_line());
  // else stdout and stderr go to that file. With lines, stderr goes to
  // stderr_file (or is the benchmark's own when empty).
  PipedProcess(const std::vector<std::string>& argv, const std::string& stdout_file,
               const std::string& stderr_file = {}) {
    // A child that exited must not kill the benchmark with SIGPIPE: write_stdin() returns false instead.
    ::signal(SIGPIPE, SIG_IGN);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    // Close-on-exec: only the dup2'd copies reach the child, and no later child holds our ends.
    int in[2] = {-1, -1}, out[2] = {-1, -1};
    if (::pipe2(in, O_CLOEXEC) == 0) {
      posix_spawn_file_actions_adddup2(&actions, in[0], 0);
      stdin_fd_ = in[1];
    }
    if (stdout_file.empty()) {
      if (::pipe2(out, O_CLOEXEC) == 0) posix_spawn_file_actions_adddup2(&actions, out[1], 1);
      if (!stderr_file.empty())
        posix_spawn_file_actions_addopen(&actions, 2, stderr_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    } else {
      posix_spawn_file_actions_addopen(&actions, 1, stdout_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      posix_spawn_file_actions_adddup2(&actions, 1, 2);
    }
    std::vector<char*> args;
    for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    if (posix_spawn(&pid_, args[0], &actions, nullptr, args.data(), environ) != 0) pid_ = 0;
    posix_spawn_file_actions_destroy(&actions);
    if (in[0] >= 0) ::close(in[0]);
    if (out[1] >= 0) ::close(out[1]);  // our copy closed: the reader sees EOF when the child exits
    if (out[0] >= 0) reader_ = std::thread([this, fd = out[0]] { read_lines(fd); });
  }
  ~PipedProcess() {
    stop(std::chrono::seconds(5));
    if (reader_.joinable()) reader_.join();
  }
  PipedProcess(const PipedProcess&) = delete;
  PipedProcess& operator=(const PipedProcess&) = delete;

  bool started() const { return pid_ != 0; }
  pid_t pid() const { return pid_; }

  // Writes all of text to the child's stdin; false if the child no longer reads.
  bool write_stdin(std::string_view text) {
    while (!text.empty() && stdin_fd_ >= 0) {
      const ssize_t n = ::write(stdin_fd_, text.data(), text.size());
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) return false;
      text.remove_prefix(static_cast<std::size_t>(n));
    }
    return text.empty();
  }

  // How many lines were read so far: a mark to wait for lines after.
  std::size_t line_count() const {
    std::lock_guard lock(mutex_);
    return lines_.size();
  }
  // The first line from index `from` on that `match` accepts, waiting until `deadline`.
  std::optional<std::string> wait_for_line(std::size_t from, const std::function<bool(const std::string&)>& match,
                                           std::chrono::steady_clock::time_point deadline) const {
    std::unique_lock lock(mutex_);
    for (std::size_t i = from;; ++i) {
      if (!changed_.wait_until(lock, deadline, [&] { return i < lines_.size() || ended_; })) return std::nullopt;
      if (i >= lines_.size()) return std::nullopt;  // ended
      if (match(lines_[i])) return lines_[i];
    }
  }
  // Every line from index `from` on that `match` accepts (no waiting).
  std::vector<std::string> lines_since(std::size_t from, const std::function<bool(const std::string&)>& match) const {
    std::lock_guard lock(mutex_);
    std::vector<std::string> out;
    for (std::size_t i = from; i < lines_.size(); ++i)
      if (match(lines_[i])) out.push_back(lines_[i]);
    return out;
  }

  // SIGTERM, then SIGKILL if it has not exited by `deadline`. The exit code
  // (128 + signal when killed by one), or nothing if it never ran.
  std::optional<int> stop(std::chrono::milliseconds deadline) {
    if (pid_ == 0 || exit_code_) return exit_code_;
    if (stdin_fd_ >= 0) ::close(stdin_fd_);
    stdin_fd_ = -1;
    ::kill(pid_, SIGTERM);
    if (!wait(deadline)) {
      ::kill(pid_, SIGKILL);
      wait(std::chrono::seconds(5));
    }
    return exit_code_;
  }

 private:
  std::optional<int> wait(std::chrono::milliseconds deadline) {
    const auto until = std::chrono::steady_clock::now() + deadline;
    while (!exit_code_) {
      int status = 0;
      if (::waitpid(pid_, &status, WNOHANG) == pid_) {
        exit_code_ = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
        break;
      }
      if (std::chrono::steady_clock::now() > until) break;
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return exit_code_;
  }

  void read_lines(int fd) {
    std::string pending;
    char buffer[4096];
    for (;;) {
      const ssize_t n = ::read(fd, buffer, sizeof buffer);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) break;
      pending.append(buffer, static_cast<std::size_t>(n));
      std::size_t newline;
      std::lock_guard lock(mutex_);
      while ((newline = pending.find('\n')) != std::string::npos) {
        lines_.push_back(pending.substr(0, newline));
        pending.erase(0, newline + 1);
      }
      changed_.notify_all();
    }
    ::close(fd);
    std::lock_guard lock(mutex_);
    ended_ = true;
    changed_.notify_all();
  }

  pid_t pid_ = 0;
  std::optional<int> exit_code_;
  int stdin_fd_ = -1;  // write end of the child's stdin
  std::thread reader_;
  mutable std::mutex mutex_;
  mutable std::condition_variable changed_;
  std::vector<std::string> lines_;
  bool ended_ = false;  // the child closed its stdout
};

}  // namespace jaus::bench
