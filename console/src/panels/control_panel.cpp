#include "jaus/console/panels/control_panel.hpp"

#include <utility>

#include "jaus/messages/all.hpp"

namespace jaus::console {

ControlPanel::ControlPanel(PanelContext& context, StopDrive stop_drive)
    : Panel(context),
      stop_drive_(std::move(stop_drive)),
      outbox_(context.session),
      environment_{context.clock, context.scheduler, outbox_,
                   context.options.log ? context.options.log : jaus::rt::silent_log()} {}

ControlPanel::Control& ControlPanel::control_of(const jaus::Address& target) {
  auto& control = controls_[target];
  if (!control.client) {
    jaus::rt::ControlClient::Io io{
        [this](const jaus::Address& to, const jaus::msg::RequestComponentControl& m) { session().send(to, m); },
        [this](const jaus::Address& to, const jaus::msg::ReleaseComponentControl& m) { session().send(to, m); },
        [this](const jaus::Address& to, const jaus::msg::QueryComponentStatus& m) { session().send(to, m); }};
    control.client = std::make_unique<jaus::rt::ControlClient>(environment_, jaus::rt::ControlClient::Options{}, io);
  }
  return control;
}

bool ControlPanel::holds(const jaus::Address& target) const {
  const auto it = controls_.find(target);
  return it != controls_.end() && it->second.client && it->second.client->held();
}

void ControlPanel::set_state(const jaus::Address& target, ControlState state, const std::string& why) {
  auto& control = controls_[target];
  control.state = state;
  control.why = why;
  pages().to_all(ControlStateFrame{target, state, why});
}

void ControlPanel::page_opened(PageId page) {
  for (const auto& [target, control] : controls_)
    if (control.state != ControlState::released)
      pages().to_page(page, ControlStateFrame{target, control.state, control.why});
}

void ControlPanel::received(const jaus::ocu::Received& r) {
  if (auto it = controls_.find(r.header.source); it != controls_.end() && it->second.client)
    it->second.client->on_message(r.header, r.payload);
}

void ControlPanel::on_frame(PageId page, const ControlFrame& frame) {
  const auto& target = frame.target;
  if (target.is_broadcast()) {
    pages().refuse(page, "control: the target must be one component, not a broadcast address");
    return;
  }
  if (!frame.request) {
    release(target);
    set_state(target, ControlState::released, "released by page " + std::to_string(page));
    pages().event(EventLevel::info,
                  "control of " + target.to_string() + " released (page " + std::to_string(page) + ")");
    return;
  }
  request(page, target, frame.authority);
}

void ControlPanel::request(PageId page, const jaus::Address& target, std::uint8_t authority) {
  auto& control = control_of(target);
  if (control.client->state() != jaus::rt::ControlClient::State::released) return;  // already asked or held
  control.authority = authority;
  set_state(target, ControlState::requesting, "");
  pages().event(EventLevel::info, "requesting control of " + target.to_string() + " with authority " +
                                      std::to_string(authority) + " (page " + std::to_string(page) + ")");
  control.client->acquire(
      target, authority,
      [this, target] {
        set_state(target, ControlState::held, "");
        pages().event(EventLevel::info, "control of " + target.to_string() + " held");
        if (auto pending = std::exchange(controls_[target].when_held, nullptr)) pending();
      },
      [this, target](const std::string& why) {
        const bool was_held = controls_[target].state == ControlState::held;
        set_state(target, was_held ? ControlState::lost : ControlState::refused, why);
        stop_drive_(target, "control " + std::string(was_held ? "lost" : "refused") + ": " + why);
        pages().event(was_held ? EventLevel::warn : EventLevel::info,
                      "control of " + target.to_string() + (was_held ? " lost: " : " refused: ") + why);
      });
}

void ControlPanel::as_controller(PageId page, const jaus::Address& target, std::function<void()> command) {
  if (holds(target)) {
    command();
    return;
  }
  auto& control = control_of(target);
  control.when_held = std::move(command);
  request(page, target, control.authority.value_or(session().options().authority));
}

void ControlPanel::release(const jaus::Address& target) {
  stop_drive_(target, "control released");  // the zero goes while control is still ours
  const auto it = controls_.find(target);
  if (it != controls_.end() && it->second.client) it->second.client->release();
}

void ControlPanel::on_frame(PageId page, const StateFrame& frame) {
  if (frame.resume) {
    // Control was lost when the target left Ready (Standby): Resume is a
    // controller's, so ask again with the authority the page last asked
    // with. The Request goes first, the Resume right behind it.
    auto it = controls_.find(frame.target);
    if (it != controls_.end() && it->second.authority && it->second.client &&
        it->second.client->state() == jaus::rt::ControlClient::State::released)
      request(page, frame.target, *it->second.authority);
    session().send(frame.target, jaus::msg::Resume{});
  } else {
    stop_drive_(frame.target, "standby");
    session().send(frame.target, jaus::msg::Standby{});
  }
  pages().event(EventLevel::info, std::string(frame.resume ? "Resume" : "Standby") + " sent to " +
                                      frame.target.to_string() + " (page " + std::to_string(page) + ")");
}

void ControlPanel::shutdown() {
  for (auto& [target, control] : controls_)
    if (control.client && control.client->state() != jaus::rt::ControlClient::State::released) {
      control.client->release();
      control.state = ControlState::released;
      pages().to_all(ControlStateFrame{target, ControlState::released, "the console is shutting down"});
    }
  Panel::shutdown();
}

}  // namespace jaus::console
