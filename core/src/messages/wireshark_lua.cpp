#include "jaus/messages/wireshark_lua.hpp"

#include "jaus/messages/all.hpp"
#include "jaus/messages/wireshark_fields.hpp"
#include "wireshark_runtime.hpp"

namespace jaus::msg {

namespace {

template <class... Ms>
void append_messages(std::string& out, TypeList<Ms...>) {
  ((out += wireshark::message_lua<Ms>()), ...);
}

}  // namespace

std::string wireshark_lua() {
  // One chunk in its own block, so its locals do not meet the Clearpath part's.
  std::string out =
      "-- JAUS RA 3.x: generated from the message descriptions by `jausctl msg wireshark`; do not edit.\n"
      "do\nlocal MESSAGES = {\n";
  append_messages(out, CoreMessages{});
  append_messages(out, CommunicationsMessages{});
  append_messages(out, PlatformMessages{});
  append_messages(out, ManipulatorMessages{});
  append_messages(out, EnvironmentMessages{});
  append_messages(out, DiscoveryMessages{});
  append_messages(out, EventMessages{});
  out += "}\n";
  out += wireshark::jaus_lua_runtime();
  out += "end\n";
  return out;
}

}  // namespace jaus::msg
