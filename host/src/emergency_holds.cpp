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

std::filesystem::path generation_file(const std::filesystem::path& holds_file) {
  return std::filesystem::path(holds_file.string() + ".generation");
}

std::string to_string(HolderDialect dialect) {
  switch (dialect) {
    case HolderDialect::ra: return "ra";
    case HolderDialect::jss: return "jss";
    case HolderDialect::unknown: break;
  }
  return "unknown";
}

std::string ipv4_to_string(std::uint32_t address) {
  return std::to_string(address >> 24) + "." + std::to_string((address >> 16) & 0xFF) + "." +
         std::to_string((address >> 8) & 0xFF) + "." + std::to_string(address & 0xFF);
}

namespace {

std::optional<std::uint32_t> parse_ipv4(const std::string& text) {
  std::uint32_t address = 0;
  int octets = 0;
  std::istringstream in(text);
  for (std::string part; std::getline(in, part, '.');) {
    if (part.empty() || part.size() > 3 || part.find_first_not_of("0123456789") != std::string::npos) return std::nullopt;
    const int value = std::stoi(part);
    if (value > 255) return std::nullopt;
    address = (address << 8) | static_cast<std::uint32_t>(value);
    ++octets;
  }
  if (octets != 4) return std::nullopt;
  return address;
}

// "-": no host known.
Expected<std::optional<std::uint32_t>> parse_host(const std::string& text, const std::string& where) {
  if (text == "-") return std::optional<std::uint32_t>{};
  const auto address = parse_ipv4(text);
  if (!address) return unexpected(make_error(ErrorCode::malformed, where + "'" + text + "' is not an IPv4 address"));
  return std::optional<std::uint32_t>{*address};
}

Expected<std::optional<std::uint64_t>> read_generation(const std::filesystem::path& file) {
  std::error_code ec;
  if (!std::filesystem::exists(file, ec)) {
    if (ec) return unexpected(file_error(file, ec.message()));
    return std::optional<std::uint64_t>{};
  }
  std::ifstream in(file);
  std::string word, extra;
  if (!(in >> word) || (in >> extra) || word.find_first_not_of("0123456789") != std::string::npos || word.size() > 19)
    return unexpected(make_error(ErrorCode::malformed, file.string() + ": expected one generation number"));
  return std::optional<std::uint64_t>{std::stoull(word)};
}

Expected<void> write_whole(const std::filesystem::path& file, const std::string& bytes) {
  const auto temporary = std::filesystem::path(file.string() + ".new");
  const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) return unexpected(file_error(temporary, std::strerror(errno)));
  std::size_t written = 0;
  while (written < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + written, bytes.size() - written);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const std::string why = n == 0 ? "nothing written" : std::strerror(errno);
      ::close(fd);
      return unexpected(file_error(temporary, why));
    }
    written += static_cast<std::size_t>(n);
  }
  // On the disk before it replaces the old one: a power cut keeps one or the other.
  if (::fsync(fd) != 0) {
    const std::string why = std::strerror(errno);
    ::close(fd);
    return unexpected(file_error(temporary, why));
  }
  if (::close(fd) != 0) return unexpected(file_error(temporary, std::strerror(errno)));
  std::error_code ec;
  std::filesystem::rename(temporary, file, ec);
  if (ec) return unexpected(file_error(file, ec.message()));
  return {};
}

}  // namespace

// One line a hold:
//   generation <n>                                  (once, first)
//   <latch> ra <holder address> <host>              an RA holder, e.g. "vehicle ra 3.1.40.1 192.168.1.20"
//   <latch> jss <alias address> <JSS ID> <host>     a JSS client, e.g. "vehicle jss 250.1.40.1 200.5.40 192.168.1.21"
//   <latch> overflow                                holders beyond the recorded ones
// <host> is "-" when the node did not know it. '#' starts a comment. The
// previous version's lines, "<latch> <holder address>", are read as holders
// bound to no host.
Expected<PersistedState> read_emergency_holds(const std::filesystem::path& file) {
  const auto sidecar = generation_file(file);
  auto recorded = read_generation(sidecar);
  if (!recorded) return unexpected(recorded.error());
  std::error_code ec;
  if (!std::filesystem::exists(file, ec)) {
    if (ec) return unexpected(file_error(file, ec.message()));
    if (*recorded)  // holds were written, and the file is gone: not "no holds"
      return unexpected(make_error(ErrorCode::io, file.string() + ": missing, but generation " +
                                                      std::to_string(**recorded) + " was written (" +
                                                      sidecar.string() + ")"));
    return PersistedState{};
  }
  std::ifstream in(file);
  if (!in) return unexpected(file_error(file, std::strerror(errno)));
  PersistedState state;
  std::optional<std::uint64_t> generation;
  bool old_lines = false;
  int number = 0;
  for (std::string line; std::getline(in, line);) {
    ++number;
    if (line.empty() || line.front() == '#') continue;
    std::istringstream stream(line);
    std::vector<std::string> words;
    for (std::string w; stream >> w;) words.push_back(w);
    const auto where = file.string() + ":" + std::to_string(number) + ": ";
    const auto malformed = [&] {
      return unexpected(make_error(ErrorCode::malformed, where + "expected '<latch> ra <holder> <host>', "
                                                                 "'<latch> jss <alias> <JSS ID> <host>' or "
                                                                 "'<latch> overflow', got '" + line + "'"));
    };
    if (words.size() == 2 && words[0] == "generation") {
      if (generation || words[1].find_first_not_of("0123456789") != std::string::npos || words[1].size() > 19)
        return unexpected(make_error(ErrorCode::malformed, where + "a second or malformed generation line"));
      generation = std::stoull(words[1]);
      continue;
    }
    if (words.size() < 2) return malformed();
    const std::string& latch = words[0];
    if (words.size() == 2 && words[1] == kOverflow) {
      state.holds[latch].overflowed = true;
      continue;
    }
    PersistedHolder holder;
    std::string address_text, host_text;
    if (words.size() == 2) {  // the previous version's: an address, no dialect, no host
      address_text = words[1];
      old_lines = true;
    } else if (words.size() == 4 && words[1] == "ra") {
      holder.dialect = HolderDialect::ra;
      address_text = words[2];
      host_text = words[3];
    } else if (words.size() == 5 && words[1] == "jss") {
      holder.dialect = HolderDialect::jss;
      address_text = words[2];
      holder.jss_client = jss::JssId::parse(words[3]);
      if (!holder.jss_client)
        return unexpected(make_error(ErrorCode::malformed, where + "'" + words[3] + "' is not a JSS ID"));
      host_text = words[4];
    } else {
      return malformed();
    }
    const auto address = Address::parse(address_text);
    if (!address) return unexpected(make_error(ErrorCode::malformed, where + "'" + address_text + "' is not an address"));
    holder.holder = *address;
    if (!host_text.empty()) {
      auto host = parse_host(host_text, where);
      if (!host) return unexpected(host.error());
      holder.host = *host;
    }
    state.holds[latch].holders.push_back(std::move(holder));
  }
  if (in.bad()) return unexpected(file_error(file, "read failed"));
  // A stale file is as unknown as an unreadable one (fail safe): the sidecar
  // is written first, so it names the last change begun.
  if (generation.value_or(0) != recorded->value_or(0) || (generation && !*recorded))
    return unexpected(make_error(
        ErrorCode::io, file.string() + ": stale: it holds generation " +
                           (generation ? std::to_string(*generation) : std::string("none")) + ", the last written was " +
                           (*recorded ? std::to_string(**recorded) : std::string("none")) + " (" + sidecar.string() + ")"));
  if (generation && old_lines)
    return unexpected(make_error(ErrorCode::malformed, file.string() + ": lines without dialect and host after a generation"));
  state.generation = generation.value_or(0);
  state.previous_version = !generation;
  return state;
}

Expected<void> write_emergency_holds(const std::filesystem::path& file, const PersistedHolds& holds,
                                     std::uint64_t generation) {
  std::ostringstream text;
  text << "# jausd: Set Emergency holds, restored at start (docs/safety.md). Clear with SIGUSR1 to jausd.\n";
  text << "generation " << generation << '\n';
  for (const auto& [latch, hold] : holds) {
    for (const auto& h : hold.holders) {
      const std::string host = h.host ? ipv4_to_string(*h.host) : std::string("-");
      if (h.dialect == HolderDialect::jss && h.jss_client)
        text << latch << " jss " << h.holder.to_string() << ' ' << h.jss_client->to_string() << ' ' << host << '\n';
      else  // an unknown dialect is written as RA bound to no host (restored for the local clear only)
        text << latch << " ra " << h.holder.to_string() << ' '
             << (h.dialect == HolderDialect::ra ? host : std::string("-")) << '\n';
    }
    if (hold.overflowed) text << latch << ' ' << kOverflow << '\n';
  }
  // The sidecar first: a crash between the two leaves a stale holds file, read as unreadable.
  if (auto written = write_whole(generation_file(file), std::to_string(generation) + "\n"); !written)
    return unexpected(written.error());
  return write_whole(file, text.str());
}

Expected<void> check_state_directory(const std::filesystem::path& directory) {
  std::error_code ec;
  if (std::filesystem::exists(directory, ec) && !std::filesystem::is_directory(directory, ec))
    return unexpected(file_error(directory, "is not a directory"));
  std::filesystem::create_directories(directory, ec);
  if (ec) return unexpected(file_error(directory, "cannot be created: " + ec.message()));
  const auto probe = directory / ".jausd-write-probe";
  if (auto written = write_whole(probe, "jausd checks it can keep its emergency holds here\n"); !written)
    return unexpected(make_error(ErrorCode::io, "state directory " + directory.string() +
                                                    " cannot be written: " + written.error().message()));
  std::filesystem::remove(probe, ec);
  return {};
}

}  // namespace jaus::host
