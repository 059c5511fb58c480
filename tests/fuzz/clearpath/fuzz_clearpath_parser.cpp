// libFuzzer target: arbitrary bytes, in arbitrary chunks, through the frame
// parser and the message decoder. Nothing may crash, leak or misbehave.
#include <cstddef>
#include <cstdint>
#include <span>

#include "jaus/clearpath/codec.hpp"
#include "jaus/clearpath/frame_parser.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  namespace cp = jaus::clearpath;
  if (size == 0) return 0;
  // The first byte picks the chunk size, so splits are fuzzed too.
  const std::size_t chunk = 1 + data[0] % 64;
  const std::span<const std::uint8_t> bytes(data + 1, size - 1);
  cp::FrameParser parser;
  for (std::size_t at = 0; at < bytes.size(); at += chunk) {
    parser.feed(bytes.subspan(at, std::min(chunk, bytes.size() - at)));
    while (auto event = parser.poll()) {
      const auto* frame = std::get_if<cp::Frame>(&*event);
      if (frame == nullptr) continue;
      for (const auto direction : {cp::Direction::to_platform, cp::Direction::from_platform}) {
        const auto decoded = cp::decode(*frame, direction);
        if (!decoded) continue;
        // Whatever decodes re-encodes to the same frame.
        const auto again = cp::encode(*decoded);
        if (!again || cp::decode_frame(*again)->payload.size() != frame->payload.size()) __builtin_trap();
      }
    }
  }
  return 0;
}
