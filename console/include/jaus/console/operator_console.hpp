// jaus-console's core, sans I/O: what the pages ask (parsed frames, pages
// opened and closed) turned into JAUS on an ocu::OcuSession, and what the
// network says turned into frames for the pages. The web server (or a test)
// hands frames in and carries frames out; time and timers are injected (the
// session's clock and scheduler: AsioRuntime in the program, VirtualTime in
// tests). Single-threaded, like the session.
//
// The console is the front of its panels (jaus/console/panels/), one per
// feature: it owns the session, routes each page frame to the panel of its
// type and every message to every panel, and tells a panel of each
// component found whose kind lists a view the panel serves (kind_views.hpp):
// what is followed is decided by the kinds, never by IDs here.
//
// Safety (docs/console.md, "The deadman"; docs/safety.md): the deadman is
// DrivePanel's, the emergency stop EmergencyPanel's; control is
// ControlPanel's, and whatever ends a hold ends the drive first.
#pragma once

#include <cstdint>
#include <set>
#include <string_view>
#include <vector>

#include "jaus/console/console_options.hpp"
#include "jaus/console/console_protocol.hpp"
#include "jaus/console/panels/arm_panel.hpp"
#include "jaus/console/panels/camera_panel.hpp"
#include "jaus/console/panels/control_panel.hpp"
#include "jaus/console/panels/drive_panel.hpp"
#include "jaus/console/panels/emergency_panel.hpp"
#include "jaus/console/panels/link_panel.hpp"
#include "jaus/console/panels/panel.hpp"
#include "jaus/console/panels/pose_panel.hpp"
#include "jaus/console/panels/tree_panel.hpp"
#include "jaus/console/panels/velocity_panel.hpp"
#include "jaus/console/panels/waypoints_panel.hpp"
#include "jaus/ocu/discovery.hpp"
#include "jaus/ocu/session.hpp"

namespace jaus::console {

class OperatorConsole {
 public:
  using Output = Pages::Output;

  struct Counters {
    std::uint64_t frames_refused = 0;  // malformed or not allowed: answered with `error`
    std::uint64_t efforts_sent = 0;    // Set Wrench Effort while driving
    std::uint64_t zero_efforts_sent = 0;
  };

  OperatorConsole(jaus::ocu::OcuSession& session, jaus::rt::Clock& clock, jaus::rt::Scheduler& scheduler,
                  ConsoleOptions options, Output output);
  ~OperatorConsole();
  OperatorConsole(const OperatorConsole&) = delete;
  OperatorConsole& operator=(const OperatorConsole&) = delete;

  // Starts discovery and the periodic queries.
  void start();
  void page_opened(PageId page);
  // A page gone (closed tab, lost WebSocket) lets go of whatever it drove.
  void page_closed(PageId page);
  void page_frame(PageId page, std::string_view text);
  // Before the program ends: zero effort where driving, control released,
  // service connections terminated. The caller then lets the session run a
  // little (OcuSession::run_cleanup_until) so the releases are heard.
  void shutdown();

  Counters counters() const;
  std::size_t page_count() const { return pages_open_.size(); }
  const jaus::ocu::Discovery& discovery() const { return tree_.discovery(); }
  // Whether this console holds control of `target` (confirmed and Ready).
  bool holds_control(const jaus::Address& target) const { return control_.holds(target); }
  bool driving(const jaus::Address& target) const { return drive_.driving(target); }
  // The components followed for their views (pose, velocity, arm, ...).
  const std::set<jaus::Address>& followed() const { return followed_; }

 private:
  void on_received(const jaus::ocu::Received& message);
  void on_heard(const jaus::Header& header);
  // Tells each panel of the components found whose views it serves.
  void follow_new_components();

  jaus::ocu::OcuSession& session_;
  ConsoleOptions options_;
  Pages pages_;
  PanelContext context_;
  // In the order they hear of pages, messages and the shutdown: the drive
  // before control, so the zero goes while control is still held.
  TreePanel tree_;
  DrivePanel drive_;
  ControlPanel control_;
  EmergencyPanel emergency_;
  PosePanel pose_;
  VelocityPanel velocity_;
  CameraPanel camera_;
  ArmPanel arm_;
  WaypointsPanel waypoints_;
  LinkPanel link_;
  const std::vector<Panel*> panels_;

  jaus::ocu::OcuSession::ListenerId listener_ = 0;
  jaus::ocu::OcuSession::ListenerId watcher_ = 0;
  bool started_ = false;
  bool shut_down_ = false;
  std::set<PageId> pages_open_;
  std::set<jaus::Address> followed_;
};

}  // namespace jaus::console
