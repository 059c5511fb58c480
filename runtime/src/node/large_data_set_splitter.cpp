#include "jaus/node/large_data_set_splitter.hpp"

#include <algorithm>
#include <cstring>
#include <string>

#include "jaus/core/large_message_pieces.hpp"

namespace jaus::node {
namespace {

DataFlag ra_data_flag_of(PieceRole role) {
  switch (role) {
    case PieceRole::first: return DataFlag::first;
    case PieceRole::middle: return DataFlag::middle;
    case PieceRole::last: return DataFlag::last;
    default: return DataFlag::single;
  }
}


std::size_t clamped_piece(std::size_t piece_size) { return std::clamp<std::size_t>(piece_size, 1, kMaxPayloadSize); }

}  // namespace

std::size_t LargeDataSetSplitter::packets_needed(std::size_t payload_size, std::size_t piece_size) {
  return pieces_needed(payload_size, clamped_piece(piece_size));
}

Expected<LargeDataSetSplitter, Error> LargeDataSetSplitter::create(const Header& header,
                                                                   std::span<const std::uint8_t> payload,
                                                                   std::size_t piece_size) {
  piece_size = clamped_piece(piece_size);
  const std::size_t count = packets_needed(payload.size(), piece_size);
  if (count > kMaxPacketsPerSet)
    return unexpected(Error{ErrorCode::payload_too_large, 0, "payload",
                            std::to_string(payload.size()) + " bytes need " + std::to_string(count) +
                                " packets, at most " + std::to_string(kMaxPacketsPerSet)});
  LargeDataSetSplitter splitter(header, payload, count, piece_size);
  // The shared fields are the same in every packet: checking the first checks all.
  if (auto checked = encode_header(splitter.packet(0).header); !checked) return unexpected(checked.error());
  return splitter;
}

PacketView LargeDataSetSplitter::packet(std::size_t index) const {
  PacketView view{header_, {}};
  if (index >= count_) return view;  // out of range: an empty view rather than a read past the end
  const PieceSlice slice = piece_of(payload_.size(), piece_size_, count_, index);
  view.payload = payload_.subspan(slice.offset, slice.size);
  Header& h = view.header;
  h.data_size = static_cast<std::uint16_t>(view.payload.size());
  h.sequence = static_cast<std::uint16_t>(header_.sequence + index);  // wraps after 65535
  h.data_flag = ra_data_flag_of(slice.role);
  return view;
}

std::vector<PacketView> LargeDataSetSplitter::packets() const {
  std::vector<PacketView> out;
  out.reserve(count_);
  for (std::size_t i = 0; i < count_; ++i) out.push_back(packet(i));
  return out;
}

Expected<std::size_t, Error> LargeDataSetSplitter::encode(std::size_t index, std::span<std::uint8_t> out) const {
  if (index >= count_)
    return unexpected(Error{ErrorCode::bad_value, 0, "packet index",
                            std::to_string(index) + " of " + std::to_string(count_)});
  const PacketView view = packet(index);
  const std::size_t size = kHeaderSize + view.payload.size();
  if (out.size() < size)
    return unexpected(Error{ErrorCode::output_too_small, 0, {}, "needs " + std::to_string(size) + " bytes"});
  encode_header_unchecked(view.header, out.first<kHeaderSize>());
  if (!view.payload.empty()) std::memcpy(out.data() + kHeaderSize, view.payload.data(), view.payload.size());
  return size;
}

}  // namespace jaus::node
