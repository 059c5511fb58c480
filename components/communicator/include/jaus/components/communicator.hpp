// The communicator (component 35): the state of this node's data links to
// other subsystems, as Part 3's communications subgroup describes them.
// Setting a link state or the selected link is a command (controller only);
// queries are answered to anyone. It is also the subsystem's voice to other
// subsystems: Report Heartbeat Pulse to (255, 255, 1, 1) at the heartbeat
// rate, which is how their node managers learn of this subsystem
// (docs/wire-format.md, "Liveness and discovery").
#pragma once

#include <map>

#include "jaus/messages/communications_messages.hpp"
#include "jaus/runtime/component.hpp"

namespace jaus::components {

namespace data_link {
inline constexpr std::uint8_t kOff = 0;
inline constexpr std::uint8_t kOn = 1;
inline constexpr std::uint8_t kStandby = 2;
inline constexpr std::uint8_t kLossOfCommand = 3;
}  // namespace data_link

struct CommunicatorConfig {
  std::uint8_t link_count = 1;
  rt::Duration heartbeat_period = std::chrono::seconds(1);  // 0: no heartbeats to other subsystems
};

class Communicator final : public rt::Component {
 public:
  Communicator(rt::ComponentConfig config, rt::Environment env, CommunicatorConfig options = {});
  ~Communicator() override;

  std::uint8_t selected_link() const { return selected_; }
  std::uint8_t link_state(std::uint8_t link) const;
  // The transport reports a link lost or back (e.g. no traffic from the OCU).
  void set_link_state(std::uint8_t link, std::uint8_t state);

 protected:
  bool initialize() override;

 private:
  void heartbeat();

  std::map<std::uint8_t, std::uint8_t> links_;  // data link ID -> state
  std::uint8_t selected_ = 0;
  rt::Duration heartbeat_period_;
  rt::TimerId heartbeat_timer_ = rt::kNoTimer;
};

}  // namespace jaus::components
