// Large JSS messages: split (docs/jss.md, "The bytes on the wire"); reassembled by the one assembler.
#include "jaus/jss/large_message.hpp"

#include <algorithm>
#include <string>

#include "jaus/core/large_message_pieces.hpp"

namespace jaus::jss {
namespace {

JudpDataFlag judp_flag_of(PieceRole role) {
  switch (role) {
    case PieceRole::first: return JudpDataFlag::first;
    case PieceRole::middle: return JudpDataFlag::middle;
    case PieceRole::last: return JudpDataFlag::last;
    default: return JudpDataFlag::single;
  }
}

}  // namespace

Expected<std::vector<ContentsPiece>> split_contents(std::span<const std::uint8_t> contents, std::size_t max_contents) {
  if (max_contents < 2)
    return unexpected(make_error(ErrorCode::invalid_argument,
                                 "at most " + std::to_string(max_contents) + " contents bytes per packet: the "
                                 "first packet must carry the 2-byte message ID"));
  const std::size_t count = pieces_needed(contents.size(), max_contents);
  std::vector<ContentsPiece> pieces;
  pieces.reserve(count);
  for (std::size_t i = 0; i < count; ++i) {
    const PieceSlice slice = piece_of(contents.size(), max_contents, count, i);
    pieces.push_back({judp_flag_of(slice.role), contents.subspan(slice.offset, slice.size)});
  }
  return pieces;
}

Expected<std::vector<std::vector<std::uint8_t>>> make_judp_datagrams(const JudpHeader& header,
                                                                     std::span<const std::uint8_t> contents,
                                                                     std::size_t max_contents) {
  if (contents.size() > max_contents && (header.destination.is_broadcast() || header.broadcast != JudpBroadcast::none))
    return unexpected(Error{ErrorCode::payload_too_large, 0, "contents",
                            std::to_string(contents.size()) + " bytes to a broadcast: broadcasts are never split (at most " +
                                std::to_string(max_contents) + ")"});
  auto pieces = split_contents(contents, max_contents);
  if (!pieces) return unexpected(pieces.error());
  std::vector<std::vector<std::uint8_t>> datagrams;
  datagrams.reserve(pieces->size());
  JudpHeader h = header;
  for (const auto& piece : *pieces) {
    h.data_flag = piece.data_flag;
    std::vector<std::uint8_t> datagram(1 + kMinDataSize + piece.bytes.size());
    auto size = encode_judp_datagram(h, piece.bytes, datagram);
    if (!size) return unexpected(size.error());
    datagrams.push_back(std::move(datagram));
    h.sequence = static_cast<std::uint16_t>(h.sequence + 1);
  }
  return datagrams;
}

}  // namespace jaus::jss
