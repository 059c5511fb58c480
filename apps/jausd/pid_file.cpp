#include "pid_file.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <system_error>

namespace jausd {

std::optional<std::filesystem::path> pid_file_path(const std::string& option, const char* runtime_directory) {
  if (!option.empty()) return std::filesystem::path(option);
  if (runtime_directory == nullptr || *runtime_directory == '\0') return std::nullopt;
  std::string first(runtime_directory);
  first = first.substr(0, first.find(':'));  // systemd lists one path per RuntimeDirectory= entry
  return std::filesystem::path(first) / "jausd.pid";
}

jaus::Expected<PidFile> PidFile::write(const std::filesystem::path& path) {
  // Written beside it and renamed: a reader sees the old file or the whole new one.
  std::filesystem::path partial = path;
  partial += ".partial";
  {
    std::ofstream out(partial, std::ios::trunc);
    out << ::getpid() << "\n";
    out.close();
    if (!out)
      return jaus::unexpected(jaus::make_error(jaus::ErrorCode::io, "--pid-file " + path.string() + ": cannot write " +
                                                                        partial.string() + ": " + std::strerror(errno)));
  }
  std::error_code ec;
  std::filesystem::rename(partial, path, ec);
  if (ec) {
    std::filesystem::remove(partial, ec);
    return jaus::unexpected(
        jaus::make_error(jaus::ErrorCode::io, "--pid-file " + path.string() + ": cannot write: " + ec.message()));
  }
  return PidFile(path);
}

PidFile::PidFile(PidFile&& other) noexcept : path_(std::move(other.path_)) { other.path_.clear(); }

PidFile::~PidFile() {
  if (path_.empty()) return;
  // Only our own: a jausd started since with the same file keeps its PID there.
  std::ifstream in(path_);
  long pid = 0;
  if (in >> pid && pid == static_cast<long>(::getpid())) {
    std::error_code ignored;
    std::filesystem::remove(path_, ignored);
  }
}

}  // namespace jausd
