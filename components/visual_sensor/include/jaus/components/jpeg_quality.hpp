// A camera's JPEG quality on a slow link (issue 45): when the node's link is
// held to a rate (a field radio's send budget), a frame should take no more
// than a tenth of a second of it (3.2 KB at 256 kbit/s). A smaller frame
// crosses a radio's fades whole more often and comes more often, so the
// operator sees more pictures, not fewer sharper ones. After each JPEG frame
// the quality steps down while frames are over that size and back up while
// they are well under it; a link without a rate gets the default quality.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>

namespace jaus::components {

inline constexpr int kDefaultJpegQuality = 85;
inline constexpr int kLeastJpegQuality = 10;

// The largest frame, in bytes, for a link of `bits_per_second` (0: no limit).
inline std::size_t frame_bytes_for(std::uint64_t bits_per_second) {
  return bits_per_second == 0 ? SIZE_MAX : static_cast<std::size_t>(bits_per_second / 8 / 10);
}

// The next frame's quality after a JPEG frame of `frame_bytes` made at `quality`.
inline int next_jpeg_quality(int quality, std::size_t frame_bytes, std::uint64_t bits_per_second) {
  if (bits_per_second == 0) return kDefaultJpegQuality;
  const std::size_t most = frame_bytes_for(bits_per_second);
  if (frame_bytes > most) return std::max(kLeastJpegQuality, quality - std::max(5, quality / 4));
  if (frame_bytes * 10 < most * 6) return std::min(kDefaultJpegQuality, quality + 5);
  return quality;
}

}  // namespace jaus::components
