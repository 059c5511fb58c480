#include "jaus/clearpath/wireshark_lua.hpp"

#include <cstdio>

#include "jaus/clearpath/any_message.hpp"
#include "jaus/clearpath/frame.hpp"
#include "jaus/clearpath/message_kind.hpp"
#include "wireshark_fields.hpp"
#include "wireshark_runtime.hpp"

namespace jaus::clearpath {

namespace {

using wireshark::lua_string;
using wireshark::LuaFieldWriter;

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
                    ",kind=" + lua_string(to_string(kind_of(M::kType))) + ",body=" + body;
  if constexpr (requires(M m) { M::prepare_decode(m, std::size_t{0}); }) {
    out += ",by_size={";
    for (std::size_t size = 1; size <= kMaxPayload; ++size) {
      const std::string other = body_for_size<M>(size);
      if (other != body) out += "[" + std::to_string(size) + "]=" + other + ",";
    }
    out += "}";
  }
  return out + "},\n";
}

template <class... Ms>
std::string messages_lua(TypeList<Ack, Ms...>) {
  return (std::string() + ... + message_lua<Ms>());
}

}  // namespace

std::string wireshark_lua() {
  std::string out =
      "-- Clearpath over UDP: generated from the message descriptions by `jausctl msg wireshark`; do not edit.\n"
      "do\nlocal CP_MESSAGES = {\n";
  out += messages_lua(MessageTypes{});
  out += "}\nlocal CP_ACK = " + LuaFieldWriter::body_of<Ack>() + "\n";
  out += wireshark::clearpath_lua_runtime();
  out += "end\n";
  return out;
}

}  // namespace jaus::clearpath
