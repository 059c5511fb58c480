// The list of path segments a path segment driver holds (components 47 and
// 48), with Part 3's numbering: segments are numbered from zero, and "the
// path segment number ... must be incremented by one for each additional
// path segment". Our rules where Part 3 is silent:
//   - number 0 starts a new list (the old one is dropped);
//   - number == count appends, number < count replaces that segment;
//   - number > count (a gap) is refused, and so is a segment beyond the
//     list's capacity (max_path_segments): nothing is stored.
// Each segment is kept exactly as received (presence vector and optional
// fields included), so a report echoes it. Body: GlobalPathSegmentBody or
// LocalPathSegmentBody.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "jaus/base/error.hpp"
#include "jaus/base/expected.hpp"

namespace jaus::components {

// What a stored segment did to the list.
enum class ListChange : std::uint8_t { new_list, appended, replaced };

template <class Body>
class PathSegmentList {
 public:
  explicit PathSegmentList(std::size_t capacity) : capacity_(capacity) {}

  // Stores `segment` by its number, or says why not (the list unchanged).
  Expected<ListChange> set(const Body& segment) {
    const std::size_t number = segment.path_segment_number;
    if (number == 0) {
      segments_.assign(1, segment);
      return ListChange::new_list;
    }
    if (number < segments_.size()) {
      segments_[number] = segment;
      return ListChange::replaced;
    }
    if (number > segments_.size())
      return unexpected(make_error(ErrorCode::invalid_argument,
                                   "path segment " + std::to_string(number) + " leaves a gap (" +
                                       std::to_string(segments_.size()) + " loaded: the next is number " +
                                       std::to_string(segments_.size()) + ")"));
    if (segments_.size() >= capacity_)
      return unexpected(make_error(ErrorCode::invalid_argument, "path segment " + std::to_string(number) +
                                                                    " is beyond the list's capacity (max_path_segments " +
                                                                    std::to_string(capacity_) + ")"));
    segments_.push_back(segment);
    return ListChange::appended;
  }

  // Segment `number` as it was set; none beyond the count.
  const Body* at(std::size_t number) const { return number < segments_.size() ? &segments_[number] : nullptr; }
  std::size_t count() const { return segments_.size(); }
  const std::vector<Body>& segments() const { return segments_; }
  void clear() { segments_.clear(); }

 private:
  std::size_t capacity_;
  std::vector<Body> segments_;
};

}  // namespace jaus::components
