#include "jaus/host/metrics.hpp"

#include <charconv>
#include <cstdint>
#include <functional>
#include <string_view>
#include <utility>
#include <vector>

#include "jaus/host/node_host.hpp"
#include "jaus/runtime/lifecycle.hpp"

namespace jaus::host {

namespace {

using MetricLabel = std::pair<std::string_view, std::string>;

// The text format: per family its HELP and TYPE lines, then its samples
// together (a family's samples may not be split).
class MetricsExposition {
 public:
  void family(std::string_view name, std::string_view type, std::string_view help) {
    name_ = name;
    text_ += "# HELP ";
    text_ += name;
    text_ += ' ';
    text_ += help;
    text_ += "\n# TYPE ";
    text_ += name;
    text_ += ' ';
    text_ += type;
    text_ += '\n';
  }
  void sample(const std::vector<MetricLabel>& labels, std::uint64_t value) { line(labels, std::to_string(value)); }
  void seconds(const std::vector<MetricLabel>& labels, rt::Duration value) {
    char buffer[32];
    const double s = std::chrono::duration<double>(value).count();
    const auto end = std::to_chars(buffer, buffer + sizeof buffer, s).ptr;
    line(labels, std::string(buffer, end));
  }
  // A counter family with one sample per label value of `label`.
  template <class Values>
  void counters(std::string_view name, std::string_view help, std::string_view label, const Values& values) {
    family(name, "counter", help);
    for (const auto& [value_name, value] : values) sample({{label, std::string(value_name)}}, value);
  }
  std::string take() { return std::move(text_); }

 private:
  static void escape_into(std::string& out, std::string_view value) {
    for (const char c : value) {
      if (c == '\\') out += "\\\\";
      else if (c == '"') out += "\\\"";
      else if (c == '\n') out += "\\n";
      else out += c;
    }
  }
  void line(const std::vector<MetricLabel>& labels, const std::string& value) {
    text_ += name_;
    if (!labels.empty()) {
      text_ += '{';
      for (std::size_t i = 0; i < labels.size(); ++i) {
        if (i) text_ += ',';
        text_ += labels[i].first;
        text_ += "=\"";
        escape_into(text_, labels[i].second);
        text_ += '"';
      }
      text_ += '}';
    }
    text_ += ' ';
    text_ += value;
    text_ += '\n';
  }

  std::string text_;
  std::string_view name_;
};

using MetricCounts = std::vector<std::pair<std::string_view, std::uint64_t>>;

void node_metrics(MetricsExposition& out, const node::Node& node) {
  const node::NodeCounters& c = node.counters();
  out.family("jaus_node_packets_received_total", "counter", "JAUS packets handed to the node");
  out.sample({}, c.packets_received);
  out.family("jaus_node_packets_sent_total", "counter", "JAUS packets the node sent (retransmissions included)");
  out.sample({}, c.packets_sent);
  out.counters("jaus_node_packets_dropped_total", "packets the node did not deliver, by reason", "reason",
               MetricCounts{{"malformed", c.malformed},
                       {"invalid_source", c.invalid_source},
                       {"undeliverable", c.undeliverable},
                       {"queue_full", c.queue_dropped}});
  out.family("jaus_node_messages_delivered_total", "counter", "messages handed to a local component");
  out.sample({}, c.delivered);
  out.family("jaus_node_duplicates_filtered_total", "counter",
             "retransmitted copies of messages already handled: ACKed again, not delivered again");
  out.sample({}, c.duplicates_filtered);
  out.counters("jaus_node_acks_sent_total", "answers to ACK requests", "answer",
               MetricCounts{{"ack", c.acks_sent}, {"nak", c.naks_sent}});
  out.family("jaus_node_send_failures_total", "counter", "local messages the node could not send");
  out.sample({}, c.send_failures);
  const node::AckCounters& a = node.acks().counters();
  out.counters("jaus_node_ack_requests_total", "the node's own ACK-requested messages, by how they ended",
               "outcome",
               MetricCounts{{"acknowledged", a.acknowledged}, {"refused", a.refused}, {"unacknowledged", a.exhausted}});
  out.family("jaus_node_retransmissions_total", "counter", "ACK-requested messages sent again");
  out.sample({}, a.retransmissions);
  out.family("jaus_node_ack_requests_pending", "gauge", "ACK-requested messages waiting for their answer");
  out.sample({}, node.acks().pending());
}

void peer_metrics(MetricsExposition& out, const node::Node& node) {
  const node::PeerCounters& peers = node.peer_counters();
  struct Row {
    std::string peer;
    const node::PeerCounts* counts;
    const node::RoundTripEstimator* round_trip;
  };
  std::vector<Row> rows;
  for (const auto& [key, counts] : peers.peers())
    rows.push_back({std::to_string(key.first) + "." + std::to_string(key.second), &counts,
                    node.acks().round_trip(Address{key.first, key.second, 0, 0})});
  const node::PeerCounts& others = peers.others();
  if (others.packets_received || others.packets_sent) rows.push_back({"other", &others, nullptr});
  const auto each = [&](std::string_view name, std::string_view help, std::uint64_t node::PeerCounts::*field) {
    out.family(name, "counter", help);
    for (const auto& r : rows) out.sample({{"peer", r.peer}}, r.counts->*field);
  };
  each("jaus_peer_packets_received_total", "packets from the peer node's components", &node::PeerCounts::packets_received);
  each("jaus_peer_packets_sent_total", "packets to the peer node's components (broadcasts not counted)",
       &node::PeerCounts::packets_sent);
  each("jaus_peer_retransmissions_total", "ACK-requested messages to the peer sent again",
       &node::PeerCounts::retransmissions);
  out.family("jaus_peer_ack_requests_total", "counter", "ACK-requested messages to the peer, by how they ended");
  for (const auto& r : rows) {
    out.sample({{"peer", r.peer}, {"outcome", "acknowledged"}}, r.counts->acknowledged);
    out.sample({{"peer", r.peer}, {"outcome", "refused"}}, r.counts->refused);
    out.sample({{"peer", r.peer}, {"outcome", "unacknowledged"}}, r.counts->unacknowledged);
  }
  each("jaus_peer_duplicates_total", "copies from the peer already handled, filtered",
       &node::PeerCounts::duplicates);
  // Only peers whose round trip was measured (an ACK of a message sent once).
  const auto measured = [&](std::string_view name, std::string_view help,
                            const std::function<rt::Duration(const node::RoundTripEstimator&)>& value) {
    out.family(name, "gauge", help);
    for (const auto& r : rows)
      if (r.round_trip && r.round_trip->smoothed()) out.seconds({{"peer", r.peer}}, value(*r.round_trip));
  };
  measured("jaus_peer_round_trip_seconds", "the smoothed round trip to the peer (RFC 6298)",
           [](const node::RoundTripEstimator& e) { return *e.smoothed(); });
  measured("jaus_peer_round_trip_variation_seconds", "the round trip's variation",
           [](const node::RoundTripEstimator& e) { return e.variation(); });
  measured("jaus_peer_retransmission_timeout_seconds", "how long an ACK from the peer is waited for before sending again",
           [](const node::RoundTripEstimator& e) { return e.timeout(); });
}

void transport_metrics(MetricsExposition& out, const transport::UdpLinkCounters& c) {
  out.family("jaus_transport_datagrams_received_total", "counter", "UDP datagrams received (both dialects)");
  out.sample({}, c.datagrams_received);
  out.family("jaus_transport_datagrams_sent_total", "counter", "UDP datagrams sent");
  out.sample({}, c.datagrams_sent);
  out.family("jaus_transport_datagrams_dropped_total", "counter", "UDP datagrams dropped on receipt, by reason");
  for (std::size_t r = 0; r < c.dropped.size(); ++r)
    out.sample({{"reason", std::string(transport::to_string(static_cast<transport::DropReason>(r)))}}, c.dropped[r]);
  out.counters("jaus_transport_unsent_total", "messages the transport could not send, by reason", "reason",
               MetricCounts{{"no_route", c.no_route + c.jss.no_route}, {"socket_refused", c.send_errors}});
  out.family("jaus_transport_relayed_total", "counter", "messages for another subsystem sent on to its node");
  out.sample({}, c.relayed);
  out.family("jaus_transport_jss_datagrams_received_total", "counter", "AS5669A (SAE JAUS) datagrams received");
  out.sample({}, c.jss.datagrams_received);
}

void budget_metrics(MetricsExposition& out, const node::BudgetedLink& budget) {
  const node::SendBudgetCounters& c = budget.counters();
  out.family("jaus_send_budget_bits_per_second", "gauge", "the send budget's rate (transport.send_rate_kbit)");
  out.sample({}, budget.bits_per_second());
  const auto per_class = [&](std::string_view name, std::string_view help,
                             std::uint64_t node::SendBudgetCounters::PerClass::*field) {
    out.family(name, "counter", help);
    for (std::size_t i = 0; i < node::kSendClasses; ++i)
      out.sample({{"class", std::string(node::to_string(static_cast<node::SendClass>(i)))}}, c.classes[i].*field);
  };
  per_class("jaus_send_budget_packets_total", "packets handed to the link, by class",
            &node::SendBudgetCounters::PerClass::sent);
  per_class("jaus_send_budget_bytes_total", "their JAUS bytes", &node::SendBudgetCounters::PerClass::bytes_sent);
  per_class("jaus_send_budget_waited_total", "packets that waited in the budget before going",
            &node::SendBudgetCounters::PerClass::waited);
  per_class("jaus_send_budget_dropped_total", "packets dropped: the class's queue was full",
            &node::SendBudgetCounters::PerClass::dropped);
  per_class("jaus_send_budget_replaced_total", "packets replaced by a newer one, or dropped by a stop",
            &node::SendBudgetCounters::PerClass::superseded);
  out.family("jaus_send_budget_queued_bytes", "gauge", "bytes waiting in the budget now");
  out.sample({}, c.queued_bytes);
  out.family("jaus_send_budget_queued_packets", "gauge", "packets waiting in the budget now");
  out.sample({}, c.queued_packets);
  out.family("jaus_send_budget_longest_wait_seconds", "gauge", "the longest a sent packet waited");
  out.seconds({}, c.longest_wait);
}

void component_metrics(MetricsExposition& out, const node::Node& node) {
  const auto components = node.local_components();
  const auto labels = [](const rt::Component& c) {
    return std::vector<MetricLabel>{{"component", c.address().to_string()}, {"name", c.name()}};
  };
  out.family("jaus_component_messages_received_total", "counter", "messages handed to the component");
  for (const auto* c : components) out.sample(labels(*c), c->counters().received);
  out.family("jaus_component_refused_total", "counter", "messages the component did not act on, by reason");
  for (const auto* c : components) {
    const rt::ComponentCounters& k = c->counters();
    const std::pair<std::string_view, std::uint64_t> reasons[] = {
        {"malformed", k.decode_errors},
        {"unsupported", k.unsupported},
        {"not_controller", k.refused_not_controller},
        {"wrong_state", k.refused_wrong_state},
        {"transition", k.refused_transitions},
        {"clear", k.refused_clears},
        {"authority", k.refused_authority_changes},
        {"observer", k.refused_observer},
        {"unrecorded", k.refused_unrecorded}};
    for (const auto& [reason, count] : reasons) {
      auto l = labels(*c);
      l.emplace_back("reason", std::string(reason));
      out.sample(l, count);
    }
  }
  out.family("jaus_component_control_changes_total", "counter", "times the component's controller changed");
  for (const auto* c : components) out.sample(labels(*c), c->counters().control_changes);
  out.family("jaus_component_stops_commanded_total", "counter", "stops the component commanded its hardware");
  for (const auto* c : components) out.sample(labels(*c), c->counters().stops_commanded);
  out.family("jaus_component_stops_entered_total", "counter",
             "entries into a state other than Ready (the stop counter of Report Component Status)");
  for (const auto* c : components) out.sample(labels(*c), c->counters().stops_entered);
  out.family("jaus_component_primary_status", "gauge",
             "the component's state: 0 Initialize, 1 Ready, 2 Standby, 3 Shutdown, 4 Failure, 5 Emergency");
  for (const auto* c : components) out.sample(labels(*c), static_cast<std::uint64_t>(c->state()));
}

}  // namespace

std::string metrics_text(const MetricsSources& sources) {
  MetricsExposition out;
  if (sources.node) {
    node_metrics(out, *sources.node);
    peer_metrics(out, *sources.node);
  }
  if (sources.link) transport_metrics(out, *sources.link);
  if (sources.budget) budget_metrics(out, *sources.budget);
  if (sources.node) component_metrics(out, *sources.node);
  return out.take();
}

std::string metrics_text(const NodeHost& host) {
  MetricsSources sources;
  sources.node = &host.node();
  sources.link = host.udp_link() ? &host.udp_link()->counters() : nullptr;
  sources.budget = host.send_budget();
  return metrics_text(sources);
}

}  // namespace jaus::host
