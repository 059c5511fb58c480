// What jausd lost, once a minute (issue 45): the counts of datagrams and
// messages dropped anywhere on the way in and out, taken from the link, the
// node and the send budget, and one log line of what changed since the last
// look, written only when something was dropped.
#pragma once

#include <array>
#include <cstdint>
#include <string>

#include "jaus/node/budgeted_link.hpp"
#include "jaus/node/node.hpp"
#include "jaus/transport/udp_link.hpp"

namespace jaus::host {

struct DropCounts {
  // By the link, by reason (its own multicast looped back and a relay's
  // copies are counted here but are not losses: never reported).
  std::array<std::uint64_t, static_cast<std::size_t>(transport::DropReason::count_)> received{};
  std::uint64_t no_route = 0;       // sent to a node with nowhere to send it
  std::uint64_t send_errors = 0;    // the socket refused
  std::uint64_t malformed = 0;      // the node's, after the link
  std::uint64_t queue_full = 0;     // the node's inbound queue
  std::uint64_t not_sent = 0;       // a component's message the node could not send
  std::uint64_t budget_full = 0;    // the send budget's queues
  std::uint64_t budget_replaced = 0;  // waiting reports and frames replaced by newer ones (not a drop)
};

// Any of the three may be absent (an attached host has no UDP link, a host
// without a send budget no budget).
DropCounts drop_counts(const transport::UdpLinkCounters* link, const node::NodeCounters& node,
                       const node::SendBudgetCounters* budget);

// "in the last minute: 14 datagrams dropped on receipt (10 not allowed, 4
// truncated), 2 messages not sent, send budget: 3 dropped (queue full), 240
// replaced by newer"; empty when nothing was dropped since `before`.
std::string describe_drops(const DropCounts& before, const DropCounts& now);

}  // namespace jaus::host
