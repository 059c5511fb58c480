#include "face_transport.hpp"

#include <algorithm>

namespace jaus::jss_face {

std::uint16_t SequenceNumbers::take(const jss::JssId& to, std::uint16_t count) {
  auto it = next_.find(to);
  if (it == next_.end()) {
    if (next_.size() >= max_) {
      const auto least = std::min_element(next_.begin(), next_.end(),
                                          [](const auto& a, const auto& b) { return a.second.used < b.second.used; });
      next_.erase(least);
    }
    it = next_.emplace(to, Entry{}).first;
  }
  const std::uint16_t first = it->second.next;
  it->second.next = static_cast<std::uint16_t>(first + count);
  it->second.used = ++uses_;
  return first;
}

void JssDuplicateFilter::expire(rt::TimePoint now) {
  while (!order_.empty() && (now - order_.front().first >= window_ || order_.size() > max_)) {
    const auto [at, key] = order_.front();
    order_.pop_front();
    if (auto it = seen_.find(key); it != seen_.end() && it->second == at) seen_.erase(it);
  }
}

bool JssDuplicateFilter::seen_before(const jss::JssId& source, std::uint16_t sequence, rt::TimePoint now) {
  expire(now);
  const Key key{source.packed(), sequence};
  if (auto it = seen_.find(key); it != seen_.end() && now - it->second < window_) return true;
  seen_[key] = now;
  order_.emplace_back(now, key);
  if (order_.size() > max_) expire(now);
  return false;
}

}  // namespace jaus::jss_face
