// Headless Chromium for tests, driven over the DevTools protocol (CDP) on one
// WebSocket (Boost.Beast): Chromium started in a temporary profile directory
// of its own (killed with its children and the directory removed at the end),
// a CDP connection with flattened sessions, and a tab a test reads and types
// into. Every wait has a deadline; nothing throws.
#pragma once

#include <sys/types.h>

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/core/flat_buffer.hpp>
#include <boost/beast/websocket/stream.hpp>
#include <chrono>
#include <deque>
#include <filesystem>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "jaus/base/expected.hpp"

namespace jaus::test::browser {

using Json = nlohmann::json;
using Clock = std::chrono::steady_clock;
using namespace std::chrono_literals;

// Chromium's path ($JAUS_CHROMIUM, else /usr/bin/chromium if it is there), or nothing.
std::optional<std::filesystem::path> find_chromium();

// One headless Chromium process group and its profile directory.
class Chromium {
 public:
  // Starts Chromium (its window `width` x `height`) and waits for its DevTools endpoint.
  static Expected<std::unique_ptr<Chromium>> launch(int width = 1400, int height = 1000,
                                                    std::chrono::milliseconds deadline = 30s);
  ~Chromium();
  Chromium(const Chromium&) = delete;
  Chromium& operator=(const Chromium&) = delete;

  int port() const { return port_; }
  const std::string& browser_path() const { return browser_path_; }  // /devtools/browser/<id>
  std::string log() const;                                          // Chromium's stderr, for failures
  const std::filesystem::path& directory() const { return dir_; }   // removed when this goes

 private:
  Chromium() = default;
  pid_t pid_ = 0;
  std::filesystem::path dir_;
  int port_ = 0;
  std::string browser_path_;
};

// A CDP connection to the browser target; commands go to a session
// (a tab) or, with no session, to the browser.
class CdpClient {
 public:
  static Expected<std::unique_ptr<CdpClient>> connect(const Chromium& chromium,
                                                      std::chrono::milliseconds deadline = 10s);
  ~CdpClient();
  CdpClient(const CdpClient&) = delete;
  CdpClient& operator=(const CdpClient&) = delete;

  // Sends `method` and waits for its answer: the result, or the protocol's error as an Error.
  Expected<Json> call(const std::string& method, Json params = Json::object(), const std::string& session = "",
                      std::chrono::milliseconds deadline = 15s);
  // The next event `method` of `session` (earlier ones of other kinds stay queued).
  Expected<Json> wait_event(const std::string& method, const std::string& session,
                            std::chrono::milliseconds deadline);
  // Forgets queued events of `session` (before an action whose event a test then awaits).
  void forget_events(const std::string& session);

 private:
  CdpClient();
  // Reads one message into responses_ or events_, waiting at most until `until`.
  Expected<void> read_one(Clock::time_point until);
  Expected<void> write(const std::string& text, Clock::time_point until);

  boost::asio::io_context io_;
  boost::beast::websocket::stream<boost::asio::ip::tcp::socket> socket_;
  boost::beast::flat_buffer buffer_;
  bool reading_ = false;
  bool read_done_ = false;
  boost::system::error_code read_error_;
  int next_id_ = 1;
  std::map<int, Json> responses_;
  std::deque<Json> events_;
};

// A tab: a page target attached with a flattened session.
class Tab {
 public:
  static Expected<Tab> open(CdpClient& cdp, const std::string& url, std::chrono::milliseconds deadline = 20s);

  const std::string& target_id() const { return target_; }
  const std::string& session() const { return session_; }

  // Goes to `url` and waits for its load event.
  Expected<void> navigate(const std::string& url, std::chrono::milliseconds deadline = 20s);
  // Evaluates `expression` in the page (promises awaited): its value as JSON.
  Expected<Json> evaluate(const std::string& expression);
  // Evaluates `expression` every 50 ms until it is true; its last value either way.
  Expected<Json> wait_until(const std::string& expression, std::chrono::milliseconds deadline);
  // A key pressed or let go, as the keyboard would: `key` is a DOM key code ("ArrowUp", "KeyW", "Space").
  Expected<void> key_down(const std::string& code);
  Expected<void> key_up(const std::string& code);
  // A left click in the middle of the first element `selector` matches (scrolled into view first).
  Expected<void> click(const std::string& selector);
  // The middle of the first element `selector` matches, in the viewport (scrolled into view first).
  Expected<Json> center_of(const std::string& selector);
  // One mouse event ("mousePressed", "mouseMoved", "mouseReleased") at x, y with the left button.
  Expected<void> mouse(const std::string& type, double x, double y);
  // The visible page as a PNG file.
  Expected<void> screenshot(const std::filesystem::path& file);
  // Closes the tab as the operator would (the page gets pagehide; its socket closes), and waits until it is gone.
  Expected<void> close(std::chrono::milliseconds deadline = 10s);

 private:
  Tab(CdpClient& cdp, std::string target, std::string session)
      : cdp_(&cdp), target_(std::move(target)), session_(std::move(session)) {}
  Expected<void> key(const std::string& type, const std::string& code);

  CdpClient* cdp_;
  std::string target_;
  std::string session_;
};

}  // namespace jaus::test::browser
