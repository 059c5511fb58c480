#include "jaus/ocu/operator_identity.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <random>
#include <sstream>

namespace jaus::ocu {

namespace {

namespace fs = std::filesystem;
constexpr const char* kIdFile = "operator-id";
constexpr std::uint8_t kOcuSubsystem = 254;  // session.hpp: kDefaultOcuAddress
constexpr std::uint8_t kOcuComponent = 40;

jaus::Error io_error(const fs::path& file, const std::string& what) {
  return jaus::make_error(jaus::ErrorCode::io, file.string() + ": " + what);
}

jaus::Expected<jaus::Address> read_id(const fs::path& file) {
  std::ifstream in(file);
  if (!in) return jaus::unexpected(io_error(file, std::string("cannot read: ") + std::strerror(errno)));
  std::string text;
  std::getline(in, text, '\0');
  while (!text.empty() && (text.back() == '\n' || text.back() == '\r' || text.back() == ' ')) text.pop_back();
  const auto address = jaus::Address::parse(text);
  if (!address || !address->is_valid() || address->is_broadcast() || address->component == 1)
    return jaus::unexpected(jaus::make_error(
        jaus::ErrorCode::invalid_argument,
        file.string() + ": '" + text + "' is not an OCU address S.N.C.I (1..254 each, component not 1); "
                        "fix or delete the file, or give --as"));
  return *address;
}

}  // namespace

std::optional<fs::path> operator_state_directory() {
  // The XDG base directory rule: a relative $XDG_STATE_HOME is ignored.
  if (const char* xdg = std::getenv("XDG_STATE_HOME"); xdg && *xdg == '/') return fs::path(xdg) / "jaus";
  if (const char* home = std::getenv("HOME"); home && *home) return fs::path(home) / ".local" / "state" / "jaus";
  return std::nullopt;
}

jaus::Address fresh_operator_address() {
  std::random_device entropy;
  std::uniform_int_distribution<int> node(1, 254);
  return jaus::Address{kOcuSubsystem, static_cast<std::uint8_t>(node(entropy)), kOcuComponent, 1};
}

jaus::Expected<jaus::Address> load_operator_id(const fs::path& directory) {
  const fs::path file = directory / kIdFile;
  std::error_code ec;
  if (fs::exists(file, ec)) return read_id(file);
  fs::create_directories(directory, ec);
  if (ec) return jaus::unexpected(io_error(directory, "cannot create: " + ec.message()));
  // Written whole to a temporary file, then linked in place: of two first
  // runs at once, the first link wins and the other reads the winner's ID.
  const fs::path temporary = directory / (std::string(kIdFile) + ".tmp." + std::to_string(::getpid()));
  {
    std::ofstream out(temporary, std::ios::trunc);
    out << fresh_operator_address().to_string() << "\n";
    out.flush();
    if (!out) return jaus::unexpected(io_error(temporary, "cannot write"));
  }
  const int linked = ::link(temporary.c_str(), file.c_str());
  const int link_errno = errno;
  fs::remove(temporary, ec);
  if (linked != 0 && link_errno != EEXIST)
    return jaus::unexpected(io_error(file, std::string("cannot create: ") + std::strerror(link_errno)));
  return read_id(file);
}

jaus::Expected<IdentityLock> IdentityLock::take(const fs::path& directory, const jaus::Address& address) {
  const fs::path folder = directory / "in-use";
  std::error_code ec;
  fs::create_directories(folder, ec);
  if (ec) return jaus::unexpected(io_error(folder, "cannot create: " + ec.message()));
  const fs::path file = folder / (address.to_string() + ".lock");
  const int fd = ::open(file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0600);
  if (fd < 0) return jaus::unexpected(io_error(file, std::string("cannot open: ") + std::strerror(errno)));
  if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
    const int why = errno;
    char pid[32] = {};
    const auto n = ::pread(fd, pid, sizeof pid - 1, 0);
    ::close(fd);
    if (why != EWOULDBLOCK)
      return jaus::unexpected(io_error(file, std::string("cannot lock: ") + std::strerror(why)));
    std::string holder(pid, n > 0 ? static_cast<std::size_t>(n) : 0);
    while (!holder.empty() && (holder.back() == '\n' || holder.back() == ' ')) holder.pop_back();
    return jaus::unexpected(jaus::make_error(
        jaus::ErrorCode::refused,
        address.to_string() + " is in use by another process" + (holder.empty() ? "" : " (pid " + holder + ")")));
  }
  // Who holds it, for the message of the next one (the lock, not the text, is what counts).
  const std::string pid = std::to_string(::getpid()) + "\n";
  if (::ftruncate(fd, 0) == 0) {
    const auto written = ::pwrite(fd, pid.data(), pid.size(), 0);
    (void)written;
  }
  return IdentityLock(fd);
}

IdentityLock& IdentityLock::operator=(IdentityLock&& other) noexcept {
  if (this != &other) {
    if (fd_ >= 0) ::close(fd_);
    fd_ = std::exchange(other.fd_, -1);
  }
  return *this;
}

IdentityLock::~IdentityLock() {
  if (fd_ >= 0) ::close(fd_);  // closing the last descriptor releases the flock
}

jaus::Expected<OperatorId> choose_operator_id(const std::optional<jaus::Address>& as, IdUse use) {
  OperatorId id;
  const auto directory = operator_state_directory();
  if (as) {
    id.address = *as;
  } else if (directory) {
    auto kept = load_operator_id(*directory);
    if (!kept) return jaus::unexpected(kept.error());
    id.address = *kept;
  } else {
    id.address = fresh_operator_address();
    if (use != IdUse::looks)
      id.note = "no state directory (neither HOME nor XDG_STATE_HOME is set): acting as " + id.address.to_string() +
                " for this run only (clear it with --as " + id.address.to_string() + ")";
    return id;
  }
  if (!directory) return id;  // --as without a state directory: nothing to lock in
  auto lock = IdentityLock::take(*directory, id.address);
  if (lock) {
    id.lock = std::move(*lock);
    return id;
  }
  if (lock.error().code != jaus::ErrorCode::refused) {
    // A lock that cannot be made (a read-only disk) never stops a command: said, and it goes on.
    id.note = "cannot tell whether another process acts as " + id.address.to_string() + ": " + lock.error().message();
    return id;
  }
  switch (use) {
    case IdUse::holds:
      return jaus::unexpected(jaus::make_error(
          jaus::ErrorCode::refused,
          lock.error().message() + ": two processes acting as one ID get each other's replies; wait for it to end, "
                                   "or give another ID with --as"));
    case IdUse::shares:  // safety: a stop is never refused (IdUse)
      id.shared = true;
      id.note = lock.error().message() + ": shared with it (only this command's own ACK is read as its answer)";
      return id;
    case IdUse::looks: {
      const jaus::Address busy = id.address;
      do id.address = fresh_operator_address();
      while (id.address.node == busy.node);
      return id;
    }
  }
  return id;
}

}  // namespace jaus::ocu
