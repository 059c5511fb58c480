// The System panel: what the console's discovery found (subsystems, nodes,
// components, as `jausctl discover` finds them) with each component's state
// and controller, polled every poll_period; the `tree` frame on every change.
#pragma once

#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "jaus/console/panels/panel.hpp"
#include "jaus/ocu/discovery.hpp"

namespace jaus::console {

class TreePanel final : public Panel {
 public:
  // Called when discovery may have found components (after a tree report).
  TreePanel(PanelContext& context, std::function<void()> found);

  void start();
  const jaus::ocu::Discovery& discovery() const { return discovery_; }
  TreeFrame tree() const;

  void page_opened(PageId page) override;
  void received(const jaus::ocu::Received& message) override;
  void heard(const jaus::Header& header) override;
  void shutdown() override;

 private:
  struct Live {
    std::optional<std::uint8_t> status;
    std::optional<jaus::Address> controller;
    std::uint8_t authority = 0;
  };

  void send_discovery(const std::vector<jaus::ocu::DiscoveryQuery>& queries);
  void poll();
  void publish();

  std::function<void()> found_;
  jaus::ocu::Discovery discovery_;
  std::map<jaus::Address, Live> live_;
  std::string last_tree_;
  Periodic poll_timer_;
};

}  // namespace jaus::console
