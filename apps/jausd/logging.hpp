// jausd's log: one readable line per event on stderr (spdlog), and the
// runtime's LogFn feeding it. Under systemd (stderr is the journal) lines
// carry their syslog priority and no time stamp of their own.
#pragma once

#include <chrono>
#include <memory>
#include <string_view>

#include <spdlog/spdlog.h>

#include "jaus/runtime/environment.hpp"

namespace jausd {

// "debug" | "info" | "warn" | "error" (validated by the configuration).
std::shared_ptr<spdlog::logger> make_logger(std::string_view level);
jaus::rt::LogFn log_function(std::shared_ptr<spdlog::logger> logger);

// Held by main from make_logger on: when main returns, what is still queued
// is written out before the process exits, for at most kLogDrainLimit. An
// output nobody reads (a full pipe, a stopped terminal) does not keep a node
// that has stopped from exiting: it exits with the code main returned through
// exiting_with(), without its last lines.
inline constexpr std::chrono::seconds kLogDrainLimit{5};

class LogDrain {
 public:
  LogDrain() = default;
  LogDrain(const LogDrain&) = delete;
  LogDrain& operator=(const LogDrain&) = delete;
  ~LogDrain();

  int exiting_with(int code) {
    code_ = code;
    return code;
  }

 private:
  int code_ = 1;  // main left without saying (an exception)
};

}  // namespace jausd
