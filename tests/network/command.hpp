// A short command run to its end (ip, nft): its output, or an error that
// quotes the command and what it printed.
#pragma once

#include <unistd.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "../system/child_process.hpp"
#include "jaus/base/error.hpp"
#include "jaus/base/expected.hpp"

namespace jaus::test::network {

inline std::string joined(const std::vector<std::string>& argv) {
  std::string text;
  for (const auto& a : argv) text += (text.empty() ? "" : " ") + a;
  return text;
}

inline jaus::Expected<std::string> run_command(const std::vector<std::string>& argv,
                                               std::chrono::milliseconds deadline = std::chrono::seconds(10)) {
  static std::atomic<int> runs = 0;
  const auto log = std::filesystem::temp_directory_path() /
                   ("jaus-network-command-" + std::to_string(::getpid()) + "-" + std::to_string(runs++) + ".log");
  std::string output;
  std::optional<int> exit_code;
  {
    ChildProcess child(argv, log.string());
    if (!child.started())
      return jaus::unexpected(jaus::make_error(jaus::ErrorCode::io, "cannot start " + joined(argv)));
    exit_code = child.wait(deadline);
    output = child.output();
  }
  std::error_code ignored;
  std::filesystem::remove(log, ignored);
  if (!exit_code)
    return jaus::unexpected(jaus::make_error(jaus::ErrorCode::timeout, joined(argv) + ": still running after " +
                                                                           std::to_string(deadline.count()) + " ms"));
  if (*exit_code != 0)
    return jaus::unexpected(jaus::make_error(
        jaus::ErrorCode::io, joined(argv) + ": exit " + std::to_string(*exit_code) + ": " + output));
  return output;
}

}  // namespace jaus::test::network
