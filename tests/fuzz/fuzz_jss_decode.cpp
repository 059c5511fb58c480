// Fuzz target: any bytes as an AS5669A datagram and as JSS contents, through
// the JSS catalogue, and the datagram's packets through the large-message
// reassembler. Whatever decodes must encode again and decode to the same
// JSON; nothing may crash, over-read or grow without bound.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <span>

#include "jaus/jss/catalogue.hpp"
#include "jaus/jss/large_message.hpp"

namespace {

void check_contents(std::span<const std::uint8_t> contents) {
  auto json = jaus::jss::contents_to_json(contents);
  if (!json) return;
  auto encoded = jaus::jss::contents_from_json(*json);
  if (!encoded) std::abort();  // what we decode we must be able to encode
  auto again = jaus::jss::contents_to_json(*encoded);
  if (!again || *again != *json) std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::span<const std::uint8_t> bytes(data, size);
  check_contents(bytes);
  auto packets = jaus::jss::decode_judp_datagram(bytes);
  if (!packets) return 0;
  jaus::jss::JssLargeMessageAssembler assembler(jaus::AssemblyLimits{.max_message_size = 4096, .max_sets = 2});
  for (const auto& packet : *packets) {
    auto assembled = assembler.feed(packet.header, packet.contents, jaus::rt::TimePoint{});
    if (assembled.message) check_contents(assembled.message->payload);
    if (assembler.buffered_bytes() > 2 * 4096) std::abort();
  }
  if (auto json = jaus::jss::datagram_to_json(bytes); json) {
    for (const auto& packet : (*json)["packets"])
      if (!jaus::jss::datagram_from_json(packet)) std::abort();
  }
  return 0;
}
