// The Arm panel: a manipulator's joints (limits from Report Manipulator
// Specifications, positions by service connection) to every page as `arm`,
// and Set Joint Positions from a page, each joint clamped to its limits and
// sent as the arm's controller.
#pragma once

#include <map>
#include <optional>
#include <vector>

#include "jaus/console/panels/control_panel.hpp"
#include "jaus/console/panels/panel.hpp"
#include "jaus/messages/manipulator_messages.hpp"

namespace jaus::console {

class ArmPanel final : public Panel {
 public:
  ArmPanel(PanelContext& context, ControlPanel& control) : Panel(context), control_(control) {}

  std::vector<std::string_view> views() const override { return {jaus::rt::operator_view::kArm}; }
  void follow(const jaus::Address& component, std::string_view view) override;
  void received(const jaus::ocu::Received& message) override;
  void on_frame(PageId page, const ArmFrame& frame);

 private:
  struct Arm {
    std::optional<jaus::msg::ManipulatorSpecificationsBody> specifications;
    std::vector<double> positions_rad_or_m;
  };

  void publish(const jaus::Address& source);

  ControlPanel& control_;
  std::map<jaus::Address, Arm> arms_;
};

}  // namespace jaus::console
