// The communicator (component 35): the state of this node's data links to
// other subsystems, as Part 3's communications subgroup describes them.
// Setting a link state or the selected link is a command (controller only);
// queries are answered to anyone.
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

class Communicator final : public rt::Component {
 public:
  Communicator(rt::ComponentConfig config, rt::Environment env, std::uint8_t link_count = 1);

  std::uint8_t selected_link() const { return selected_; }
  std::uint8_t link_state(std::uint8_t link) const;
  // The transport reports a link lost or back (e.g. no traffic from the OCU).
  void set_link_state(std::uint8_t link, std::uint8_t state);

 private:
  std::map<std::uint8_t, std::uint8_t> links_;  // data link ID -> state
  std::uint8_t selected_ = 0;
};

}  // namespace jaus::components
