// The JAUS half's table: every message of the catalogue's lists, walked by
// jaus_table.hpp.
#include "jaus_table.hpp"

#include "jaus/messages/all.hpp"
#include "wireshark_plugin.hpp"

namespace jaus::wireshark {

namespace {

template <class... Ms>
void append_messages(std::string& out, msg::TypeList<Ms...>) {
  ((out += jaus_table::message_lua<Ms>()), ...);
}

}  // namespace

std::string jaus_tables_lua() {
  std::string out = "local MESSAGES = {\n";
  append_messages(out, msg::CoreMessages{});
  append_messages(out, msg::CommunicationsMessages{});
  append_messages(out, msg::PlatformMessages{});
  append_messages(out, msg::ManipulatorMessages{});
  append_messages(out, msg::EnvironmentMessages{});
  append_messages(out, msg::DiscoveryMessages{});
  append_messages(out, msg::EventMessages{});
  return out + "}\n";
}

}  // namespace jaus::wireshark
