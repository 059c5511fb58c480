#include "jaus/host/emergency_holds.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>

namespace jaus::host {

namespace {
constexpr const char* kFileName = "emergency-holds";
constexpr const char* kOverflow = "overflow";

Error file_error(const std::filesystem::path& file, const std::string& what) {
  return make_error(ErrorCode::io, file.string() + ": " + what);
}
}  // namespace

std::optional<std::filesystem::path> emergency_holds_file(const EmergencySettings& settings) {
  std::string dir = settings.state_directory;
  if (dir.empty()) {
    // systemd may list several directories, separated by colons: the first is ours.
    if (const char* env = std::getenv("STATE_DIRECTORY"); env != nullptr) dir = std::string(env).substr(0, std::string(env).find(':'));
  }
  if (dir.empty()) return std::nullopt;
  return std::filesystem::path(dir) / kFileName;
}

// One line a hold: "<latch> <holder address>" or "<latch> overflow"; '#' starts a comment.
Expected<PersistedHolds> read_emergency_holds(const std::filesystem::path& file) {
  std::error_code ec;
  if (!std::filesystem::exists(file, ec)) {
    if (ec) return unexpected(file_error(file, ec.message()));
    return PersistedHolds{};
  }
  std::ifstream in(file);
  if (!in) return unexpected(file_error(file, std::strerror(errno)));
  PersistedHolds holds;
  int number = 0;
  for (std::string line; std::getline(in, line);) {
    ++number;
    if (line.empty() || line.front() == '#') continue;
    std::istringstream words(line);
    std::string latch, holder, extra;
    words >> latch >> holder >> extra;
    const auto where = file.string() + ":" + std::to_string(number) + ": ";
    if (latch.empty() || holder.empty() || !extra.empty())
      return unexpected(make_error(ErrorCode::malformed, where + "expected '<latch> <holder>', got '" + line + "'"));
    if (holder == kOverflow) {
      holds[latch].overflowed = true;
      continue;
    }
    const auto address = Address::parse(holder);
    if (!address) return unexpected(make_error(ErrorCode::malformed, where + "'" + holder + "' is not an address"));
    holds[latch].holders.push_back(*address);
  }
  if (in.bad()) return unexpected(file_error(file, "read failed"));
  return holds;
}

Expected<void> write_emergency_holds(const std::filesystem::path& file, const PersistedHolds& holds) {
  std::ostringstream text;
  text << "# jausd: Set Emergency holds, restored at start (docs/safety.md). Clear with SIGUSR1 to jausd.\n";
  for (const auto& [latch, hold] : holds) {
    for (const auto& h : hold.holders) text << latch << ' ' << h.to_string() << '\n';
    if (hold.overflowed) text << latch << ' ' << kOverflow << '\n';
  }
  const std::string bytes = text.str();
  const auto temporary = std::filesystem::path(file.string() + ".new");
  const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) return unexpected(file_error(temporary, std::strerror(errno)));
  std::size_t written = 0;
  while (written < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + written, bytes.size() - written);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const std::string why = std::strerror(errno);
      ::close(fd);
      return unexpected(file_error(temporary, why));
    }
    written += static_cast<std::size_t>(n);
  }
  // On the disk before it replaces the old holds: a power cut keeps one or the other.
  if (::fsync(fd) != 0 || ::close(fd) != 0) return unexpected(file_error(temporary, std::strerror(errno)));
  std::error_code ec;
  std::filesystem::rename(temporary, file, ec);
  if (ec) return unexpected(file_error(file, ec.message()));
  return {};
}

}  // namespace jaus::host
