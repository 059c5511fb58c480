// jausd's log: one readable line per event on stderr (spdlog), and the
// runtime's LogFn feeding it.
#pragma once

#include <memory>
#include <string_view>

#include <spdlog/spdlog.h>

#include "jaus/runtime/environment.hpp"

namespace jausd {

// "debug" | "info" | "warn" | "error" (validated by the configuration).
std::shared_ptr<spdlog::logger> make_logger(std::string_view level);
jaus::rt::LogFn log_function(std::shared_ptr<spdlog::logger> logger);

// Held by main from make_logger on: when main returns, what is still queued
// is written out before the process exits.
struct LogDrain {
  LogDrain() = default;
  LogDrain(const LogDrain&) = delete;
  LogDrain& operator=(const LogDrain&) = delete;
  ~LogDrain();
};

}  // namespace jausd
