// Fuzz target: any bytes through the JAUS decoder, in both dialects. Whatever
// decodes must encode again; in the RA dialect it must also decode to the same
// JSON (the openjaus dialect's rounding moves negative values by a step).
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <span>

#include "jaus/messages/catalogue.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::span<const std::uint8_t> bytes(data, size);
  for (const auto dialect : {jaus::wire::Dialect::ra, jaus::wire::Dialect::openjaus}) {
    auto json = jaus::msg::message_to_json(bytes, dialect);
    if (!json) continue;
    auto encoded = jaus::msg::message_from_json(*json, dialect);
    if (!encoded) std::abort();  // what we decode we must be able to encode
    auto again = jaus::msg::message_to_json(*encoded, dialect);
    if (!again) std::abort();
    if (dialect == jaus::wire::Dialect::ra && (*again)["fields"] != (*json)["fields"]) std::abort();
  }
  return 0;
}
