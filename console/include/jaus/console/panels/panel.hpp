// One feature of jaus-console (docs/console.md, "The page"): a panel has one
// job (the tree, control, the drive, the emergency stop, the pose, ...), the
// page frames of that job and the reports it needs. OperatorConsole owns the
// session and routes page frames and what the network says to its panels;
// a panel that shows reports names the operator views it serves
// (rt::operator_view) and is told of each component whose kind lists one.
#pragma once

#include <chrono>
#include <cstdint>
#include <algorithm>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "jaus/console/console_options.hpp"
#include "jaus/console/console_protocol.hpp"
#include "jaus/ocu/session.hpp"
#include "jaus/runtime/component_kind.hpp"
#include "jaus/wire/message.hpp"

namespace jaus::console {

// Sent to every page (a frame's `to`) rather than to one.
inline constexpr PageId kEveryPage = 0;

// The way to the pages: frames to one page or to all, refusals, the event log.
class Pages {
 public:
  // Where frames go: to one page, or kEveryPage.
  using Output = std::function<void(PageId to, const std::string& frame)>;

  Pages(Output output, jaus::rt::Clock& clock, jaus::rt::LogFn log)
      : output_(std::move(output)), clock_(clock), log_(std::move(log)) {}

  void to_page(PageId page, const ServerFrame& frame) { output_(page, format_frame(frame)); }
  void to_all(const ServerFrame& frame) { output_(kEveryPage, format_frame(frame)); }
  // A frame already formatted (one image to every watcher, an unchanged tree not sent again).
  void send(PageId to, const std::string& text) { output_(to, text); }
  // An `error` to the page that sent a frame it may not act on, counted.
  void refuse(PageId page, const std::string& why);
  // An `event` to every page, and the log.
  void event(EventLevel level, const std::string& text);
  std::uint64_t frames_refused() const { return frames_refused_; }

 private:
  Output output_;
  jaus::rt::Clock& clock_;
  jaus::rt::LogFn log_;
  std::uint64_t frames_refused_ = 0;
};

// What every panel shares.
struct PanelContext {
  jaus::ocu::OcuSession& session;
  jaus::rt::Clock& clock;
  jaus::rt::Scheduler& scheduler;
  const ConsoleOptions& options;
  Pages& pages;
};

// A task every `period` until stopped or destroyed.
class Periodic {
 public:
  Periodic(jaus::rt::Clock& clock, jaus::rt::Scheduler& scheduler) : clock_(clock), scheduler_(scheduler) {}
  ~Periodic() { stop(); }
  Periodic(const Periodic&) = delete;
  Periodic& operator=(const Periodic&) = delete;

  void start(std::chrono::milliseconds period, std::function<void()> task);
  void stop();

 private:
  void arm();

  jaus::rt::Clock& clock_;
  jaus::rt::Scheduler& scheduler_;
  std::chrono::milliseconds period_{};
  std::function<void()> task_;
  bool running_ = false;
  jaus::rt::TimerId timer_ = jaus::rt::kNoTimer;
};

class Panel {
 public:
  explicit Panel(PanelContext& context) : context_(context) {}
  virtual ~Panel() = default;
  Panel(const Panel&) = delete;
  Panel& operator=(const Panel&) = delete;

  // The operator views (rt::operator_view) this panel serves.
  virtual std::vector<std::string_view> views() const { return {}; }
  // A component found whose kind lists `view`, one of views(): follow its reports.
  virtual void follow(const jaus::Address& /*component*/, std::string_view /*view*/) {}
  // What a page that opens must see of this panel.
  virtual void page_opened(PageId /*page*/) {}
  // A page gone lets go of what it held here.
  virtual void page_closed(PageId /*page*/) {}
  // Every message to the console's component, and every header it hears.
  virtual void received(const jaus::ocu::Received& /*message*/) {}
  virtual void heard(const jaus::Header& /*header*/) {}
  // Before the program ends: what it drives stopped, what it holds let go.
  // A panel that overrides it calls Panel::shutdown() too.
  virtual void shutdown() { unsubscribe_all(); }

 protected:
  jaus::ocu::OcuSession& session() { return context_.session; }
  const ConsoleOptions& options() const { return context_.options; }
  Pages& pages() { return context_.pages; }
  // Report `R` from `source` by service connection at the console's report
  // rate, ended at shutdown.
  template <class R, class Handler>
  void subscribe(const jaus::Address& source, std::uint32_t presence_vector, Handler handler) {
    subscriptions_.push_back(context_.session.component().subscribe<R>(source, context_.options.report_rate_hz,
                                                                        presence_vector, std::move(handler)));
  }

  PanelContext& context_;

 private:
  void unsubscribe_all();

  std::vector<jaus::rt::SubscriptionId> subscriptions_;
};

// A message's body, read in the RA dialect; nothing when it is malformed.
template <class M>
std::optional<M> decode_report(std::span<const std::uint8_t> payload) {
  M message{};
  if (!jaus::wire::decode_payload_into(payload, message, jaus::wire::Dialect::ra, jaus::kHeaderSize))
    return std::nullopt;
  return message;
}

// v within [a, b], a range given either way round (std::clamp needs a <= b).
inline double within(double v, double a, double b) { return std::max(std::min(a, b), std::min(std::max(a, b), v)); }

// The node a component is on (component 0), to key what is per node.
inline jaus::Address node_of(const jaus::Address& a) { return jaus::Address{a.subsystem, a.node, 0, 0}; }

}  // namespace jaus::console
