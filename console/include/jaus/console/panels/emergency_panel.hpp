// The emergency button (docs/console.md, "The deadman and the safety
// rules"): Set Emergency must arrive (ACK-requested and retransmitted by the
// node; to a wildcard such as `all`, to every component it names, each
// confirming it), and nothing this console drives there drives on; Clear
// Emergency releases this console's own hold. Every page sees the holds.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "jaus/console/panels/drive_panel.hpp"
#include "jaus/console/panels/panel.hpp"
#include "jaus/ocu/wildcard_command.hpp"

namespace jaus::console {

class EmergencyPanel final : public Panel {
 public:
  EmergencyPanel(PanelContext& context, DrivePanel& drive) : Panel(context), drive_(drive) {}
  ~EmergencyPanel() override;
  EmergencyPanel(const EmergencyPanel&) = delete;
  EmergencyPanel& operator=(const EmergencyPanel&) = delete;

  std::vector<std::string_view> views() const override { return {jaus::rt::operator_view::kEmergency}; }
  void on_frame(PageId page, const EmergencyFrame& frame);
  void page_opened(PageId page) override;

 private:
  template <class M>
  void send_must_arrive(const jaus::Address& to, const M& message, const std::string& what);
  void send_to_every_member(const jaus::Address& to, jaus::Header header, std::vector<std::uint8_t> payload,
                            const std::string& what);

  DrivePanel& drive_;
  std::map<jaus::Address, bool> emergencies_;  // set by this console: active
  std::vector<std::unique_ptr<jaus::ocu::WildcardCommand>> wildcards_;
  // Callbacks the node may call after this panel is gone check this first.
  std::shared_ptr<int> alive_ = std::make_shared<int>(0);
};

}  // namespace jaus::console
