// The JSS (SAE JAUS) table of the JAUS half: every message of the JSS
// catalogue's lists, walked by jaus_table.hpp like the RA ones; lua/jaus.lua
// dissects AS5669A datagrams (version byte 0x02) with it.
#include "jaus/jss/all.hpp"
#include "jaus_table.hpp"
#include "wireshark_plugin.hpp"

namespace jaus::wireshark {

namespace {

template <class... Ms>
void append_jss_messages(std::string& out, msg::TypeList<Ms...>) {
  ((out += jaus_table::message_lua<Ms>(wire::Dialect::jss)), ...);
}

}  // namespace

std::string jss_tables_lua() {
  std::string out = "local JSS_MESSAGES = {\n";
  append_jss_messages(out, jss::msg::AccessControlMessages{});
  append_jss_messages(out, jss::msg::ManagementMessages{});
  append_jss_messages(out, jss::msg::TimeMessages{});
  append_jss_messages(out, jss::msg::LivenessMessages{});
  append_jss_messages(out, jss::msg::EventsMessages{});
  append_jss_messages(out, jss::msg::DiscoveryMessages{});
  append_jss_messages(out, jss::msg::SensorDriverMessages{});
  append_jss_messages(out, jss::msg::WaypointMessages{});
  return out + "}\n";
}

}  // namespace jaus::wireshark
