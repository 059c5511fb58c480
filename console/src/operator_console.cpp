#include "jaus/console/operator_console.hpp"

#include <algorithm>
#include <type_traits>
#include <utility>
#include <variant>

#include "jaus/console/kind_views.hpp"

namespace jaus::console {

OperatorConsole::OperatorConsole(jaus::ocu::OcuSession& session, jaus::rt::Clock& clock,
                                 jaus::rt::Scheduler& scheduler, ConsoleOptions options, Output output)
    : session_(session),
      options_(std::move(options)),
      pages_(std::move(output), clock, options_.log),
      context_{session, clock, scheduler, options_, pages_},
      tree_(context_, [this] { follow_new_components(); }),
      drive_(context_, control_),
      control_(context_, [this](const jaus::Address& target, const std::string& why) { drive_.stop(target, why); }),
      emergency_(context_, drive_),
      pose_(context_),
      velocity_(context_),
      camera_(context_, control_),
      arm_(context_, control_),
      waypoints_(context_),
      link_(context_),
      panels_{&tree_, &drive_, &control_, &emergency_, &pose_, &velocity_, &camera_, &arm_, &waypoints_, &link_} {}

OperatorConsole::~OperatorConsole() {
  shutdown();
  if (listener_) session_.unlisten(listener_);
  if (watcher_) session_.unlisten(watcher_);
}

void OperatorConsole::start() {
  if (started_) return;
  started_ = true;
  listener_ = session_.listen([this](const jaus::ocu::Received& r) { on_received(r); });
  watcher_ = session_.watch([this](const jaus::Header& h) { on_heard(h); });
  tree_.start();
  link_.start();
}

void OperatorConsole::shutdown() {
  if (shut_down_) return;
  shut_down_ = true;
  for (auto* panel : panels_) panel->shutdown();
}

OperatorConsole::Counters OperatorConsole::counters() const {
  return Counters{pages_.frames_refused(), drive_.counters().efforts_sent, drive_.counters().zero_efforts_sent};
}

// ---- pages

void OperatorConsole::page_opened(PageId page) {
  pages_open_.insert(page);
  pages_.to_page(page, WelcomeFrame{session_.self(), page, options_.version,
                                    static_cast<int>(options_.deadman.count()), views_by_id()});
  for (auto* panel : panels_) panel->page_opened(page);
}

void OperatorConsole::page_closed(PageId page) {
  if (!pages_open_.erase(page)) return;
  for (auto* panel : panels_) panel->page_closed(page);
}

void OperatorConsole::page_frame(PageId page, std::string_view text) {
  if (shut_down_) return;
  auto frame = parse_page_frame(text);
  if (!frame) {
    pages_.refuse(page, frame.error().message());
    return;
  }
  std::visit(
      [&](const auto& f) {
        using F = std::decay_t<decltype(f)>;
        if constexpr (std::is_same_v<F, ControlFrame> || std::is_same_v<F, StateFrame>) control_.on_frame(page, f);
        else if constexpr (std::is_same_v<F, DriveFrame>) drive_.on_frame(page, f);
        else if constexpr (std::is_same_v<F, EmergencyFrame>) emergency_.on_frame(page, f);
        else if constexpr (std::is_same_v<F, CameraFrame>) camera_.on_frame(page, f);
        else if constexpr (std::is_same_v<F, ArmFrame>) arm_.on_frame(page, f);
        else waypoints_.on_frame(page, f);
      },
      *frame);
}

// ---- the network

void OperatorConsole::on_heard(const jaus::Header& header) {
  if (header.source.subsystem == session_.self().subsystem && header.source.node == session_.self().node) return;
  for (auto* panel : panels_) panel->heard(header);
}

void OperatorConsole::on_received(const jaus::ocu::Received& message) {
  // Control first: a hold is decided before anything acts on the message.
  control_.received(message);
  for (auto* panel : panels_)
    if (panel != &control_) panel->received(message);
}

void OperatorConsole::follow_new_components() {
  if (shut_down_) return;
  for (const auto& [sid, subsystem] : tree_.discovery().subsystems())
    for (const auto& [nid, node] : subsystem.nodes)
      for (const auto& [key, c] : node.components) {
        const auto a = c.address;
        if (followed_.count(a)) continue;
        const auto views = views_of(a.component);
        if (views.empty()) continue;  // a kind nobody here knows: in the tree, nothing followed
        for (auto* panel : panels_)
          for (const auto view : panel->views())
            if (std::find(views.begin(), views.end(), view) != views.end()) panel->follow(a, view);
        followed_.insert(a);
      }
}

}  // namespace jaus::console
