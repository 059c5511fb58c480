#include "list_manager_elements.hpp"

#include <set>

namespace jaus::components_jss {
namespace {

Unexpected<ElementRejection> reject(ElementReject code, std::string why) {
  return unexpected(ElementRejection{code, std::move(why)});
}

std::string uid_text(std::uint16_t uid) { return "element " + std::to_string(uid); }

}  // namespace

void ListElements::unlink(Store& store, std::uint16_t uid) {
  const auto it = store.find(uid);
  if (it == store.end()) return;
  const ListElement gone = it->second;
  store.erase(it);
  for (auto& [other_uid, other] : store) {
    // A neighbour never ends up linking to itself (a circle of two becomes one element).
    if (other.next_uid == uid) other.next_uid = gone.next_uid == other_uid ? 0 : gone.next_uid;
    if (other.previous_uid == uid) other.previous_uid = gone.previous_uid == other_uid ? 0 : gone.previous_uid;
  }
}

Expected<void, ElementRejection> ListElements::insert(Store& store, const ListElement& element) {
  const std::uint16_t uid = element.uid;
  if (uid == kReservedUid || uid == kAllUids) return reject(ElementReject::invalid_element_id, "UID " + std::to_string(uid) + " is reserved");
  if (element.previous_uid == uid) return reject(ElementReject::invalid_previous, uid_text(uid) + " is its own previous");
  if (element.next_uid == uid) return reject(ElementReject::invalid_next, uid_text(uid) + " is its own next");
  // Setting an existing UID moves it: out of its old place first.
  unlink(store, uid);
  if (element.previous_uid != 0) {
    const auto previous = store.find(element.previous_uid);
    if (previous != store.end()) previous->second.next_uid = uid;
  }
  if (element.next_uid != 0) {
    const auto next = store.find(element.next_uid);
    // The tail pointing at the head closes a circle: the head stays the head.
    const bool closes_circle = element.previous_uid != 0 && next != store.end() && next->second.previous_uid == 0;
    if (next != store.end() && !closes_circle) next->second.previous_uid = uid;
  }
  store[uid] = element;
  return {};
}

Expected<void, ElementRejection> ListElements::check(const Store& store) {
  if (store.empty()) return {};
  std::uint16_t head = 0;
  std::size_t heads = 0;
  for (const auto& [uid, e] : store) {
    if (e.previous_uid == 0) {
      ++heads;
      head = uid;
      continue;
    }
    const auto previous = store.find(e.previous_uid);
    if (previous == store.end())
      return reject(ElementReject::invalid_previous,
                    uid_text(uid) + ": previous " + std::to_string(e.previous_uid) + " does not exist");
    if (previous->second.next_uid != uid)
      return reject(ElementReject::invalid_previous, uid_text(uid) + ": its previous " +
                                                         std::to_string(e.previous_uid) + " is followed by " +
                                                         std::to_string(previous->second.next_uid));
  }
  if (heads != 1)
    return reject(ElementReject::invalid_previous,
                  "the list would have " + std::to_string(heads) + " heads (previous 0), not exactly one");
  for (const auto& [uid, e] : store) {
    if (e.next_uid == 0) continue;
    const auto next = store.find(e.next_uid);
    if (next == store.end())
      return reject(ElementReject::invalid_next, uid_text(uid) + ": next " + std::to_string(e.next_uid) + " does not exist");
    if (next->second.previous_uid != uid && e.next_uid != head)
      return reject(ElementReject::invalid_next, uid_text(uid) + ": its next " + std::to_string(e.next_uid) +
                                                     " follows " + std::to_string(next->second.previous_uid));
  }
  // From the head every element once, ending at a tail or back at the head.
  std::set<std::uint16_t> seen;
  std::uint16_t at = head;
  while (at != 0 && seen.insert(at).second) {
    at = store.at(at).next_uid;
    if (at == head) break;
  }
  if (seen.size() != store.size())
    return reject(ElementReject::invalid_next, std::to_string(store.size() - seen.size()) +
                                                   " element(s) not reached from the head (orphans or a loop)");
  return {};
}

Expected<void, ElementRejection> ListElements::set(std::span<const ListElement> elements) {
  if (elements.empty()) return reject(ElementReject::unspecified, "no elements");
  // Links may name elements set later in the same request.
  std::set<std::uint16_t> requested;
  for (const auto& e : elements) requested.insert(e.uid);
  const auto known = [&](std::uint16_t uid) { return uid == 0 || elements_.contains(uid) || requested.contains(uid); };
  Store next = elements_;
  for (const auto& e : elements) {
    if (!known(e.previous_uid))
      return reject(ElementReject::invalid_previous,
                    uid_text(e.uid) + ": previous " + std::to_string(e.previous_uid) + " does not exist");
    if (!known(e.next_uid))
      return reject(ElementReject::invalid_next,
                    uid_text(e.uid) + ": next " + std::to_string(e.next_uid) + " does not exist");
    if (auto inserted = insert(next, e); !inserted) return inserted;
  }
  if (next.size() > capacity_)
    return reject(ElementReject::out_of_memory,
                  std::to_string(next.size()) + " elements, at most " + std::to_string(capacity_) + " are kept");
  if (auto valid = check(next); !valid) return valid;
  elements_ = std::move(next);
  return {};
}

Expected<void, ElementRejection> ListElements::remove(std::span<const std::uint16_t> uids) {
  if (uids.empty()) return reject(ElementReject::unspecified, "no elements");
  Store next = elements_;
  for (const std::uint16_t uid : uids) {
    if (uid == kAllUids) {
      elements_.clear();
      return {};
    }
    if (uid == kReservedUid) return reject(ElementReject::invalid_element_id, "UID 0 is reserved");
    if (!next.contains(uid)) return reject(ElementReject::not_found, uid_text(uid) + " does not exist");
    unlink(next, uid);
  }
  if (auto valid = check(next); !valid) return valid;
  elements_ = std::move(next);
  return {};
}

const ListElement* ListElements::find(std::uint16_t uid) const {
  const auto it = elements_.find(uid);
  return it == elements_.end() ? nullptr : &it->second;
}

std::vector<std::uint16_t> ListElements::in_order() const {
  std::vector<std::uint16_t> uids;
  for (const auto& [uid, e] : elements_) {
    if (e.previous_uid != 0) continue;
    for (const ListElement* element : from(uid)) uids.push_back(element->uid);
    break;
  }
  return uids;
}

std::vector<const ListElement*> ListElements::from(std::uint16_t start) const {
  std::vector<const ListElement*> route;
  const ListElement* at = find(start);
  // Bounded by the size: a valid list has no other loop, but the walk never trusts it.
  while (at != nullptr && route.size() < elements_.size()) {
    route.push_back(at);
    if (at->next_uid == 0 || at->next_uid == start) break;
    at = find(at->next_uid);
  }
  return route;
}

}  // namespace jaus::components_jss
