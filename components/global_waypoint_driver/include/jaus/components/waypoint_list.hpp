// The list a waypoint driver holds (components 45 and 46; Part 3's numbering
// from zero), sans I/O: which Set ... Waypoint is taken and what it does.
//   number 0          a new list (the old one dropped);
//   number == count   appended;
//   number < count    replaces that element;
//   number > count    refused (a gap), as is anything beyond `capacity`.
// Each element is kept exactly as received (its presence vector included),
// so a Report echoes what was set.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "jaus/base/expected.hpp"

namespace jaus::components {

enum class WaypointLoad : std::uint8_t { new_list, appended, replaced };

template <class Body>
class WaypointList {
 public:
  explicit WaypointList(std::size_t capacity) : capacity_(capacity) {}

  Expected<WaypointLoad> load(const Body& waypoint) {
    const std::size_t number = waypoint.waypoint_number;
    if (number == 0) {
      elements_.assign(1, waypoint);
      return WaypointLoad::new_list;
    }
    if (number > elements_.size())
      return unexpected(make_error(ErrorCode::invalid_argument,
                                   "waypoint " + std::to_string(number) + " beyond the count " +
                                       std::to_string(elements_.size()) + " (numbering is from 0, without gaps)"));
    if (number < elements_.size()) {
      elements_[number] = waypoint;
      return WaypointLoad::replaced;
    }
    if (elements_.size() >= capacity_)
      return unexpected(make_error(ErrorCode::invalid_argument,
                                   "waypoint " + std::to_string(number) + " beyond max_waypoints " +
                                       std::to_string(capacity_)));
    elements_.push_back(waypoint);
    return WaypointLoad::appended;
  }

  // The element `number` as set; null beyond the count.
  const Body* find(std::size_t number) const { return number < elements_.size() ? &elements_[number] : nullptr; }
  std::size_t size() const { return elements_.size(); }
  bool empty() const { return elements_.empty(); }
  const std::vector<Body>& elements() const { return elements_; }
  void clear() { elements_.clear(); }

 private:
  std::size_t capacity_;
  std::vector<Body> elements_;
};

}  // namespace jaus::components
