// The List Manager's element store of one component (docs/jss.md, "List Manager and Local Waypoint List Driver"):
// elements with a UID and previous/next links, kept by the face since RA has
// no list manager. Sans-I/O: requests in, a confirmation or the Reject
// Element Request code out; a rejected request leaves the list unchanged.
//
// Rules (the JSS List Manager service's, docs/jss.md): UIDs 0 and 65535 are reserved; exactly one
// head (previous 0); at most one tail (next 0), none when the list is
// circular (the tail's next is the head, whose previous stays 0); every link
// names an element of the list or 0, no element links to itself, and walking
// from the head reaches every element once (no orphans). Setting an element
// inserts it between its previous and next (their links follow); setting an
// existing UID moves or rewrites it; deleting relinks its neighbours.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <span>
#include <string>
#include <vector>

#include "jaus/base/expected.hpp"

namespace jaus::components_jss {

// Reject Element Request response codes.
enum class ElementReject : std::uint8_t {
  invalid_element_id = 1,
  invalid_previous = 2,
  invalid_next = 3,
  unsupported_type = 4,
  not_found = 5,
  out_of_memory = 6,
  unspecified = 7,
};

struct ElementRejection {
  ElementReject code = ElementReject::unspecified;
  std::string why;  // for the log
};

struct ListElement {
  std::uint16_t uid = 0;
  std::uint16_t previous_uid = 0;  // 0: the head
  std::uint16_t next_uid = 0;      // 0: the tail
  std::uint8_t format = 0;         // 0: a JAUS message
  std::vector<std::uint8_t> data;  // the element's contents (a JSS message, ID first)
  bool operator==(const ListElement&) const = default;
};

class ListElements {
 public:
  static constexpr std::uint16_t kReservedUid = 0;
  static constexpr std::uint16_t kAllUids = 65535;

  explicit ListElements(std::size_t capacity) : capacity_(capacity) {}

  // Applies every element of one Set Element request, or none. The caller
  // has checked each element's format and data (code 4).
  Expected<void, ElementRejection> set(std::span<const ListElement> elements);
  // Deletes the UIDs of one Delete Element request (65535: all), or none.
  Expected<void, ElementRejection> remove(std::span<const std::uint16_t> uids);

  const ListElement* find(std::uint16_t uid) const;
  // UIDs from the head along the next links (a circular list once round).
  std::vector<std::uint16_t> in_order() const;
  // The elements to execute from `start`: along the next links to the tail,
  // or once round a circular list.
  std::vector<const ListElement*> from(std::uint16_t start) const;
  std::size_t size() const { return elements_.size(); }
  bool empty() const { return elements_.empty(); }
  std::size_t capacity() const { return capacity_; }

 private:
  using Store = std::map<std::uint16_t, ListElement>;
  static void unlink(Store& store, std::uint16_t uid);
  static Expected<void, ElementRejection> insert(Store& store, const ListElement& element);
  static Expected<void, ElementRejection> check(const Store& store);

  std::size_t capacity_;
  Store elements_;
};

}  // namespace jaus::components_jss
