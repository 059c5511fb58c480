// A node's counters in the Prometheus text exposition format (version
// 0.0.4, what fleet monitoring scrapes; issue 45 step 4, issue 46): the
// node's (packets, drops, ACK requests and their outcomes), each peer
// node's (packets each way, retransmissions, ACK outcomes, copies filtered,
// the round trip measured to it and its retransmission timeout), the UDP
// transport's (datagrams, drops by reason), the send budget's (per class)
// and each component's (messages, refusals by reason, stops, state).
// Sans-I/O: metrics_server.hpp serves it; tests read it as text.
//
// Names are prefixed jaus_; counters end in _total; a peer is labelled
// peer="S.N" (or "other" beyond the node's 256 kept peers), a component
// component="S.N.C.I" and name="...".
#pragma once

#include <string>

#include "jaus/node/budgeted_link.hpp"
#include "jaus/node/node.hpp"
#include "jaus/transport/udp_link.hpp"

namespace jaus::host {

class NodeHost;

struct MetricsSources {
  const node::Node* node = nullptr;
  const transport::UdpLinkCounters* link = nullptr;  // none: an attached node (no UDP)
  const node::BudgetedLink* budget = nullptr;        // none: no send budget
};

std::string metrics_text(const MetricsSources& sources);
// The host's node, link and budget.
std::string metrics_text(const NodeHost& host);

}  // namespace jaus::host
