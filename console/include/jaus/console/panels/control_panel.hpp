// The Control panel: control of a component as this console's OCU (one JAUS
// ID shared by every page), requested and released by pages or asked for by
// a command that needs it (pan/tilt, joints), and the component's state
// (Resume, Standby). rt::ControlClient keeps each hold: "held" is confirmed
// and Ready. Whatever ends a hold (released, refused, lost, a Standby) ends
// the drive of that target first (`stop_drive`).
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>

#include "jaus/console/panels/panel.hpp"
#include "jaus/runtime/control_client.hpp"

namespace jaus::console {

class ControlPanel final : public Panel {
 public:
  using StopDrive = std::function<void(const jaus::Address& target, const std::string& why)>;

  ControlPanel(PanelContext& context, StopDrive stop_drive);

  void on_frame(PageId page, const ControlFrame& frame);
  void on_frame(PageId page, const StateFrame& frame);
  // Whether this console holds control of `target` (confirmed and Ready).
  bool holds(const jaus::Address& target) const;
  // Runs `command` now if control of `target` is held, else asks for it
  // (the page's last authority, or the OCU's own) and runs it once held;
  // the latest command wins.
  void as_controller(PageId page, const jaus::Address& target, std::function<void()> command);

  void page_opened(PageId page) override;
  void received(const jaus::ocu::Received& message) override;
  void shutdown() override;

 private:
  struct Control {
    std::unique_ptr<jaus::rt::ControlClient> client;
    ControlState state = ControlState::released;
    std::string why;
    std::optional<std::uint8_t> authority;  // of the last request a page made
    std::function<void()> when_held;
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

  Control& control_of(const jaus::Address& target);
  void request(PageId page, const jaus::Address& target, std::uint8_t authority);
  void set_state(const jaus::Address& target, ControlState state, const std::string& why);
  void release(const jaus::Address& target);

  StopDrive stop_drive_;
  SessionOutbox outbox_;
  jaus::rt::Environment environment_;
  std::map<jaus::Address, Control> controls_;
};

}  // namespace jaus::console
