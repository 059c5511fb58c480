// Who is alive: every subsystem, node and component we have heard from (any
// traffic, heartbeats included) and when, forgotten after a silence of its
// level's timeout. expire() hands back what was forgotten so the caller can
// react (end service connections, release control, ...).
//
// Hearing a component also refreshes its node and subsystem. A node or
// subsystem that goes silent takes everything under it along, whatever the
// timeouts of the lower levels.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <vector>

#include "jaus/core/address.hpp"
#include "jaus/base/time.hpp"

namespace jaus::node {

enum class LivenessLevel : std::uint8_t { subsystem, node, component };

// Entries are keyed by the address cut to their level, with 0 (never a real
// ID) below it: subsystem 5 is 5.0.0.0, its node 2 is 5.2.0.0.
Address subsystem_of(const Address& address);
Address node_of(const Address& address);

struct LivenessEntry {
  LivenessLevel level = LivenessLevel::component;
  Address address;
  rt::TimePoint first_heard{};
  rt::TimePoint last_heard{};
};

// What heard() learnt: lets the caller start discovery (Query Identification
// to a new subsystem, and so on).
struct HeardResult {
  bool recorded = false;  // false: invalid source, or the table was full for a newcomer
  bool new_subsystem = false;
  bool new_node = false;
  bool new_component = false;
};

struct LivenessCounters {
  std::uint64_t invalid_sources = 0;  // an octet of 0 or 255
  std::uint64_t rejected_full = 0;    // newcomers not recorded because of max_entries
  std::uint64_t expired = 0;          // entries forgotten by expire()
};

class LivenessTable {
 public:
  struct Options {
    rt::Duration component_timeout = std::chrono::seconds(3);
    rt::Duration node_timeout = std::chrono::seconds(5);
    rt::Duration subsystem_timeout = std::chrono::seconds(5);
    // Entries of all levels together. When full, newcomers are not recorded
    // (known peers are never pushed out by a flood of new sources); call
    // expire() regularly to make room.
    std::size_t max_entries = 1024;
  };

  LivenessTable() : LivenessTable(Options{}) {}
  explicit LivenessTable(Options options) : options_(options) {}

  // `source` sent us something at `now`.
  HeardResult heard(const Address& source, rt::TimePoint now);

  // Forgets every entry silent for its timeout at `now` (and what lies under
  // a forgotten node or subsystem); returns them, components first, then
  // nodes, then subsystems.
  std::vector<LivenessEntry> expire(rt::TimePoint now);
  // When the next entry would expire, for scheduling expire().
  std::optional<rt::TimePoint> next_deadline() const;

  std::optional<LivenessEntry> find_component(const Address& component) const;
  std::optional<LivenessEntry> find_node(const Address& any_address_on_node) const;
  std::optional<LivenessEntry> find_subsystem(const Address& any_address_in_subsystem) const;
  // Known entries of one level, in address order.
  std::vector<LivenessEntry> known(LivenessLevel level) const;

  std::size_t size() const { return entries_.size(); }
  const LivenessCounters& counters() const { return counters_; }

 private:
  rt::Duration timeout_of(LivenessLevel level) const;
  std::optional<LivenessEntry> find(const Address& key) const;

  Options options_;
  std::map<Address, LivenessEntry> entries_;  // keys cut to their level (see above)
  LivenessCounters counters_;
};

}  // namespace jaus::node
