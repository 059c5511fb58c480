// jausd's PID file: where the local clear (SIGUSR1) finds this one jausd
// when a host runs several (`kill -USR1 "$(cat PATH)"`), instead of
// `pidof jausd`, which names every one of them. Written once the node is
// listening, removed at exit when it still names this process.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include "jaus/base/expected.hpp"

namespace jausd {

// Where the PID file goes: `--pid-file` when given; else, under systemd
// (RuntimeDirectory=jausd: $RUNTIME_DIRECTORY, the first of its paths),
// $RUNTIME_DIRECTORY/jausd.pid; else nowhere.
std::optional<std::filesystem::path> pid_file_path(const std::string& option, const char* runtime_directory);

class PidFile {
 public:
  // Writes this process's ID (written whole: a reader never sees half of it).
  static jaus::Expected<PidFile> write(const std::filesystem::path& path);
  PidFile(PidFile&& other) noexcept;
  PidFile& operator=(PidFile&&) = delete;
  PidFile(const PidFile&) = delete;
  PidFile& operator=(const PidFile&) = delete;
  ~PidFile();

 private:
  explicit PidFile(std::filesystem::path path) : path_(std::move(path)) {}
  std::filesystem::path path_;  // empty once moved from
};

}  // namespace jausd
