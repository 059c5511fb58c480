#include "logging.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <future>
#include <thread>

#include <spdlog/async.h>
#include <spdlog/pattern_formatter.h>
#include <spdlog/sinks/stdout_color_sinks.h>

namespace jausd {

namespace {

// Under systemd, stderr is the journal when JOURNAL_STREAM names it
// ("device:inode", systemd.exec(5)); not when stderr was redirected elsewhere.
bool stderr_is_journal() {
  const char* stream = std::getenv("JOURNAL_STREAM");
  if (stream == nullptr) return false;
  unsigned long long device = 0, inode = 0;
  if (std::sscanf(stream, "%llu:%llu", &device, &inode) != 2) return false;
  struct stat st {};
  if (fstat(STDERR_FILENO, &st) != 0) return false;
  return static_cast<unsigned long long>(st.st_dev) == device && static_cast<unsigned long long>(st.st_ino) == inode;
}

// "<N>" in front of a line is its syslog priority to journald (sd-daemon(3)):
// journalctl -p warning, colours and forwarding to syslog then know the level.
class SyslogPriority final : public spdlog::custom_flag_formatter {
 public:
  void format(const spdlog::details::log_msg& msg, const std::tm&, spdlog::memory_buf_t& dest) override {
    char priority = '6';  // info
    switch (msg.level) {
      case spdlog::level::trace:
      case spdlog::level::debug:
        priority = '7';
        break;
      case spdlog::level::warn:
        priority = '4';
        break;
      case spdlog::level::err:
        priority = '3';
        break;
      case spdlog::level::critical:
        priority = '2';
        break;
      default:
        break;
    }
    const char prefix[] = {'<', priority, '>'};
    dest.append(prefix, prefix + sizeof prefix);
  }
  std::unique_ptr<custom_flag_formatter> clone() const override { return std::make_unique<SyslogPriority>(); }
};

}  // namespace

std::shared_ptr<spdlog::logger> make_logger(std::string_view level) {
  // The event loop never waits on stderr: lines go through a queue to a
  // logging thread, and when the output stalls (a full pipe, a stopped
  // terminal) and the queue is full, the oldest queued lines are dropped,
  // never the controller timeout or a deadman.
  constexpr std::size_t kQueuedLines = 8192;
  spdlog::init_thread_pool(kQueuedLines, 1);
  auto logger = spdlog::create_async_nb<spdlog::sinks::stderr_color_sink_mt>("jausd");
  if (stderr_is_journal()) {
    // The journal stamps every line itself: <6>info    node 1.1: hosts communicator 1.1.35.1
    auto formatter = std::make_unique<spdlog::pattern_formatter>();
    formatter->add_flag<SyslogPriority>('*').set_pattern("%*%-7l %v");
    logger->set_formatter(std::move(formatter));
  } else {
    // 2026-11-21 11:42:07.123 info    node 1.1: hosts communicator 1.1.35.1
    logger->set_pattern("%Y-%m-%d %H:%M:%S.%e %-7l %v");
  }
  logger->set_level(spdlog::level::from_str(std::string(level == "warn" ? "warning" : level)));
  logger->flush_on(spdlog::level::info);
  return logger;
}

jaus::rt::LogFn log_function(std::shared_ptr<spdlog::logger> logger) {
  return [logger = std::move(logger)](jaus::rt::LogLevel level, const std::string& text) {
    switch (level) {
      case jaus::rt::LogLevel::debug: logger->debug(text); break;
      case jaus::rt::LogLevel::info: logger->info(text); break;
      case jaus::rt::LogLevel::warn: logger->warn(text); break;
      case jaus::rt::LogLevel::error: logger->error(text); break;
    }
  };
}

LogDrain::~LogDrain() {
  // The queued lines (the last ones say how the node stopped) are written out
  // by spdlog::shutdown, which waits for the logging thread; that thread may
  // be blocked for good in a write. The node's stop paths have run by now
  // (NodeHost::run: platform commanded to stop), so after the limit the
  // process leaves without the lines; nothing can be said on stderr, which is
  // what is stalled.
  std::promise<void> done;
  std::future<void> drained = done.get_future();
  std::thread drainer([&done] {
    spdlog::shutdown();
    done.set_value();
  });
  if (drained.wait_for(kLogDrainLimit) == std::future_status::ready) {
    drainer.join();
    return;
  }
  std::_Exit(code_);
}

}  // namespace jausd
