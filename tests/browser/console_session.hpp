// What the browser test and the latency benchmark share: a default jausd,
// jaus-console on it, headless Chromium with the console's page open, and the
// page's own readings (the tree, control) through window.jausConsole.
#pragma once

#include <chrono>
#include <filesystem>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "cdp_client.hpp"
#include "default_jausd.hpp"

namespace jaus::test::browser {

// A page reading, or `fallback` when the page could not be read.
inline Json value_of(const Expected<Json>& reading, Json fallback) { return reading ? *reading : std::move(fallback); }

// The first JSON line of a finished jausctl's output, or nothing.
inline std::optional<Json> json_line_of(ChildProcess& child) {
  if (child.wait(std::chrono::seconds(20)) != 0) return std::nullopt;
  std::istringstream lines(child.output());
  for (std::string line; std::getline(lines, line);)
    if (!line.empty() && line.front() == '{') {
      Json parsed = Json::parse(line, nullptr, false);
      if (!parsed.is_discarded()) return parsed;
    }
  return std::nullopt;
}

// jaus-console as the operator starts it: JAUS on `jaus_bind`, the page on `http_listen`, the node at `to`.
inline std::unique_ptr<ChildProcess> start_console(const DefaultJausd& jausd, const std::string& to,
                                                   const std::string& jaus_bind, const std::string& http_listen) {
  return std::make_unique<ChildProcess>(
      std::vector<std::string>{JAUS_CONSOLE_PATH, "--to", to, "--bind", jaus_bind, "--listen", http_listen, "-v"},
      (jausd.dir() / "jaus-console.log").string());
}

// Opens the console's page in a new tab, retrying while the console is not listening yet.
inline Expected<Tab> open_console_page(CdpClient& cdp, const std::string& url, std::chrono::milliseconds deadline) {
  auto tab = Tab::open(cdp, "about:blank");
  if (!tab) return tab;
  const auto until = Clock::now() + deadline;
  while (true) {
    auto loaded = tab->navigate(url);
    if (loaded) {
      auto connected = tab->wait_until("document.getElementById('link-status').classList.contains('ok')",
                                       std::chrono::duration_cast<std::chrono::milliseconds>(until - Clock::now()));
      if (connected && connected->is_boolean() && connected->get<bool>()) return tab;
    }
    if (Clock::now() >= until)
      return unexpected(make_error(ErrorCode::timeout, "the console's page did not connect: " +
                                                           (loaded ? std::string("no WebSocket") : loaded.error().message())));
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
  }
}

// JavaScript: true once the page's tree lists `address`.
inline std::string tree_lists(const std::string& address) {
  return "document.querySelector('#tree [data-address=\"" + address + "\"]') !== null";
}
// JavaScript: true once this console holds control of `address` (the tree's controller is the console's ID).
inline std::string console_controls(const std::string& address) {
  return "(() => { const s = window.jausConsole.state; const c = s.components.get('" + address +
         "'); return !!c && c.controller === s.self; })()";
}
// JavaScript: the tree's state of `address` ("Ready", ...), or null.
inline std::string component_state(const std::string& address) {
  return "(() => { const c = window.jausConsole.state.components.get('" + address + "'); return c ? c.state : null; })()";
}

}  // namespace jaus::test::browser
