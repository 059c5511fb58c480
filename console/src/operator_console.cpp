#include "jaus/console/operator_console.hpp"

#include <algorithm>
#include <cmath>
#include <ctime>
#include <numbers>
#include <utility>

#include "jaus/core/component_ids.hpp"
#include "jaus/messages/all.hpp"
#include "jaus/wire/message.hpp"

namespace jaus::console {

namespace {

using namespace std::chrono_literals;

// Presence vectors: x, y, yaw (bits 0, 1, 6) and latitude, longitude (0, 1).
constexpr std::uint32_t kLocalPoseFields = 0x43;
constexpr std::uint32_t kVelocityFields = 0x43;
constexpr std::uint32_t kGlobalPoseFields = 0x03;

constexpr jaus::node::AckPolicy kMustArrive{50ms, 10};

jaus::Address node_key(const jaus::Address& a) { return jaus::Address{a.subsystem, a.node, 0, 0}; }

template <class M>
std::optional<M> decode(std::span<const std::uint8_t> payload) {
  M message{};
  if (!jaus::wire::decode_payload_into(payload, message, jaus::wire::Dialect::ra, jaus::kHeaderSize))
    return std::nullopt;
  return message;
}

std::string iso_time(jaus::rt::UtcTime time) {
  const auto since = time.time_since_epoch();
  const auto seconds = std::chrono::duration_cast<std::chrono::seconds>(since);
  const auto millis = std::chrono::duration_cast<std::chrono::milliseconds>(since - seconds).count();
  const std::time_t t = seconds.count();
  std::tm tm{};
  gmtime_r(&t, &tm);
  char text[40];
  const auto n = std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%S", &tm);
  char out[64];
  std::snprintf(out, sizeof out, "%.*s.%03dZ", static_cast<int>(n), text, static_cast<int>(millis));
  return out;
}

std::string state_name(std::optional<std::uint8_t> status) {
  if (!status) return "unknown";
  for (const auto& s : jaus::msg::kComponentStates)
    if (s.value == *status) return std::string(s.name);
  return "unknown";
}

std::string image_format_name(std::uint8_t code) {
  for (const auto& f : jaus::msg::kImageFormats)
    if (f.value == code) return std::string(f.name);
  return "format " + std::to_string(code);
}

struct JointLimit {
  bool revolute = true;
  double min = 0, max = 0;  // rad or m
};

// Part 3 carries revolute angles as 0 .. 2 pi: back into (-pi, pi], with
// the 0.001 rad of the wire's rounding allowed above pi.
double signed_angle(double rad) {
  constexpr double kTwoPi = 2 * std::numbers::pi;
  return rad > std::numbers::pi + 0.002 ? rad - kTwoPi : rad;
}

JointLimit joint_limit(std::uint8_t type, double min, double max) {
  if (type == static_cast<std::uint8_t>(jaus::msg::JointType::prismatic)) return {false, min, max};
  JointLimit limit{true, signed_angle(min), signed_angle(max)};
  // -pi and pi are one angle on the wire: a minimum that came back as +pi.
  if (limit.min >= limit.max) limit.min -= 2 * std::numbers::pi;
  return limit;
}

// Joints 1 .. n-1 with their links, then the last joint (Part 3's order).
std::vector<JointLimit> joint_limits(const jaus::msg::ManipulatorSpecificationsBody& s) {
  std::vector<JointLimit> limits;
  for (const auto& j : s.joints) limits.push_back(joint_limit(j.type, j.min_rad_or_m, j.max_rad_or_m));
  limits.push_back(joint_limit(s.last_joint_type, s.last_joint_min_rad_or_m, s.last_joint_max_rad_or_m));
  return limits;
}

double degrees(double rad) { return rad * 180.0 / std::numbers::pi; }
double radians(double deg) { return deg * std::numbers::pi / 180.0; }

// A range given the wrong way round still clamps (std::clamp would not).
double within(double v, double a, double b) { return std::max(std::min(a, b), std::min(std::max(a, b), v)); }

bool is_tree_report(std::uint16_t code) {
  return code == jaus::msg::ReportComponentStatus::code || code == jaus::msg::ReportComponentControl::code ||
         code == jaus::msg::ReportIdentification::code || code == jaus::msg::ReportConfiguration::code ||
         code == jaus::msg::ReportServices::code || code == jaus::msg::ReportSubsystemList::code;
}

}  // namespace

OperatorConsole::OperatorConsole(jaus::ocu::OcuSession& session, jaus::rt::Clock& clock,
                                 jaus::rt::Scheduler& scheduler, ConsoleOptions options, Output output)
    : session_(session),
      clock_(clock),
      scheduler_(scheduler),
      options_(std::move(options)),
      output_(std::move(output)),
      outbox_(session),
      environment_{clock, scheduler, outbox_, options_.log ? options_.log : jaus::rt::silent_log()},
      discovery_(session.self()) {}

OperatorConsole::~OperatorConsole() {
  shutdown();
  wildcards_.clear();  // their timers and listeners go with them
  scheduler_.cancel(poll_timer_);
  scheduler_.cancel(link_timer_);
  if (listener_) session_.unlisten(listener_);
  if (watcher_) session_.unlisten(watcher_);
}

void OperatorConsole::start() {
  if (started_) return;
  started_ = true;
  listener_ = session_.listen([this](const jaus::ocu::Received& r) { on_received(r); });
  watcher_ = session_.watch([this](const jaus::Header& h) { on_heard(h); });
  send_discovery(discovery_.start());
  arm_timer(poll_timer_, options_.poll_period, &OperatorConsole::poll);
  arm_timer(link_timer_, options_.link_period, &OperatorConsole::send_link);
}

void OperatorConsole::arm_timer(jaus::rt::TimerId& timer, std::chrono::milliseconds period,
                                void (OperatorConsole::*what)()) {
  timer = scheduler_.call_at(clock_.now() + period, [this, &timer, period, what] {
    timer = jaus::rt::kNoTimer;
    (this->*what)();
    if (!shut_down_) arm_timer(timer, period, what);
  });
}

// ---- pages

void OperatorConsole::page_opened(PageId page) {
  pages_.insert(page);
  to_page(page, WelcomeFrame{session_.self(), page, options_.version, static_cast<int>(options_.deadman.count())});
  to_page(page, tree());
  for (const auto& [target, control] : controls_)
    if (control.state != ControlState::released) to_page(page, ControlStateFrame{target, control.state, control.why});
  for (const auto& [target, active] : emergencies_)
    if (active) to_page(page, EmergencyStateFrame{target, true, {session_.self()}});
  for (const auto& [target, drive] : drives_) to_page(page, DrivingFrame{target, true, drive.by});
  std::optional<std::int64_t> last;
  for (const auto& [node, when] : heard_) {
    const auto ms = std::chrono::duration_cast<std::chrono::milliseconds>(clock_.now() - when).count();
    last = last ? std::min(*last, static_cast<std::int64_t>(ms)) : static_cast<std::int64_t>(ms);
  }
  to_page(page, LinkFrame{heard_.size(), last});
}

void OperatorConsole::page_closed(PageId page) {
  if (!pages_.erase(page)) return;
  std::vector<jaus::Address> driven;
  for (const auto& [target, drive] : drives_)
    if (drive.by == page) driven.push_back(target);
  for (const auto& target : driven) stop_drive(target, "page " + std::to_string(page) + " closed");
  std::vector<jaus::Address> watched;
  for (const auto& [target, camera] : cameras_)
    if (camera.watchers.count(page)) watched.push_back(target);
  for (const auto& target : watched) unwatch(target, page);
}

void OperatorConsole::page_frame(PageId page, std::string_view text) {
  if (shut_down_) return;
  auto frame = parse_page_frame(text);
  if (!frame) {
    refuse(page, frame.error().message());
    return;
  }
  std::visit(
      [&](const auto& f) {
        using F = std::decay_t<decltype(f)>;
        if constexpr (std::is_same_v<F, ControlFrame>) on_control(page, f);
        else if constexpr (std::is_same_v<F, DriveFrame>) on_drive(page, f);
        else if constexpr (std::is_same_v<F, EmergencyFrame>) on_emergency(page, f);
        else if constexpr (std::is_same_v<F, StateFrame>) on_state(page, f);
        else if constexpr (std::is_same_v<F, CameraFrame>) on_camera(page, f);
        else if constexpr (std::is_same_v<F, ArmFrame>) on_arm(page, f);
        else on_waypoints(page, f);
      },
      *frame);
}

void OperatorConsole::refuse(PageId page, const std::string& why) {
  ++counters_.frames_refused;
  to_page(page, ErrorFrame{why});
}

void OperatorConsole::event(EventLevel level, const std::string& text) {
  if (options_.log)
    options_.log(level == EventLevel::info ? jaus::rt::LogLevel::info
                 : level == EventLevel::warn ? jaus::rt::LogLevel::warn
                                             : jaus::rt::LogLevel::error,
                 text);
  to_all(EventFrame{iso_time(clock_.utc_now()), level, text});
}

void OperatorConsole::shutdown() {
  if (shut_down_) return;
  shut_down_ = true;
  std::vector<jaus::Address> driven;
  for (const auto& [target, drive] : drives_) driven.push_back(target);
  for (const auto& target : driven) stop_drive(target, "the console is shutting down");
  for (auto& [target, control] : controls_)
    if (control.client && control.client->state() != jaus::rt::ControlClient::State::released) {
      control.client->release();
      control.state = ControlState::released;
      to_all(ControlStateFrame{target, ControlState::released, "the console is shutting down"});
    }
  for (auto& [target, camera] : cameras_)
    if (camera.subscription) session_.component().unsubscribe(*camera.subscription);
  cameras_.clear();
  for (auto id : report_subscriptions_) session_.component().unsubscribe(id);
  report_subscriptions_.clear();
}

// ---- control

OperatorConsole::Control& OperatorConsole::control_of(const jaus::Address& target) {
  auto& control = controls_[target];
  if (!control.client) {
    jaus::rt::ControlClient::Io io{
        [this](const jaus::Address& to, const jaus::msg::RequestComponentControl& m) { session_.send(to, m); },
        [this](const jaus::Address& to, const jaus::msg::ReleaseComponentControl& m) { session_.send(to, m); },
        [this](const jaus::Address& to, const jaus::msg::QueryComponentStatus& m) { session_.send(to, m); }};
    control.client = std::make_unique<jaus::rt::ControlClient>(environment_, jaus::rt::ControlClient::Options{}, io);
  }
  return control;
}

bool OperatorConsole::holds_control(const jaus::Address& target) const {
  const auto it = controls_.find(target);
  return it != controls_.end() && it->second.client && it->second.client->held();
}

void OperatorConsole::set_control_state(const jaus::Address& target, ControlState state, const std::string& why) {
  auto& control = controls_[target];
  control.state = state;
  control.why = why;
  to_all(ControlStateFrame{target, state, why});
}

void OperatorConsole::on_control(PageId page, const ControlFrame& frame) {
  const auto& target = frame.target;
  if (target.is_broadcast()) {
    refuse(page, "control: the target must be one component, not a broadcast address");
    return;
  }
  if (!frame.request) {
    release_control(target);
    set_control_state(target, ControlState::released, "released by page " + std::to_string(page));
    event(EventLevel::info, "control of " + target.to_string() + " released (page " + std::to_string(page) + ")");
    return;
  }
  request_control(page, target, frame.authority);
}

void OperatorConsole::request_control(PageId page, const jaus::Address& target, std::uint8_t authority) {
  auto& control = control_of(target);
  if (control.client->state() != jaus::rt::ControlClient::State::released) return;  // already asked or held
  control.authority = authority;
  set_control_state(target, ControlState::requesting, "");
  event(EventLevel::info, "requesting control of " + target.to_string() + " with authority " +
                              std::to_string(authority) + " (page " + std::to_string(page) + ")");
  control.client->acquire(
      target, authority,
      [this, target] {
        set_control_state(target, ControlState::held, "");
        event(EventLevel::info, "control of " + target.to_string() + " held");
        if (auto pending = std::exchange(controls_[target].when_held, nullptr)) pending();
      },
      [this, target](const std::string& why) {
        const bool was_held = controls_[target].state == ControlState::held;
        set_control_state(target, was_held ? ControlState::lost : ControlState::refused, why);
        stop_drive(target, "control " + std::string(was_held ? "lost" : "refused") + ": " + why);
        event(was_held ? EventLevel::warn : EventLevel::info,
              "control of " + target.to_string() + (was_held ? " lost: " : " refused: ") + why);
      });
}

void OperatorConsole::as_controller(PageId page, const jaus::Address& target, std::function<void()> command) {
  if (holds_control(target)) {
    command();
    return;
  }
  auto& control = control_of(target);
  control.when_held = std::move(command);  // the latest command wins
  request_control(page, target, control.authority.value_or(session_.options().authority));
}

void OperatorConsole::release_control(const jaus::Address& target) {
  stop_drive(target, "control released");  // the zero goes while control is still ours
  const auto it = controls_.find(target);
  if (it != controls_.end() && it->second.client) it->second.client->release();
}

// ---- the deadman

void OperatorConsole::send_effort(const jaus::Address& target, double linear, double angular) {
  jaus::msg::SetWrenchEffort effort{};
  effort.propulsive_linear_effort_x_percent = linear;
  effort.propulsive_rotational_effort_z_percent = angular;
  session_.send(target, effort);
}

void OperatorConsole::on_drive(PageId page, const DriveFrame& frame) {
  const auto& target = frame.target;
  auto it = drives_.find(target);
  if (!frame.held) {
    if (it != drives_.end() && it->second.by == page)
      stop_drive(target, "released by page " + std::to_string(page));
    return;
  }
  if (it != drives_.end() && it->second.by != page) {
    refuse(page, "drive: " + target.to_string() + " is driven by page " + std::to_string(it->second.by));
    return;
  }
  if (!holds_control(target)) {
    refuse(page, "drive: this console does not hold control of " + target.to_string() +
                     " (request control first; it must be Ready)");
    return;
  }
  const auto now = clock_.now();
  const bool starting = it == drives_.end();
  auto& drive = drives_[target];
  const bool changed = starting || drive.linear != frame.linear_percent || drive.angular != frame.angular_percent;
  drive.by = page;
  drive.linear = frame.linear_percent;
  drive.angular = frame.angular_percent;
  drive.fresh_until = now + options_.deadman;
  if (!changed) return;  // the timer sends it on at 20 Hz
  // A change goes at once (a key pressed is on the wire within the handler),
  // and the period starts again from it.
  send_effort(target, drive.linear, drive.angular);
  ++counters_.efforts_sent;
  scheduler_.cancel(drive.timer);
  drive.timer = scheduler_.call_at(now + options_.drive_period, [this, target] { drive_tick(target); });
  if (starting) {
    to_all(DrivingFrame{target, true, page});
    event(EventLevel::info, "page " + std::to_string(page) + " drives " + target.to_string());
  }
}

void OperatorConsole::drive_tick(const jaus::Address& target) {
  auto it = drives_.find(target);
  if (it == drives_.end()) return;
  auto& drive = it->second;
  drive.timer = jaus::rt::kNoTimer;
  const auto now = clock_.now();
  if (!holds_control(target)) {
    stop_drive(target, "control of it is not held");
    return;
  }
  if (now > drive.fresh_until) {
    stop_drive(target, "deadman: no drive frame for " + std::to_string(options_.deadman.count()) + " ms");
    return;
  }
  send_effort(target, drive.linear, drive.angular);
  ++counters_.efforts_sent;
  drive.timer = scheduler_.call_at(now + options_.drive_period, [this, target] { drive_tick(target); });
}

void OperatorConsole::stop_drive(const jaus::Address& target, const std::string& why) {
  auto it = drives_.find(target);
  if (it == drives_.end()) return;
  scheduler_.cancel(it->second.timer);
  drives_.erase(it);
  // Zero only to a driver we still command: one that left Ready or changed
  // controller stopped itself (docs/safety.md), and refuses commands.
  if (holds_control(target)) {
    send_effort(target, 0, 0);
    ++counters_.zero_efforts_sent;
  }
  to_all(DrivingFrame{target, false, std::nullopt});
  event(EventLevel::info, "stopped driving " + target.to_string() + ": " + why);
}

// ---- emergency, state

void OperatorConsole::send_to_every_member(const jaus::Address& to, jaus::Header header,
                                           std::vector<std::uint8_t> payload, const std::string& what) {
  // Finished ones go first (never from their own callback).
  std::erase_if(wildcards_, [](const auto& w) { return w->finished(); });
  // Every component `to` names, found or not yet (a stop is broadcast too,
  // until they all confirm): ocu/wildcard_command.hpp (issue 49).
  std::weak_ptr<int> alive = alive_;
  auto& command = *wildcards_.emplace_back(std::make_unique<jaus::ocu::WildcardCommand>(
      session_, to, header, std::move(payload), jaus::ocu::WildcardPolicy{},
      [this, alive, what](const jaus::ocu::WildcardResult& result) {
        if (alive.expired()) return;
        const auto confirmed = result.confirmed();
        const auto unconfirmed = result.unconfirmed();
        std::string text = what + ": confirmed by " + std::to_string(confirmed.size()) + " component(s)";
        for (std::size_t i = 0; i < confirmed.size(); ++i) text += (i ? ", " : " (") + confirmed[i].to_string();
        if (!confirmed.empty()) text += ")";
        if (!unconfirmed.empty()) {
          text += "; NOT by";
          for (const auto& a : unconfirmed) text += " " + a.to_string();
        }
        if (confirmed.empty() && unconfirmed.empty()) text += ": no component answered";
        event(confirmed.empty() || !unconfirmed.empty() ? EventLevel::error : EventLevel::info, text);
      }));
  command.start();
}

template <class M>
void OperatorConsole::send_must_arrive(const jaus::Address& to, const M& message, const std::string& what) {
  std::vector<std::uint8_t> payload(jaus::kMaxPayloadSize);
  const auto size = jaus::wire::encode_payload(message, payload);
  if (!size) return;
  payload.resize(*size);
  jaus::Header header;
  header.command_code = M::code;
  header.priority = M::code == jaus::msg::SetEmergency::code ? jaus::priority::kSafetyCritical : jaus::priority::kDefault;
  header.destination = to;
  header.source = session_.self();
  header.data_size = static_cast<std::uint16_t>(payload.size());
  if (to.is_broadcast()) return send_to_every_member(to, header, std::move(payload), what);
  std::weak_ptr<int> alive = alive_;
  session_.node().send_acknowledged(
      header, payload, kMustArrive, [this, alive, what](const jaus::node::AckResolution& resolution) {
        if (alive.expired()) return;
        const bool arrived = resolution.outcome == jaus::node::AckOutcome::acknowledged;
        event(arrived ? EventLevel::info : EventLevel::error,
              what + ": " + std::string(jaus::node::to_string(resolution.outcome)) + " after " +
                  std::to_string(resolution.transmissions) + " transmission(s)");
      });
}

void OperatorConsole::on_emergency(PageId page, const EmergencyFrame& frame) {
  const auto& target = frame.target;
  const std::string who = target.is_broadcast() ? std::string("all") : target.to_string();
  if (frame.set) {
    send_must_arrive(target, jaus::msg::SetEmergency{{1}}, "Set Emergency to " + who);
    emergencies_[target] = true;
    to_all(EmergencyStateFrame{target, true, {session_.self()}});
    event(EventLevel::warn, "emergency set on " + who + " (page " + std::to_string(page) + ")");
    // Nothing drives into an emergency: stop what this console drives there.
    std::vector<jaus::Address> driven;
    for (const auto& [driven_target, drive] : drives_)
      if (target.is_broadcast() || driven_target == target) driven.push_back(driven_target);
    for (const auto& t : driven) stop_drive(t, "emergency");
    return;
  }
  send_must_arrive(target, jaus::msg::ClearEmergency{{1}}, "Clear Emergency to " + who);
  emergencies_.erase(target);
  to_all(EmergencyStateFrame{target, false, {}});
  event(EventLevel::info, "emergency cleared on " + who + " by this console (page " + std::to_string(page) + ")");
}

void OperatorConsole::on_state(PageId page, const StateFrame& frame) {
  if (frame.resume) {
    // Control was lost when the target left Ready (Standby): Resume is a
    // controller's, so ask again with the authority the page last asked
    // with. The Request goes first, the Resume right behind it.
    auto it = controls_.find(frame.target);
    if (it != controls_.end() && it->second.authority && it->second.client &&
        it->second.client->state() == jaus::rt::ControlClient::State::released)
      request_control(page, frame.target, *it->second.authority);
    session_.send(frame.target, jaus::msg::Resume{});
  } else {
    stop_drive(frame.target, "standby");
    session_.send(frame.target, jaus::msg::Standby{});
  }
  event(EventLevel::info, std::string(frame.resume ? "Resume" : "Standby") + " sent to " +
                              frame.target.to_string() + " (page " + std::to_string(page) + ")");
}

// ---- camera, arm, waypoints

void OperatorConsole::on_camera(PageId page, const CameraFrame& frame) {
  const auto& target = frame.target;
  if (frame.watch) {
    auto& camera = cameras_[target];
    camera.watchers.insert(page);
    if (!camera.subscription) {
      camera.subscription = session_.component().subscribe<jaus::msg::ReportImage>(
          target, options_.report_rate_hz, 0, [this, target](const jaus::Header&, const jaus::msg::ReportImage& r) {
            auto it = cameras_.find(target);
            if (it == cameras_.end()) return;
            const auto text = format_frame(
                ImageFrame{target, image_format_name(r.image_format), base64(r.data), ++it->second.frames});
            for (PageId watcher : it->second.watchers) output_(watcher, text);
          });
      event(EventLevel::info, "watching " + target.to_string());
    }
  } else {
    unwatch(target, page);
  }
  if (frame.pan_deg || frame.tilt_deg) {
    const auto percent = [](std::optional<double> deg, double full_scale) -> std::optional<double> {
      if (!deg || !(full_scale > 0)) return std::nullopt;
      return within(*deg / full_scale * 100, -100, 100);
    };
    jaus::msg::SetCameraPose pose{};
    pose.camera_id = options_.camera_id;
    pose.mode_indicator = 0;  // position, not rate
    pose.y_angular_percent = percent(frame.pan_deg, options_.camera_pan_full_scale_deg);
    pose.x_angular_percent = percent(frame.tilt_deg, options_.camera_tilt_full_scale_deg);
    as_controller(page, target, [this, target, pose] { session_.send(target, pose); });
  }
}

void OperatorConsole::unwatch(const jaus::Address& target, PageId page) {
  auto it = cameras_.find(target);
  if (it == cameras_.end()) return;
  it->second.watchers.erase(page);
  if (!it->second.watchers.empty()) return;
  if (it->second.subscription) session_.component().unsubscribe(*it->second.subscription);
  cameras_.erase(it);
  event(EventLevel::info, "no page watches " + target.to_string() + ": its images stop");
}

void OperatorConsole::on_arm(PageId page, const ArmFrame& frame) {
  auto it = arms_.find(frame.target);
  if (it == arms_.end() || !it->second.specifications) {
    session_.send(frame.target, jaus::msg::QueryManipulatorSpecifications{});
    refuse(page, "arm: no Report Manipulator Specifications from " + frame.target.to_string() + " yet");
    return;
  }
  const auto limits = joint_limits(*it->second.specifications);
  if (frame.joints.size() != limits.size()) {
    refuse(page, "arm: " + frame.target.to_string() + " has " + std::to_string(limits.size()) + " joints, not " +
                     std::to_string(frame.joints.size()));
    return;
  }
  jaus::msg::SetJointPositions set{};
  for (std::size_t i = 0; i < limits.size(); ++i) {
    const double value = limits[i].revolute ? radians(frame.joints[i]) : frame.joints[i];
    // The specifications carry limits to 0.001 (rad or m), rounded either
    // way: one step inside them is within the arm's real limits.
    constexpr double kStep = 0.001;
    const double low = std::min(limits[i].min, limits[i].max) + kStep;
    const double high = std::max(limits[i].min, limits[i].max) - kStep;
    set.positions_rad.push_back(low < high ? within(value, low, high) : within(value, limits[i].min, limits[i].max));
  }
  as_controller(page, frame.target, [this, target = frame.target, set] { session_.send(target, set); });
}

void OperatorConsole::publish_arm(const jaus::Address& source) {
  const auto it = arms_.find(source);
  if (it == arms_.end() || !it->second.specifications) return;
  const auto limits = joint_limits(*it->second.specifications);
  ArmStateFrame frame{source, {}};
  for (std::size_t i = 0; i < limits.size(); ++i) {
    const auto& l = limits[i];
    const double position = i < it->second.positions_rad_or_m.size() ? it->second.positions_rad_or_m[i] : 0.0;
    frame.joints.push_back(l.revolute ? ArmJoint{degrees(l.min), degrees(l.max), degrees(signed_angle(position)), "deg"}
                                      : ArmJoint{l.min, l.max, position, "m"});
  }
  to_all(frame);
}

void OperatorConsole::on_waypoints(PageId page, const WaypointsFrame& frame) {
  // A route drives when its driver goes from Standby to Ready (Resume):
  // Standby first, then the list, all while still its controller (control
  // is lost at the next status poll; `resume` takes it again).
  session_.send(frame.target, jaus::msg::Standby{});
  session_.send(frame.target, jaus::msg::SetTravelSpeed{{frame.speed_mps}});
  for (std::size_t i = 0; i < frame.points.size(); ++i) {
    jaus::msg::SetLocalWaypoint waypoint{};
    waypoint.waypoint_number = static_cast<std::uint16_t>(i);
    waypoint.x_m = frame.points[i].x;
    waypoint.y_m = frame.points[i].y;
    session_.send(frame.target, waypoint);
  }
  event(EventLevel::info, "loaded " + std::to_string(frame.points.size()) + " waypoint(s) into " +
                              frame.target.to_string() + " at " + std::to_string(frame.speed_mps) + " m/s (page " +
                              std::to_string(page) + ")");
}

// ---- the network

void OperatorConsole::send_discovery(const std::vector<jaus::ocu::DiscoveryQuery>& queries) {
  for (const auto& q : queries) {
    switch (q.kind) {
      case jaus::ocu::DiscoveryQuery::Kind::identification:
        session_.send(q.to, jaus::msg::QueryIdentification{{q.field}});
        break;
      case jaus::ocu::DiscoveryQuery::Kind::configuration:
        session_.send(q.to, jaus::msg::QueryConfiguration{{q.field}});
        break;
      case jaus::ocu::DiscoveryQuery::Kind::services:
        session_.send(q.to, jaus::msg::QueryServices{});
        break;
      case jaus::ocu::DiscoveryQuery::Kind::subsystem_list:
        session_.send(q.to, jaus::msg::QuerySubsystemList{});
        break;
    }
  }
}

void OperatorConsole::on_heard(const jaus::Header& header) {
  if (header.source.subsystem == session_.self().subsystem && header.source.node == session_.self().node) return;
  heard_[node_key(header.source)] = clock_.now();
  const auto queries = discovery_.heard(header.source);
  if (queries.empty()) return;
  send_discovery(queries);
  publish_tree();
}

void OperatorConsole::on_received(const jaus::ocu::Received& r) {
  const auto& h = r.header;
  const auto code = h.command_code;
  if (auto it = controls_.find(h.source); it != controls_.end() && it->second.client)
    it->second.client->on_message(h, r.payload);
  if (code == jaus::msg::ReportComponentStatus::code) {
    if (auto m = decode<jaus::msg::ReportComponentStatus>(r.payload))
      live_[h.source].status = static_cast<std::uint8_t>(m->primary_status & 0x0F);
  } else if (code == jaus::msg::ReportComponentControl::code) {
    if (auto m = decode<jaus::msg::ReportComponentControl>(r.payload)) {
      auto& live = live_[h.source];
      live.controller = m->controller == jaus::Address{} ? std::nullopt : std::optional<jaus::Address>(m->controller);
      live.authority = m->authority;
    }
  } else if (code == jaus::msg::ReportManipulatorSpecifications::code) {
    if (auto m = decode<jaus::msg::ReportManipulatorSpecifications>(r.payload)) {
      arms_[h.source].specifications = *m;
      publish_arm(h.source);
    }
  }
  if (!is_tree_report(code)) return;
  send_discovery(discovery_.received(h, r.payload, session_.options().dialect));
  follow_new_components();
  publish_tree();
}

void OperatorConsole::follow_new_components() {
  if (shut_down_) return;
  auto& component = session_.component();
  for (const auto& [sid, subsystem] : discovery_.subsystems())
    for (const auto& [nid, node] : subsystem.nodes)
      for (const auto& [key, c] : node.components) {
        const auto a = c.address;
        if (followed_.count(a)) continue;
        const auto rate = options_.report_rate_hz;
        switch (a.component) {
          case component_id::kLocalPoseSensor:
            report_subscriptions_.push_back(component.subscribe<jaus::msg::ReportLocalPose>(
                a, rate, kLocalPoseFields, [this, a](const jaus::Header&, const jaus::msg::ReportLocalPose& p) {
                  PoseFrame frame{a, p.x_m.value_or(0), p.y_m.value_or(0), p.yaw_rad.value_or(0), {}, {}};
                  if (auto ll = latitude_longitude_.find(node_key(a)); ll != latitude_longitude_.end()) {
                    frame.latitude = ll->second.first;
                    frame.longitude = ll->second.second;
                  }
                  to_all(frame);
                }));
            break;
          case component_id::kGlobalPoseSensor:
            report_subscriptions_.push_back(component.subscribe<jaus::msg::ReportGlobalPose>(
                a, rate, kGlobalPoseFields, [this, a](const jaus::Header&, const jaus::msg::ReportGlobalPose& p) {
                  if (p.latitude_deg && p.longitude_deg)
                    latitude_longitude_[node_key(a)] = {*p.latitude_deg, *p.longitude_deg};
                }));
            break;
          case component_id::kVelocityStateSensor:
            report_subscriptions_.push_back(component.subscribe<jaus::msg::ReportVelocityState>(
                a, rate, kVelocityFields, [this, a](const jaus::Header&, const jaus::msg::ReportVelocityState& v) {
                  to_all(VelocityFrame{a, v.velocity_x_mps.value_or(0), v.velocity_y_mps.value_or(0),
                                       v.yaw_rate_rps.value_or(0)});
                }));
            break;
          case component_id::kPrimitiveManipulator:
            session_.send(a, jaus::msg::QueryManipulatorSpecifications{});
            report_subscriptions_.push_back(component.subscribe<jaus::msg::ReportJointPositions>(
                a, rate, 0, [this, a](const jaus::Header&, const jaus::msg::ReportJointPositions& j) {
                  arms_[a].positions_rad_or_m = j.positions_rad;
                  publish_arm(a);
                }));
            break;
          default: continue;
        }
        followed_.insert(a);
      }
}

void OperatorConsole::poll() {
  for (const auto& [sid, subsystem] : discovery_.subsystems())
    for (const auto& [nid, node] : subsystem.nodes)
      for (const auto& [key, c] : node.components) {
        session_.send(c.address, jaus::msg::QueryComponentStatus{});
        session_.send(c.address, jaus::msg::QueryComponentControl{});
      }
}

void OperatorConsole::send_link() {
  std::optional<std::int64_t> last;
  for (const auto& [node, when] : heard_) {
    const auto ms = static_cast<std::int64_t>(
        std::chrono::duration_cast<std::chrono::milliseconds>(clock_.now() - when).count());
    last = last ? std::min(*last, ms) : ms;
  }
  to_all(LinkFrame{heard_.size(), last});
}

TreeFrame OperatorConsole::tree() const {
  TreeFrame frame;
  for (const auto& [sid, subsystem] : discovery_.subsystems()) {
    TreeSubsystem s{sid, subsystem.identification ? subsystem.identification->name : std::string(), {}};
    for (const auto& [nid, node] : subsystem.nodes) {
      TreeNode n{nid, node.identification ? node.identification->name : std::string(), {}};
      for (const auto& [key, c] : node.components) {
        TreeComponent tc{c.address, c.identification ? c.identification->name : std::string(), "unknown", {}, 0};
        if (auto it = live_.find(c.address); it != live_.end()) {
          tc.state = state_name(it->second.status);
          tc.controller = it->second.controller;
          tc.authority = it->second.authority;
        }
        n.components.push_back(std::move(tc));
      }
      s.nodes.push_back(std::move(n));
    }
    frame.subsystems.push_back(std::move(s));
  }
  return frame;
}

void OperatorConsole::publish_tree() {
  auto text = format_frame(tree());
  if (text == last_tree_) return;
  last_tree_ = std::move(text);
  output_(kEveryPage, last_tree_);
}

}  // namespace jaus::console
