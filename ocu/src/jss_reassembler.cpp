#include "jss_reassembler.hpp"

#include <algorithm>

namespace jaus::ocu::detail {

void JssReassembler::expire(rt::TimePoint now) {
  for (auto it = partial_.begin(); it != partial_.end();) {
    if (now - it->second.last_heard >= timeout_) {
      it = partial_.erase(it);
      ++dropped_;
    } else {
      ++it;
    }
  }
}

std::optional<JssReassembler::Whole> JssReassembler::add(const jss::JudpPacket& packet, rt::TimePoint now) {
  expire(now);
  const jss::JssId source = packet.header.source;
  if (packet.header.data_flag == jss::JudpDataFlag::first) {
    if (partial_.erase(source) > 0) ++dropped_;  // a new message before the last one ended
    if (partial_.size() >= max_sources_ && !partial_.empty()) {
      const auto oldest = std::min_element(partial_.begin(), partial_.end(), [](const auto& a, const auto& b) {
        return a.second.last_heard < b.second.last_heard;
      });
      partial_.erase(oldest);
      ++dropped_;
    }
    if (packet.contents.size() > max_bytes_) {
      ++dropped_;
      return std::nullopt;
    }
    Partial& p = partial_[source];
    p.whole.header = packet.header;
    p.whole.header.data_flag = jss::JudpDataFlag::single;
    p.whole.contents.assign(packet.contents.begin(), packet.contents.end());
    p.next_sequence = static_cast<std::uint16_t>(packet.header.sequence + 1);
    p.last_heard = now;
    return std::nullopt;
  }
  const auto it = partial_.find(source);
  if (it == partial_.end()) {
    ++dropped_;  // a middle or last packet without its first
    return std::nullopt;
  }
  Partial& p = it->second;
  if (packet.header.sequence != p.next_sequence || p.whole.contents.size() + packet.contents.size() > max_bytes_) {
    partial_.erase(it);
    ++dropped_;
    return std::nullopt;
  }
  p.whole.contents.insert(p.whole.contents.end(), packet.contents.begin(), packet.contents.end());
  p.next_sequence = static_cast<std::uint16_t>(p.next_sequence + 1);
  p.last_heard = now;
  if (packet.header.data_flag != jss::JudpDataFlag::last) return std::nullopt;
  Whole whole = std::move(p.whole);
  partial_.erase(it);
  return whole;
}

}  // namespace jaus::ocu::detail
