// Large JSS messages: split and reassembled (docs/jss.md, "The bytes on the wire").
#include "jaus/jss/large_message.hpp"

#include <algorithm>
#include <string>

namespace jaus::jss {
namespace {

Unexpected<Error> dropped(ErrorCode code, std::string why) { return unexpected(Error{code, 0, "data_flag", std::move(why)}); }

}  // namespace

Expected<std::vector<ContentsPiece>> split_contents(std::span<const std::uint8_t> contents, std::size_t max_contents) {
  if (max_contents < 2)
    return unexpected(make_error(ErrorCode::invalid_argument,
                                 "at most " + std::to_string(max_contents) + " contents bytes per packet: the "
                                 "first packet must carry the 2-byte message ID"));
  std::vector<ContentsPiece> pieces;
  if (contents.size() <= max_contents) {
    pieces.push_back({JudpDataFlag::single, contents});
    return pieces;
  }
  for (std::size_t at = 0; at < contents.size(); at += max_contents) {
    const std::size_t n = std::min(max_contents, contents.size() - at);
    const JudpDataFlag flag = at == 0                          ? JudpDataFlag::first
                              : at + n == contents.size()      ? JudpDataFlag::last
                                                               : JudpDataFlag::middle;
    pieces.push_back({flag, contents.subspan(at, n)});
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

void LargeMessageReassembler::drop(std::map<Key, Set>::iterator it) {
  total_bytes_ -= it->second.contents.size();
  sets_.erase(it);
}

void LargeMessageReassembler::expire(rt::TimePoint now) {
  for (auto it = sets_.begin(); it != sets_.end();) {
    auto next = std::next(it);
    if (now - it->second.last_heard > limits_.timeout) {
      ++counters_.timed_out;
      drop(it);
    }
    it = next;
  }
}

Expected<std::optional<WholeMessage>> LargeMessageReassembler::add(const JudpPacket& packet, rt::TimePoint now) {
  expire(now);
  const JudpHeader& h = packet.header;
  if (h.data_flag == JudpDataFlag::single) {
    ++counters_.completed;
    return std::optional<WholeMessage>(WholeMessage{h, {packet.contents.begin(), packet.contents.end()}});
  }

  if (h.data_flag == JudpDataFlag::first) {
    if (packet.contents.size() < 2) {
      ++counters_.bad_first;
      return dropped(ErrorCode::malformed, "a first packet of " + std::to_string(packet.contents.size()) +
                                               " bytes cannot carry the message ID");
    }
    if (packet.contents.size() > limits_.max_set_bytes) {
      ++counters_.too_large;
      return dropped(ErrorCode::payload_too_large, "first packet above " + std::to_string(limits_.max_set_bytes) + " bytes");
    }
    // The source's own oldest set goes first when it has too many.
    std::size_t own = 0;
    auto oldest = sets_.end();
    for (auto it = sets_.begin(); it != sets_.end(); ++it) {
      if (it->first.source != h.source) continue;
      ++own;
      if (oldest == sets_.end() || it->second.started < oldest->second.started) oldest = it;
    }
    if (own >= limits_.max_sets_per_source && oldest != sets_.end()) {
      ++counters_.superseded;
      drop(oldest);
    }
    if (sets_.size() >= limits_.max_sets) {
      ++counters_.refused;
      return dropped(ErrorCode::refused, std::to_string(sets_.size()) + " large messages in progress (the bound)");
    }
    if (total_bytes_ + packet.contents.size() > limits_.max_total_bytes) {
      ++counters_.too_large;
      return dropped(ErrorCode::payload_too_large,
                     "large messages in progress hold " + std::to_string(total_bytes_) + " bytes (the bound is " +
                         std::to_string(limits_.max_total_bytes) + ")");
    }
    const Key key{h.source, h.destination, h.sequence};
    if (auto existing = sets_.find(key); existing != sets_.end()) drop(existing);  // a resent first packet restarts
    Set set;
    set.header = h;
    set.header.data_flag = JudpDataFlag::single;
    set.contents.assign(packet.contents.begin(), packet.contents.end());
    set.next_sequence = static_cast<std::uint16_t>(h.sequence + 1);
    set.last_heard = now;
    set.started = next_started_++;
    total_bytes_ += set.contents.size();
    sets_.emplace(key, std::move(set));
    return std::optional<WholeMessage>{};
  }

  // Middle or last: the set of this source and destination expecting this sequence number.
  auto it = std::find_if(sets_.begin(), sets_.end(), [&](const auto& entry) {
    return entry.first.source == h.source && entry.first.destination == h.destination &&
           entry.second.next_sequence == h.sequence;
  });
  if (it == sets_.end()) {
    ++counters_.stray;
    return dropped(ErrorCode::malformed, std::string(to_string(h.data_flag)) + " packet, sequence " +
                                             std::to_string(h.sequence) + ": no large message from " +
                                             h.source.to_string() + " expects it");
  }
  Set& set = it->second;
  if (set.contents.size() + packet.contents.size() > limits_.max_set_bytes ||
      total_bytes_ + packet.contents.size() > limits_.max_total_bytes) {
    ++counters_.too_large;
    drop(it);
    return dropped(ErrorCode::payload_too_large, "a large message from " + h.source.to_string() + " above " +
                                                     std::to_string(limits_.max_set_bytes) + " bytes (or the total bound)");
  }
  set.contents.insert(set.contents.end(), packet.contents.begin(), packet.contents.end());
  total_bytes_ += packet.contents.size();
  set.next_sequence = static_cast<std::uint16_t>(h.sequence + 1);
  set.last_heard = now;
  if (h.data_flag == JudpDataFlag::middle) return std::optional<WholeMessage>{};
  WholeMessage whole{set.header, std::move(set.contents)};
  set.contents.clear();  // moved from: nothing left to count
  total_bytes_ -= whole.contents.size();
  sets_.erase(it);
  ++counters_.completed;
  return std::optional<WholeMessage>(std::move(whole));
}

}  // namespace jaus::jss
