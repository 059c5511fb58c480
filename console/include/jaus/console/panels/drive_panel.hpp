// The Drive panel and its deadman (docs/console.md, "The deadman"; docs/safety.md):
// Set Wrench Effort goes to a driver only while this console holds control
// of it and it is Ready (ControlPanel::holds), and only while a page keeps
// the deadman fresh (a `drive` with held:true younger than `deadman`), at
// drive_period, a change at once. The moment the page lets go (held:false),
// goes silent, closes, or the console shuts down, one zero effort is sent
// and then nothing. Control lost stops the drive at once, without a zero:
// the driver already stopped itself on that path (Component::enforce_stop).
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <string>

#include "jaus/console/panels/control_panel.hpp"
#include "jaus/console/panels/panel.hpp"

namespace jaus::console {

class DrivePanel final : public Panel {
 public:
  struct Counters {
    std::uint64_t efforts_sent = 0;  // Set Wrench Effort while driving
    std::uint64_t zero_efforts_sent = 0;
  };

  DrivePanel(PanelContext& context, const ControlPanel& control) : Panel(context), control_(control) {}
  ~DrivePanel() override;
  DrivePanel(const DrivePanel&) = delete;
  DrivePanel& operator=(const DrivePanel&) = delete;

  std::vector<std::string_view> views() const override { return {jaus::rt::operator_view::kDrive}; }
  void on_frame(PageId page, const DriveFrame& frame);
  // Stops the drive of `target`.
  void stop(const jaus::Address& target, const std::string& why);
  // Stops every drive an emergency to `target` reaches: its own, or every
  // one for a broadcast address.
  void stop_reached_by(const jaus::Address& target, const std::string& why);
  bool driving(const jaus::Address& target) const { return drives_.count(target) != 0; }
  const Counters& counters() const { return counters_; }

  void page_opened(PageId page) override;
  void page_closed(PageId page) override;
  void shutdown() override;

 private:
  struct Drive {
    PageId by = 0;
    double linear = 0;
    double angular = 0;
    jaus::rt::TimePoint fresh_until{};
    jaus::rt::TimerId timer = jaus::rt::kNoTimer;
  };

  void tick(const jaus::Address& target);
  void stop_where(const std::function<bool(const jaus::Address&, const Drive&)>& which, const std::string& why);
  void send_effort(const jaus::Address& target, double linear, double angular);

  const ControlPanel& control_;
  std::map<jaus::Address, Drive> drives_;
  Counters counters_;
};

}  // namespace jaus::console
