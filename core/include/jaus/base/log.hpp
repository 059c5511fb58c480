// How every state machine of the project logs: a level and one line, handed
// to a function the application provides (spdlog in jausd, a recorder in
// tests). Nothing here writes anywhere by itself.
#pragma once

#include <functional>
#include <string>

namespace jaus::rt {

enum class LogLevel { debug, info, warn, error };
using LogFn = std::function<void(LogLevel, const std::string&)>;

// A LogFn that drops everything: the default where no log is given.
inline LogFn silent_log() {
  return [](LogLevel, const std::string&) {};
}

}  // namespace jaus::rt
