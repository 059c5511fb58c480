#include "jaus/host/drop_summary.hpp"

namespace jaus::host {

DropCounts drop_counts(const transport::UdpLinkCounters* link, const node::NodeCounters& node,
                       const node::SendBudgetCounters* budget) {
  DropCounts c;
  if (link) {
    c.received = link->dropped;
    c.no_route = link->no_route + link->jss.no_route;
    c.send_errors = link->send_errors;
  }
  c.malformed = node.malformed;
  c.queue_full = node.queue_dropped;
  c.not_sent = node.send_failures;
  if (budget) {
    for (const auto& per_class : budget->classes) {
      c.budget_full += per_class.dropped;
      c.budget_replaced += per_class.superseded;
    }
  }
  return c;
}

std::string describe_drops(const DropCounts& before, const DropCounts& now) {
  std::string parts;
  const auto add = [&parts](std::uint64_t count, const std::string& what) {
    if (count == 0) return;
    parts += (parts.empty() ? "" : ", ") + std::to_string(count) + " " + what;
  };
  std::uint64_t received = 0;
  std::string reasons;
  for (std::size_t r = 0; r < now.received.size(); ++r) {
    const auto reason = static_cast<transport::DropReason>(r);
    // Our own multicast coming back and a relay's copy of what came directly
    // are the network working as it should, not losses.
    if (reason == transport::DropReason::from_self || reason == transport::DropReason::relayed_copy) continue;
    const std::uint64_t n = now.received[r] - before.received[r];
    if (n == 0) continue;
    received += n;
    reasons += (reasons.empty() ? "" : ", ") + std::to_string(n) + " " +
               std::string(transport::to_string(reason));
  }
  add(received, "datagrams dropped on receipt (" + reasons + ")");
  add(now.malformed - before.malformed, "malformed packets");
  add(now.queue_full - before.queue_full, "messages dropped (inbound queue full)");
  add(now.no_route - before.no_route, "messages with no route");
  add(now.send_errors - before.send_errors, "datagrams the socket refused");
  add(now.not_sent - before.not_sent, "messages not sent");
  add(now.budget_full - before.budget_full, "dropped by the send budget (queue full)");
  if (parts.empty()) return {};
  add(now.budget_replaced - before.budget_replaced, "waiting reports and frames replaced by newer");
  return "in the last minute: " + parts;
}

}  // namespace jaus::host
