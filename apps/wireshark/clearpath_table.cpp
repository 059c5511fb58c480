// The Clearpath half's tables: every message type of the catalogue, and the
// ACK, walked by clearpath_table.hpp.
#include <cstdio>

#include "clearpath_table.hpp"
#include "jaus/clearpath/any_message.hpp"
#include "jaus/clearpath/frame.hpp"
#include "jaus/clearpath/message_kind.hpp"
#include "wireshark_plugin.hpp"

namespace jaus::wireshark {

namespace {

using clearpath_table::LuaFieldWriter;

template <class M>
std::string body_for_size(std::size_t payload_size) {
  M message{};
  if constexpr (requires { M::prepare_decode(message, payload_size); }) M::prepare_decode(message, payload_size);
  LuaFieldWriter writer;
  M::describe(message, writer);
  return writer.out + "}";
}

// [0x0204]={name="set_velocity",kind="command",body={...}}; a message whose
// layout depends on its payload size (prepare_decode) also lists the other
// layouts by size.
template <class M>
std::string message_lua() {
  char type[8];
  std::snprintf(type, sizeof type, "0x%04X", static_cast<unsigned>(M::kType));
  const std::string body = body_for_size<M>(0);
  std::string out = std::string("[") + type + "]={name=" + lua_string(M::kName) +
                    ",kind=" + lua_string(clearpath::to_string(clearpath::kind_of(M::kType))) + ",body=" + body;
  if constexpr (requires(M m) { M::prepare_decode(m, std::size_t{0}); }) {
    out += ",by_size={";
    for (std::size_t size = 1; size <= clearpath::kMaxPayload; ++size) {
      const std::string other = body_for_size<M>(size);
      if (other != body) out += "[" + std::to_string(size) + "]=" + other + ",";
    }
    out += "}";
  }
  return out + "},\n";
}

template <class... Ms>
std::string messages_lua(clearpath::TypeList<clearpath::Ack, Ms...>) {
  return (std::string() + ... + message_lua<Ms>());
}

}  // namespace

std::string clearpath_tables_lua() {
  return "local CP_MESSAGES = {\n" + messages_lua(clearpath::MessageTypes{}) +
         "}\nlocal CP_ACK = " + LuaFieldWriter::body_of<clearpath::Ack>() + "\n";
}

}  // namespace jaus::wireshark
