// The Camera panel: Report Image of a visual sensor by service connection
// while any page watches it (one connection for every page, each image to
// the watchers alone), and pan/tilt as Set Camera Pose, sent as the
// sensor's controller.
#pragma once

#include <map>
#include <optional>
#include <set>

#include "jaus/console/panels/control_panel.hpp"
#include "jaus/console/panels/panel.hpp"

namespace jaus::console {

class CameraPanel final : public Panel {
 public:
  CameraPanel(PanelContext& context, ControlPanel& control) : Panel(context), control_(control) {}

  std::vector<std::string_view> views() const override { return {jaus::rt::operator_view::kCamera}; }
  void on_frame(PageId page, const CameraFrame& frame);
  void page_closed(PageId page) override;
  void shutdown() override;

 private:
  struct Camera {
    std::set<PageId> watchers;
    std::optional<jaus::rt::SubscriptionId> subscription;
    std::uint64_t frames = 0;
  };

  void watch(const jaus::Address& target, PageId page);
  void unwatch(const jaus::Address& target, PageId page);

  ControlPanel& control_;
  std::map<jaus::Address, Camera> cameras_;
};

}  // namespace jaus::console
