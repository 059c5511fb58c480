// jaus-console's core, sans I/O: what the pages ask (parsed frames, pages
// opened and closed) turned into JAUS on an ocu::OcuSession, and what the
// network says turned into frames for the pages. The web server (or a test)
// hands frames in and carries frames out; time and timers are injected (the
// session's clock and scheduler: AsioRuntime in the program, VirtualTime in
// tests). Single-threaded, like the session.
//
// Safety (docs/console.md, "The deadman"; docs/safety.md): Set Wrench Effort
// goes to a driver only while this console holds control of it and the
// driver is Ready (rt::ControlClient's "held"), and only while a page keeps
// the deadman fresh (a `drive` with held:true younger than `deadman`). The
// moment the page lets go (held:false), goes silent, closes, or the console
// shuts down, one zero effort is sent and then nothing. Control lost (taken
// over, the driver left Ready or fell silent) stops the drive at once; the
// driver already stopped itself on that path (Component::enforce_stop).
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "jaus/console/console_protocol.hpp"
#include "jaus/messages/manipulator_messages.hpp"
#include "jaus/ocu/discovery.hpp"
#include "jaus/ocu/session.hpp"
#include "jaus/ocu/wildcard_command.hpp"
#include "jaus/runtime/control_client.hpp"

namespace jaus::console {

// Sent to every page (a frame's `to`) rather than to one.
inline constexpr PageId kEveryPage = 0;

struct ConsoleOptions {
  std::chrono::milliseconds deadman{250};       // a drive older than this stops
  std::chrono::milliseconds drive_period{50};   // Set Wrench Effort at 20 Hz while held
  std::chrono::milliseconds poll_period{1000};  // Query Component Status/Control of every component
  std::chrono::milliseconds link_period{1000};  // the `link` frame
  double report_rate_hz = 5;                    // pose, velocity, joints, images by service connection
  std::uint8_t camera_id = 1;
  // Set Camera Pose carries percent of the mount's full scale (the larger of
  // |min| and |max|), which no report tells: these are the default jausd
  // camera's (config/jausd.yaml: pan +-170 deg, tilt -30..90 deg).
  double camera_pan_full_scale_deg = 170;
  double camera_tilt_full_scale_deg = 90;
  std::string version;
  jaus::rt::LogFn log;
};

class OperatorConsole {
 public:
  // Where frames go: to one page, or kEveryPage.
  using Output = std::function<void(PageId to, const std::string& frame)>;

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

  const Counters& counters() const { return counters_; }
  std::size_t page_count() const { return pages_.size(); }
  const jaus::ocu::Discovery& discovery() const { return discovery_; }
  // Whether this console holds control of `target` (confirmed and Ready).
  bool holds_control(const jaus::Address& target) const;
  bool driving(const jaus::Address& target) const { return drives_.count(target) != 0; }

 private:
  struct Drive {
    PageId by = 0;
    double linear = 0;
    double angular = 0;
    jaus::rt::TimePoint fresh_until{};
    jaus::rt::TimerId timer = jaus::rt::kNoTimer;
  };
  struct Control {
    std::unique_ptr<jaus::rt::ControlClient> client;
    ControlState state = ControlState::released;
    std::string why;
    std::optional<std::uint8_t> authority;  // of the last request a page made
    // A command that needs control (pan/tilt, joints), sent once control is held.
    std::function<void()> when_held;
  };
  struct ComponentLive {
    std::optional<std::uint8_t> status;
    std::optional<jaus::Address> controller;
    std::uint8_t authority = 0;
  };
  struct Camera {
    std::set<PageId> watchers;
    std::optional<jaus::rt::SubscriptionId> subscription;
    std::uint64_t frames = 0;
  };
  struct Arm {
    std::optional<jaus::msg::ManipulatorSpecificationsBody> specifications;
    std::vector<double> positions_rad_or_m;
  };
  // Forwards what the control clients send through the session.
  class SessionOutbox final : public jaus::rt::Outbox {
   public:
    explicit SessionOutbox(jaus::ocu::OcuSession& session) : session_(session) {}
    void send(const jaus::Header& header, std::span<const std::uint8_t> payload) override {
      session_.send_raw(header, payload);
    }

   private:
    jaus::ocu::OcuSession& session_;
  };

  // Frames out.
  void to_page(PageId page, const ServerFrame& frame) { output_(page, format_frame(frame)); }
  void to_all(const ServerFrame& frame) { output_(kEveryPage, format_frame(frame)); }
  void refuse(PageId page, const std::string& why);
  void event(EventLevel level, const std::string& text);

  // Page frames.
  void on_control(PageId page, const ControlFrame& frame);
  void on_drive(PageId page, const DriveFrame& frame);
  void on_emergency(PageId page, const EmergencyFrame& frame);
  void on_state(PageId page, const StateFrame& frame);
  void on_camera(PageId page, const CameraFrame& frame);
  void on_arm(PageId page, const ArmFrame& frame);
  void on_waypoints(PageId page, const WaypointsFrame& frame);

  // Control.
  Control& control_of(const jaus::Address& target);
  void request_control(PageId page, const jaus::Address& target, std::uint8_t authority);
  // Runs `command` now if control of `target` is held, else asks for it
  // (the page's last authority, or the OCU's own) and runs it once held.
  void as_controller(PageId page, const jaus::Address& target, std::function<void()> command);
  void set_control_state(const jaus::Address& target, ControlState state, const std::string& why);
  void release_control(const jaus::Address& target);

  // The deadman.
  void drive_tick(const jaus::Address& target);
  void stop_drive(const jaus::Address& target, const std::string& why);
  void send_effort(const jaus::Address& target, double linear, double angular);

  // Cameras.
  void unwatch(const jaus::Address& target, PageId page);

  // The network.
  void on_received(const jaus::ocu::Received& message);
  void on_heard(const jaus::Header& header);
  void send_discovery(const std::vector<jaus::ocu::DiscoveryQuery>& queries);
  void follow_new_components();
  void poll();
  void send_link();
  void publish_tree();
  TreeFrame tree() const;
  void publish_arm(const jaus::Address& source);
  void arm_timer(jaus::rt::TimerId& timer, std::chrono::milliseconds period, void (OperatorConsole::*what)());
  // A command that must arrive (Set/Clear Emergency): ACK-requested and
  // retransmitted by the node; to a wildcard (`all`), to every component it
  // names, each confirming it (send_to_every_member).
  template <class M>
  void send_must_arrive(const jaus::Address& to, const M& message, const std::string& what);
  void send_to_every_member(const jaus::Address& to, jaus::Header header, std::vector<std::uint8_t> payload,
                            const std::string& what);

  jaus::ocu::OcuSession& session_;
  jaus::rt::Clock& clock_;
  jaus::rt::Scheduler& scheduler_;
  ConsoleOptions options_;
  Output output_;
  SessionOutbox outbox_;
  jaus::rt::Environment environment_;
  jaus::ocu::Discovery discovery_;
  jaus::ocu::OcuSession::ListenerId listener_ = 0;
  jaus::ocu::OcuSession::ListenerId watcher_ = 0;
  bool started_ = false;
  bool shut_down_ = false;
  // Callbacks the node may call after this console is gone check this first.
  std::shared_ptr<int> alive_ = std::make_shared<int>(0);
  std::vector<std::unique_ptr<jaus::ocu::WildcardCommand>> wildcards_;

  std::set<PageId> pages_;
  std::map<jaus::Address, Control> controls_;
  std::map<jaus::Address, Drive> drives_;
  std::map<jaus::Address, ComponentLive> live_;
  std::map<jaus::Address, bool> emergencies_;  // set by this console: active
  std::map<jaus::Address, Camera> cameras_;
  std::map<jaus::Address, Arm> arms_;
  std::set<jaus::Address> followed_;  // pose, velocity and arm sources subscribed to
  std::vector<jaus::rt::SubscriptionId> report_subscriptions_;
  std::map<jaus::Address, std::pair<double, double>> latitude_longitude_;  // by node (component 0)
  std::map<jaus::Address, jaus::rt::TimePoint> heard_;                     // by node (component 0)
  std::string last_tree_;
  jaus::rt::TimerId poll_timer_ = jaus::rt::kNoTimer;
  jaus::rt::TimerId link_timer_ = jaus::rt::kNoTimer;
  Counters counters_;
};

}  // namespace jaus::console
