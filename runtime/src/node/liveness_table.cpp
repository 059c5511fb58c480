#include "jaus/node/liveness_table.hpp"

#include <algorithm>
#include <array>

namespace jaus::node {

Address subsystem_of(const Address& address) { return Address{address.subsystem, 0, 0, 0}; }
Address node_of(const Address& address) { return Address{address.subsystem, address.node, 0, 0}; }

namespace {
bool is_under(const Address& key, const LivenessEntry& ancestor) {
  switch (ancestor.level) {
    case LivenessLevel::subsystem: return key.subsystem == ancestor.address.subsystem;
    case LivenessLevel::node: return node_of(key) == ancestor.address;
    case LivenessLevel::component: return false;
  }
  return false;
}
}  // namespace

HeardResult LivenessTable::heard(const Address& source, rt::TimePoint now) {
  HeardResult result;
  if (!source.is_valid() || source.is_broadcast()) {
    ++counters_.invalid_sources;
    return result;
  }
  const std::array<std::pair<LivenessLevel, Address>, 3> levels{{
      {LivenessLevel::subsystem, subsystem_of(source)},
      {LivenessLevel::node, node_of(source)},
      {LivenessLevel::component, source},
  }};
  const auto newcomers = static_cast<std::size_t>(std::count_if(
      levels.begin(), levels.end(), [&](const auto& level) { return !entries_.contains(level.second); }));
  const bool room = entries_.size() + newcomers <= options_.max_entries;
  if (!room) ++counters_.rejected_full;
  for (const auto& [level, key] : levels) {
    if (const auto it = entries_.find(key); it != entries_.end()) {
      it->second.last_heard = now;  // known peers are refreshed even when newcomers do not fit
    } else if (room) {
      entries_.emplace(key, LivenessEntry{level, key, now, now});
      (level == LivenessLevel::subsystem ? result.new_subsystem
       : level == LivenessLevel::node    ? result.new_node
                                         : result.new_component) = true;
    }
  }
  result.recorded = room;
  return result;
}

std::vector<LivenessEntry> LivenessTable::expire(rt::TimePoint now) {
  std::vector<LivenessEntry> silent_ancestors;
  for (const auto& [key, entry] : entries_)
    if (entry.level != LivenessLevel::component && now >= entry.last_heard + timeout_of(entry.level))
      silent_ancestors.push_back(entry);

  std::vector<LivenessEntry> expired;
  for (auto it = entries_.begin(); it != entries_.end();) {
    const LivenessEntry& entry = it->second;
    const bool silent = now >= entry.last_heard + timeout_of(entry.level);
    const bool orphaned = std::any_of(silent_ancestors.begin(), silent_ancestors.end(),
                                      [&](const LivenessEntry& a) { return is_under(it->first, a); });
    if (!silent && !orphaned) {
      ++it;
      continue;
    }
    expired.push_back(entry);
    it = entries_.erase(it);
  }
  // Components first, then nodes, then subsystems: callers tear down from the bottom.
  std::stable_sort(expired.begin(), expired.end(), [](const LivenessEntry& a, const LivenessEntry& b) {
    return static_cast<int>(a.level) > static_cast<int>(b.level);
  });
  counters_.expired += expired.size();
  return expired;
}

std::optional<rt::TimePoint> LivenessTable::next_deadline() const {
  std::optional<rt::TimePoint> earliest;
  for (const auto& [key, entry] : entries_) {
    const auto deadline = entry.last_heard + timeout_of(entry.level);
    if (!earliest || deadline < *earliest) earliest = deadline;
  }
  return earliest;
}

std::optional<LivenessEntry> LivenessTable::find(const Address& key) const {
  const auto it = entries_.find(key);
  if (it == entries_.end()) return std::nullopt;
  return it->second;
}
std::optional<LivenessEntry> LivenessTable::find_component(const Address& component) const {
  if (component.component == 0) return std::nullopt;  // that key would be a node's or subsystem's
  return find(component);
}
std::optional<LivenessEntry> LivenessTable::find_node(const Address& address) const { return find(node_of(address)); }
std::optional<LivenessEntry> LivenessTable::find_subsystem(const Address& address) const {
  return find(subsystem_of(address));
}

std::vector<LivenessEntry> LivenessTable::known(LivenessLevel level) const {
  std::vector<LivenessEntry> out;
  for (const auto& [key, entry] : entries_)
    if (entry.level == level) out.push_back(entry);
  return out;
}

rt::Duration LivenessTable::timeout_of(LivenessLevel level) const {
  switch (level) {
    case LivenessLevel::subsystem: return options_.subsystem_timeout;
    case LivenessLevel::node: return options_.node_timeout;
    case LivenessLevel::component: return options_.component_timeout;
  }
  return options_.component_timeout;
}

}  // namespace jaus::node
