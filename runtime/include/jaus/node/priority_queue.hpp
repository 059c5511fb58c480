// A bounded queue of messages waiting to be sent or dispatched, ordered by
// header priority: 15 first down to 0, first in first out within a priority.
// So safety-critical messages (12-15) always leave before anything else that
// is queued, whatever arrived earlier. Strict priority may starve low
// priorities under sustained high-priority load; that is the RA's intent.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include "jaus/core/header.hpp"

namespace jaus::node {

inline constexpr std::uint8_t kPriorityLevels = 16;

inline bool is_safety_critical(std::uint8_t priority) { return priority >= priority::kSafetyCritical; }

// First in, first out over a ring that grows and never shrinks: once it has
// grown to the traffic's bursts, pushing and popping allocate nothing (a
// std::deque frees and allocates a block every few messages).
template <class T>
class Fifo {
 public:
  bool empty() const { return size_ == 0; }
  T& front() { return slots_[head_]; }
  void push_back(T item) {
    if (size_ == slots_.size()) grow();
    slots_[(head_ + size_) % slots_.size()] = std::move(item);
    ++size_;
  }
  // What stays in the slot is a moved-from T (an empty vector holds nothing).
  void pop_front() {
    head_ = (head_ + 1) % slots_.size();
    --size_;
  }
  void clear() {
    slots_.assign(slots_.size(), T{});
    head_ = size_ = 0;
  }

 private:
  void grow() {
    std::vector<T> bigger(slots_.empty() ? 8 : slots_.size() * 2);
    for (std::size_t i = 0; i < size_; ++i) bigger[i] = std::move(slots_[(head_ + i) % slots_.size()]);
    slots_.swap(bigger);
    head_ = 0;
  }

  std::vector<T> slots_;
  std::size_t head_ = 0;
  std::size_t size_ = 0;
};

template <class T>
class PriorityQueue {
 public:
  struct Options {
    std::size_t capacity = 1024;  // messages held at once (at least 1)
  };

  // What push() did. `dropped` holds the message that did not stay in the
  // queue (the evicted older one, or the new one itself when rejected), so
  // the caller can still answer it, e.g. with a NAK when it requested an ACK.
  struct PushResult {
    bool accepted = false;
    std::optional<T> dropped;
    std::uint8_t dropped_priority = 0;
  };

  struct Counters {
    std::uint64_t dropped = 0;                  // every message that was evicted or rejected
    std::uint64_t dropped_safety_critical = 0;  // of those, priorities 12-15
  };

  PriorityQueue() : PriorityQueue(Options{}) {}
  explicit PriorityQueue(Options options) : capacity_(options.capacity == 0 ? 1 : options.capacity) {}

  // Queues `item` at `priority` (values over 15 are taken as 15). When full,
  // the oldest message of the lowest priority present makes room, provided
  // its priority is not above the new one's; otherwise the new message is the
  // one dropped. A message is therefore never dropped in favour of a lower
  // one; between equals, the newer wins (fresher commands and reports).
  PushResult push(std::uint8_t priority, T item) {
    const std::uint8_t level = priority < kPriorityLevels ? priority : kPriorityLevels - 1;
    PushResult result;
    if (size_ >= capacity_) {
      const std::uint8_t lowest = lowest_occupied_level();
      if (lowest > level) {
        result.dropped = std::move(item);
        result.dropped_priority = level;
        count_drop(level);
        return result;
      }
      auto& victims = levels_[lowest];
      result.dropped = std::move(victims.front());
      result.dropped_priority = lowest;
      victims.pop_front();
      --size_;
      count_drop(lowest);
    }
    levels_[level].push_back(std::move(item));
    ++size_;
    result.accepted = true;
    return result;
  }

  // Removes and returns the next message: highest priority, oldest first.
  std::optional<T> pop() {
    for (int level = kPriorityLevels - 1; level >= 0; --level) {
      auto& queue = levels_[static_cast<std::size_t>(level)];
      if (queue.empty()) continue;
      std::optional<T> item(std::move(queue.front()));
      queue.pop_front();
      --size_;
      return item;
    }
    return std::nullopt;
  }

  // Priority of the message pop() would return.
  std::optional<std::uint8_t> next_priority() const {
    for (int level = kPriorityLevels - 1; level >= 0; --level)
      if (!levels_[static_cast<std::size_t>(level)].empty()) return static_cast<std::uint8_t>(level);
    return std::nullopt;
  }

  std::size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  std::size_t capacity() const { return capacity_; }
  const Counters& counters() const { return counters_; }

  void clear() {
    for (auto& queue : levels_) queue.clear();
    size_ = 0;
  }

 private:
  // Only called when the queue is full, so some level is occupied.
  std::uint8_t lowest_occupied_level() const {
    for (std::uint8_t level = 0; level < kPriorityLevels; ++level)
      if (!levels_[level].empty()) return level;
    return kPriorityLevels - 1;
  }
  void count_drop(std::uint8_t level) {
    ++counters_.dropped;
    if (is_safety_critical(level)) ++counters_.dropped_safety_critical;
  }

  std::size_t capacity_;
  std::size_t size_ = 0;
  std::array<Fifo<T>, kPriorityLevels> levels_;
  Counters counters_;
};

}  // namespace jaus::node
