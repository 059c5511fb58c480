// How a message too large for one packet is cut into pieces, in both
// dialects (RA large data sets, docs/wire-format.md; AS5669A large messages,
// docs/jss.md): consecutive pieces of at most `max_piece` bytes, the first
// flagged first, the last last, the others middle; a message that fits is one
// piece flagged single. Each dialect spells the roles in its own data flag.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>

namespace jaus {

// Sequence numbers are 16 bits; more pieces would reuse a number in one message.
inline constexpr std::size_t kMaxPiecesPerMessage = 65535;

enum class PieceRole : std::uint8_t {
  single,         // the whole message
  first,          // starts a large message (carries its message ID)
  middle,
  last,
  retransmitted,  // RA only: a piece sent again, to replace the one with its sequence number
  unknown,        // a data flag the dialect does not define
};

// Pieces a message of `size` bytes needs (1 for an empty message); max_piece > 0.
inline std::size_t pieces_needed(std::size_t size, std::size_t max_piece) {
  return size <= max_piece ? 1 : (size + max_piece - 1) / max_piece;
}

struct PieceSlice {
  PieceRole role = PieceRole::single;
  std::size_t offset = 0;
  std::size_t size = 0;
};

// Piece `index` (< count) of a message of `size` bytes cut into `count` pieces of `max_piece`.
inline PieceSlice piece_of(std::size_t size, std::size_t max_piece, std::size_t count, std::size_t index) {
  const std::size_t offset = std::min(index * max_piece, size);
  const PieceSlice slice{PieceRole::single, offset, std::min(max_piece, size - offset)};
  if (count == 1) return slice;
  return {index == 0 ? PieceRole::first : index + 1 == count ? PieceRole::last : PieceRole::middle, slice.offset,
          slice.size};
}

}  // namespace jaus
