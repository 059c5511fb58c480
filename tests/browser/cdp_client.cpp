#include "cdp_client.hpp"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <boost/asio/connect.hpp>
#include <boost/beast/core/detail/base64.hpp>
#include <boost/beast/core/buffers_to_string.hpp>
#include <boost/beast/websocket.hpp>
#include <cstdlib>
#include <fstream>
#include <random>
#include <sstream>
#include <thread>
#include <vector>

extern char** environ;

namespace jaus::test::browser {

namespace {

namespace beast = boost::beast;
namespace asio = boost::asio;

Unexpected<Error> fail(ErrorCode code, std::string detail) { return unexpected(make_error(code, std::move(detail))); }

std::string read_text(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// The DOM code's key, and Windows virtual key code, for the keys tests press.
struct KeyInfo {
  std::string key;
  int virtual_code;
};
std::optional<KeyInfo> key_info(const std::string& code) {
  static const std::map<std::string, KeyInfo> keys{
      {"ArrowUp", {"ArrowUp", 38}}, {"ArrowDown", {"ArrowDown", 40}}, {"ArrowLeft", {"ArrowLeft", 37}},
      {"ArrowRight", {"ArrowRight", 39}}, {"KeyW", {"w", 87}}, {"KeyA", {"a", 65}}, {"KeyS", {"s", 83}},
      {"KeyD", {"d", 68}}, {"Space", {" ", 32}}, {"Escape", {"Escape", 27}}};
  const auto it = keys.find(code);
  if (it == keys.end()) return std::nullopt;
  return it->second;
}

}  // namespace

std::optional<std::filesystem::path> find_chromium() {
  if (const char* configured = std::getenv("JAUS_CHROMIUM"); configured && *configured) {
    if (::access(configured, X_OK) == 0) return std::filesystem::path(configured);
    return std::nullopt;
  }
  for (const char* candidate : {"/usr/bin/chromium", "/usr/bin/chromium-browser"})
    if (::access(candidate, X_OK) == 0) return std::filesystem::path(candidate);
  return std::nullopt;
}

// ---------------------------------------------------------------------------- Chromium

Expected<std::unique_ptr<Chromium>> Chromium::launch(int width, int height, std::chrono::milliseconds deadline) {
  const auto binary = find_chromium();
  if (!binary) return fail(ErrorCode::io, "Chromium is not installed (apt-get install chromium)");
  std::unique_ptr<Chromium> chromium(new Chromium);
  std::random_device random;
  chromium->dir_ = std::filesystem::temp_directory_path() /
                   ("jaus-chromium-" + std::to_string(::getpid()) + "-" + std::to_string(random()));
  std::error_code ec;
  std::filesystem::create_directories(chromium->dir_ / "profile", ec);
  if (ec) return fail(ErrorCode::io, "cannot create " + chromium->dir_.string() + ": " + ec.message());

  // The flags keep Chromium off the network (this machine may have none) and out of any first-run dialogue.
  const std::vector<std::string> argv{binary->string(),
                                      "--headless=new",
                                      "--no-sandbox",
                                      "--disable-gpu",
                                      "--disable-quic",
                                      "--no-first-run",
                                      "--no-default-browser-check",
                                      "--disable-background-networking",
                                      "--disable-component-update",
                                      "--disable-sync",
                                      "--disable-extensions",
                                      "--disable-background-timer-throttling",
                                      "--disable-renderer-backgrounding",
                                      "--disable-backgrounding-occluded-windows",
                                      "--hide-scrollbars",
                                      "--window-size=" + std::to_string(width) + "," + std::to_string(height),
                                      "--user-data-dir=" + (chromium->dir_ / "profile").string(),
                                      "--remote-debugging-port=0",
                                      "about:blank"};
  std::vector<char*> args;
  for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  const std::string log_file = (chromium->dir_ / "chromium.log").string();
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 1, log_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, 1, 2);
  // A process group of its own: its renderers and helpers are killed with it.
  posix_spawnattr_t attributes;
  posix_spawnattr_init(&attributes);
  posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETPGROUP);
  posix_spawnattr_setpgroup(&attributes, 0);
  const int spawned = posix_spawn(&chromium->pid_, args[0], &actions, &attributes, args.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  posix_spawnattr_destroy(&attributes);
  if (spawned != 0) {
    chromium->pid_ = 0;
    return fail(ErrorCode::io, "cannot start " + binary->string());
  }

  // Chromium writes its port and browser path here once it listens.
  const auto port_file = chromium->dir_ / "profile" / "DevToolsActivePort";
  const auto until = Clock::now() + deadline;
  while (Clock::now() < until) {
    std::istringstream lines(read_text(port_file));
    std::string port, path;
    if (std::getline(lines, port) && std::getline(lines, path) && !path.empty()) {
      chromium->port_ = std::atoi(port.c_str());
      chromium->browser_path_ = path;
      return chromium;
    }
    int status = 0;
    if (::waitpid(chromium->pid_, &status, WNOHANG) == chromium->pid_) {
      chromium->pid_ = 0;
      return fail(ErrorCode::io, "Chromium exited at start: " + chromium->log());
    }
    std::this_thread::sleep_for(50ms);
  }
  return fail(ErrorCode::timeout, "Chromium did not open its DevTools port: " + chromium->log());
}

Chromium::~Chromium() {
  if (pid_ != 0) {
    ::kill(-pid_, SIGTERM);
    const auto until = Clock::now() + 5s;
    int status = 0;
    while (::waitpid(pid_, &status, WNOHANG) == 0 && Clock::now() < until) std::this_thread::sleep_for(20ms);
    ::kill(-pid_, SIGKILL);  // helpers that outlived the browser, or a browser that did not stop
    ::waitpid(pid_, &status, WNOHANG);
  }
  std::error_code ignored;
  if (!dir_.empty()) std::filesystem::remove_all(dir_, ignored);
}

std::string Chromium::log() const { return read_text(dir_ / "chromium.log"); }

// ---------------------------------------------------------------------------- CdpClient

CdpClient::CdpClient() : socket_(io_) {}
CdpClient::~CdpClient() {
  boost::system::error_code ignored;
  socket_.next_layer().close(ignored);
}

Expected<std::unique_ptr<CdpClient>> CdpClient::connect(const Chromium& chromium, std::chrono::milliseconds deadline) {
  std::unique_ptr<CdpClient> client(new CdpClient);
  const asio::ip::tcp::endpoint endpoint(asio::ip::make_address_v4("127.0.0.1"),
                                         static_cast<unsigned short>(chromium.port()));
  boost::system::error_code ec;
  const auto until = Clock::now() + deadline;
  do {
    client->socket_.next_layer().close(ec);
    client->socket_.next_layer().connect(endpoint, ec);
    if (!ec) break;
    std::this_thread::sleep_for(50ms);
  } while (Clock::now() < until);
  if (ec) return fail(ErrorCode::io, "cannot connect to Chromium's DevTools port: " + ec.message());
  client->socket_.read_message_max(256u << 20);  // screenshots arrive as one large message
  client->socket_.handshake("127.0.0.1:" + std::to_string(chromium.port()), chromium.browser_path(), ec);
  if (ec) return fail(ErrorCode::io, "DevTools WebSocket handshake: " + ec.message());
  return client;
}

Expected<void> CdpClient::write(const std::string& text, Clock::time_point until) {
  bool done = false;
  boost::system::error_code error;
  socket_.text(true);
  socket_.async_write(asio::buffer(text), [&](boost::system::error_code e, std::size_t) {
    error = e;
    done = true;
  });
  while (!done && Clock::now() < until) {
    if (io_.stopped()) io_.restart();
    io_.run_one_for(until - Clock::now());
  }
  if (!done) {
    // A write left pending would outlive `text`: the connection is of no more use.
    boost::system::error_code ignored;
    socket_.next_layer().close(ignored);
    while (!done) {
      if (io_.stopped()) io_.restart();
      io_.run_one();
    }
    return fail(ErrorCode::timeout, "DevTools write timed out");
  }
  if (error) return fail(ErrorCode::io, "DevTools write: " + error.message());
  return {};
}

Expected<void> CdpClient::read_one(Clock::time_point until) {
  if (!reading_) {
    reading_ = true;
    read_done_ = false;
    socket_.async_read(buffer_, [this](boost::system::error_code e, std::size_t) {
      read_error_ = e;
      read_done_ = true;
      reading_ = false;
    });
  }
  while (!read_done_ && Clock::now() < until) {
    if (io_.stopped()) io_.restart();
    io_.run_one_for(until - Clock::now());
  }
  if (!read_done_) return fail(ErrorCode::timeout, "no DevTools message in time");  // the read stays pending
  read_done_ = false;
  if (read_error_) return fail(ErrorCode::io, "DevTools connection: " + read_error_.message());
  Json message = Json::parse(beast::buffers_to_string(buffer_.data()), nullptr, false);
  buffer_.consume(buffer_.size());
  if (message.is_discarded()) return fail(ErrorCode::malformed, "DevTools sent a frame that is not JSON");
  if (message.contains("id") && message["id"].is_number_integer()) {
    const int id = message["id"].get<int>();  // before the move: an assignment's right side goes first
    responses_[id] = std::move(message);
  } else
    events_.push_back(std::move(message));
  return {};
}

Expected<Json> CdpClient::call(const std::string& method, Json params, const std::string& session,
                               std::chrono::milliseconds deadline) {
  const auto until = Clock::now() + deadline;
  const int id = next_id_++;
  Json request{{"id", id}, {"method", method}, {"params", std::move(params)}};
  if (!session.empty()) request["sessionId"] = session;
  if (auto written = write(request.dump(), until); !written) return unexpected(written.error());
  while (true) {
    if (auto it = responses_.find(id); it != responses_.end()) {
      Json response = std::move(it->second);
      responses_.erase(it);
      if (response.contains("error"))
        return fail(ErrorCode::refused, method + ": " + response["error"].value("message", response.dump()));
      return response.value("result", Json::object());
    }
    if (auto read = read_one(until); !read) return fail(read.error().code, method + ": " + read.error().message());
  }
}

Expected<Json> CdpClient::wait_event(const std::string& method, const std::string& session,
                                     std::chrono::milliseconds deadline) {
  const auto until = Clock::now() + deadline;
  while (true) {
    for (auto it = events_.begin(); it != events_.end(); ++it)
      if (it->value("method", "") == method && it->value("sessionId", "") == session) {
        Json event = std::move(*it);
        events_.erase(it);
        return event.value("params", Json::object());
      }
    if (auto read = read_one(until); !read) return fail(read.error().code, method + ": " + read.error().message());
  }
}

void CdpClient::forget_events(const std::string& session) {
  std::erase_if(events_, [&](const Json& e) { return e.value("sessionId", "") == session; });
}

// ---------------------------------------------------------------------------- Tab

Expected<Tab> Tab::open(CdpClient& cdp, const std::string& url, std::chrono::milliseconds deadline) {
  auto created = cdp.call("Target.createTarget", {{"url", "about:blank"}});
  if (!created) return unexpected(created.error());
  const std::string target = (*created)["targetId"].get<std::string>();
  auto attached = cdp.call("Target.attachToTarget", {{"targetId", target}, {"flatten", true}});
  if (!attached) return unexpected(attached.error());
  Tab tab(cdp, target, (*attached)["sessionId"].get<std::string>());
  for (const char* domain : {"Page.enable", "Runtime.enable"})
    if (auto enabled = cdp.call(domain, Json::object(), tab.session_); !enabled) return unexpected(enabled.error());
  if (auto focused = cdp.call("Target.activateTarget", {{"targetId", target}}); !focused)
    return unexpected(focused.error());
  if (auto navigated = tab.navigate(url, deadline); !navigated) return unexpected(navigated.error());
  return tab;
}

Expected<void> Tab::navigate(const std::string& url, std::chrono::milliseconds deadline) {
  cdp_->forget_events(session_);
  auto navigated = cdp_->call("Page.navigate", {{"url", url}}, session_);
  if (!navigated) return unexpected(navigated.error());
  if (navigated->contains("errorText")) return fail(ErrorCode::io, url + ": " + (*navigated)["errorText"].dump());
  if (auto loaded = cdp_->wait_event("Page.loadEventFired", session_, deadline); !loaded)
    return unexpected(loaded.error());
  return {};
}

Expected<Json> Tab::evaluate(const std::string& expression) {
  auto result = cdp_->call("Runtime.evaluate",
                           {{"expression", expression}, {"returnByValue", true}, {"awaitPromise", true}}, session_);
  if (!result) return unexpected(result.error());
  if (result->contains("exceptionDetails"))
    return fail(ErrorCode::refused, "page threw: " + (*result)["exceptionDetails"].dump());
  return (*result)["result"].value("value", Json());
}

Expected<Json> Tab::wait_until(const std::string& expression, std::chrono::milliseconds deadline) {
  const auto until = Clock::now() + deadline;
  Expected<Json> last = Json();
  while (true) {
    last = evaluate(expression);
    if (last && last->is_boolean() && last->get<bool>()) return last;
    if (Clock::now() >= until) return last;
    std::this_thread::sleep_for(50ms);
  }
}

Expected<void> Tab::key(const std::string& type, const std::string& code) {
  const auto info = key_info(code);
  if (!info) return fail(ErrorCode::invalid_argument, "no such key in the test's keyboard: " + code);
  Json params{{"type", type},
              {"key", info->key},
              {"code", code},
              {"windowsVirtualKeyCode", info->virtual_code},
              {"nativeVirtualKeyCode", info->virtual_code}};
  if (type == "keyDown" && info->key.size() == 1) params["text"] = info->key;
  auto sent = cdp_->call("Input.dispatchKeyEvent", params, session_);
  if (!sent) return unexpected(sent.error());
  return {};
}
Expected<void> Tab::key_down(const std::string& code) {
  // Printable keys type their character (keyDown with text); the others are raw key downs.
  const auto info = key_info(code);
  return key(info && info->key.size() == 1 ? "keyDown" : "rawKeyDown", code);
}
Expected<void> Tab::key_up(const std::string& code) { return key("keyUp", code); }

Expected<Json> Tab::center_of(const std::string& selector) {
  const Json quoted = selector;
  auto box = evaluate("(() => { const e = document.querySelector(" + quoted.dump() +
                      "); if (!e) return null; e.scrollIntoView({block: 'center'});"
                      " const r = e.getBoundingClientRect(); return {x: r.x + r.width / 2, y: r.y + r.height / 2}; })()");
  if (!box) return box;
  if (box->is_null()) return fail(ErrorCode::invalid_argument, "no element matches " + selector);
  return box;
}

Expected<void> Tab::mouse(const std::string& type, double x, double y) {
  // A move carries no button down in this client (no drags with the button up are needed).
  Json params{{"type", type}, {"x", x}, {"y", y}, {"button", "left"}, {"buttons", 1}, {"clickCount", 1}};
  if (type == "mouseReleased") params["buttons"] = 0;
  auto sent = cdp_->call("Input.dispatchMouseEvent", params, session_);
  if (!sent) return unexpected(sent.error());
  return {};
}

Expected<void> Tab::click(const std::string& selector) {
  auto box = center_of(selector);
  if (!box) return unexpected(box.error());
  const double x = (*box)["x"].get<double>(), y = (*box)["y"].get<double>();
  Json moved{{"type", "mouseMoved"}, {"x", x}, {"y", y}, {"button", "none"}};
  if (auto sent = cdp_->call("Input.dispatchMouseEvent", moved, session_); !sent) return unexpected(sent.error());
  for (const char* type : {"mousePressed", "mouseReleased"})
    if (auto sent = mouse(type, x, y); !sent) return sent;
  return {};
}

Expected<void> Tab::screenshot(const std::filesystem::path& file) {
  auto shot = cdp_->call("Page.captureScreenshot", {{"format", "png"}}, session_, 30s);
  if (!shot) return unexpected(shot.error());
  const std::string encoded = (*shot)["data"].get<std::string>();
  std::string png(beast::detail::base64::decoded_size(encoded.size()), '\0');
  png.resize(beast::detail::base64::decode(png.data(), encoded.data(), encoded.size()).first);
  std::error_code ec;
  std::filesystem::create_directories(file.parent_path(), ec);
  std::ofstream out(file, std::ios::binary);
  out << png;
  if (!out) return fail(ErrorCode::io, "cannot write " + file.string());
  return {};
}

Expected<void> Tab::close(std::chrono::milliseconds deadline) {
  auto closed = cdp_->call("Target.closeTarget", {{"targetId", target_}});
  if (!closed) return unexpected(closed.error());
  // Closing is asynchronous: the tab is gone once the browser no longer lists it.
  const auto until = Clock::now() + deadline;
  while (true) {
    auto targets = cdp_->call("Target.getTargets");
    if (!targets) return unexpected(targets.error());
    bool listed = false;
    for (const auto& target : (*targets)["targetInfos"]) listed = listed || target.value("targetId", "") == target_;
    if (!listed) return {};
    if (Clock::now() >= until) return fail(ErrorCode::timeout, "the tab did not close");
    std::this_thread::sleep_for(20ms);
  }
}

}  // namespace jaus::test::browser
