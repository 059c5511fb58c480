#include "jaus/console/panels/drive_panel.hpp"

#include <vector>

#include "jaus/messages/all.hpp"

namespace jaus::console {

DrivePanel::~DrivePanel() {
  for (auto& [target, drive] : drives_) context_.scheduler.cancel(drive.timer);
}

void DrivePanel::send_effort(const jaus::Address& target, double linear, double angular) {
  jaus::msg::SetWrenchEffort effort{};
  effort.propulsive_linear_effort_x_percent = linear;
  effort.propulsive_rotational_effort_z_percent = angular;
  session().send(target, effort);
}

void DrivePanel::on_frame(PageId page, const DriveFrame& frame) {
  const auto& target = frame.target;
  auto it = drives_.find(target);
  if (!frame.held) {
    if (it != drives_.end() && it->second.by == page) stop(target, "released by page " + std::to_string(page));
    return;
  }
  if (it != drives_.end() && it->second.by != page) {
    pages().refuse(page, "drive: " + target.to_string() + " is driven by page " + std::to_string(it->second.by));
    return;
  }
  if (!control_.holds(target)) {
    pages().refuse(page, "drive: this console does not hold control of " + target.to_string() +
                             " (request control first; it must be Ready)");
    return;
  }
  const auto now = context_.clock.now();
  const bool starting = it == drives_.end();
  auto& drive = drives_[target];
  const bool changed = starting || drive.linear != frame.linear_percent || drive.angular != frame.angular_percent;
  drive.by = page;
  drive.linear = frame.linear_percent;
  drive.angular = frame.angular_percent;
  drive.fresh_until = now + options().deadman;
  if (!changed) return;  // the timer sends it on at 20 Hz
  // A change goes at once (a key pressed is on the wire within the handler),
  // and the period starts again from it.
  send_effort(target, drive.linear, drive.angular);
  ++counters_.efforts_sent;
  context_.scheduler.cancel(drive.timer);
  drive.timer = context_.scheduler.call_at(now + options().drive_period, [this, target] { tick(target); });
  if (starting) {
    pages().to_all(DrivingFrame{target, true, page});
    pages().event(EventLevel::info, "page " + std::to_string(page) + " drives " + target.to_string());
  }
}

void DrivePanel::tick(const jaus::Address& target) {
  auto it = drives_.find(target);
  if (it == drives_.end()) return;
  auto& drive = it->second;
  drive.timer = jaus::rt::kNoTimer;
  const auto now = context_.clock.now();
  if (!control_.holds(target)) {
    stop(target, "control of it is not held");
    return;
  }
  if (now > drive.fresh_until) {
    stop(target, "deadman: no drive frame for " + std::to_string(options().deadman.count()) + " ms");
    return;
  }
  send_effort(target, drive.linear, drive.angular);
  ++counters_.efforts_sent;
  drive.timer = context_.scheduler.call_at(now + options().drive_period, [this, target] { tick(target); });
}

void DrivePanel::stop_reached_by(const jaus::Address& target, const std::string& why) {
  stop_where([&](const jaus::Address& driven, const Drive&) { return target.is_broadcast() || driven == target; }, why);
}

void DrivePanel::stop_where(const std::function<bool(const jaus::Address&, const Drive&)>& which,
                            const std::string& why) {
  std::vector<jaus::Address> driven;
  for (const auto& [target, drive] : drives_)
    if (which(target, drive)) driven.push_back(target);
  for (const auto& target : driven) stop(target, why);
}

void DrivePanel::stop(const jaus::Address& target, const std::string& why) {
  auto it = drives_.find(target);
  if (it == drives_.end()) return;
  context_.scheduler.cancel(it->second.timer);
  drives_.erase(it);
  // Zero only to a driver we still command: one that left Ready or changed
  // controller stopped itself (docs/safety.md), and refuses commands.
  if (control_.holds(target)) {
    send_effort(target, 0, 0);
    ++counters_.zero_efforts_sent;
  }
  pages().to_all(DrivingFrame{target, false, std::nullopt});
  pages().event(EventLevel::info, "stopped driving " + target.to_string() + ": " + why);
}

void DrivePanel::page_opened(PageId page) {
  for (const auto& [target, drive] : drives_) pages().to_page(page, DrivingFrame{target, true, drive.by});
}

void DrivePanel::page_closed(PageId page) {
  stop_where([page](const jaus::Address&, const Drive& drive) { return drive.by == page; },
             "page " + std::to_string(page) + " closed");
}

void DrivePanel::shutdown() {
  stop_where([](const jaus::Address&, const Drive&) { return true; }, "the console is shutting down");
  Panel::shutdown();
}

}  // namespace jaus::console
