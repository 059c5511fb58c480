#include "jaus/console/panels/tree_panel.hpp"

#include "jaus/messages/all.hpp"

namespace jaus::console {

namespace {

std::string state_name(std::optional<std::uint8_t> status) {
  if (!status) return "unknown";
  for (const auto& s : jaus::msg::kComponentStates)
    if (s.value == *status) return std::string(s.name);
  return "unknown";
}

bool is_tree_report(std::uint16_t code) {
  return code == jaus::msg::ReportComponentStatus::code || code == jaus::msg::ReportComponentControl::code ||
         code == jaus::msg::ReportIdentification::code || code == jaus::msg::ReportConfiguration::code ||
         code == jaus::msg::ReportServices::code || code == jaus::msg::ReportSubsystemList::code;
}

}  // namespace

TreePanel::TreePanel(PanelContext& context, std::function<void()> found)
    : Panel(context), found_(std::move(found)), discovery_(context.session.self()), poll_timer_(context.clock, context.scheduler) {}

void TreePanel::start() {
  send_discovery(discovery_.start());
  poll_timer_.start(options().poll_period, [this] { poll(); });
}

void TreePanel::shutdown() {
  poll_timer_.stop();
  Panel::shutdown();
}

void TreePanel::page_opened(PageId page) { pages().to_page(page, tree()); }

void TreePanel::send_discovery(const std::vector<jaus::ocu::DiscoveryQuery>& queries) {
  for (const auto& q : queries) {
    switch (q.kind) {
      case jaus::ocu::DiscoveryQuery::Kind::identification:
        session().send(q.to, jaus::msg::QueryIdentification{{q.field}});
        break;
      case jaus::ocu::DiscoveryQuery::Kind::configuration:
        session().send(q.to, jaus::msg::QueryConfiguration{{q.field}});
        break;
      case jaus::ocu::DiscoveryQuery::Kind::services:
        session().send(q.to, jaus::msg::QueryServices{});
        break;
      case jaus::ocu::DiscoveryQuery::Kind::subsystem_list:
        session().send(q.to, jaus::msg::QuerySubsystemList{});
        break;
    }
  }
}

void TreePanel::heard(const jaus::Header& header) {
  const auto queries = discovery_.heard(header.source);
  if (queries.empty()) return;
  send_discovery(queries);
  publish();
}

void TreePanel::received(const jaus::ocu::Received& r) {
  const auto& h = r.header;
  const auto code = h.command_code;
  if (code == jaus::msg::ReportComponentStatus::code) {
    if (auto m = decode_report<jaus::msg::ReportComponentStatus>(r.payload))
      live_[h.source].status = static_cast<std::uint8_t>(m->primary_status & 0x0F);
  } else if (code == jaus::msg::ReportComponentControl::code) {
    if (auto m = decode_report<jaus::msg::ReportComponentControl>(r.payload)) {
      auto& live = live_[h.source];
      live.controller = m->controller == jaus::Address{} ? std::nullopt : std::optional<jaus::Address>(m->controller);
      live.authority = m->authority;
    }
  }
  if (!is_tree_report(code)) return;
  send_discovery(discovery_.received(h, r.payload, session().options().dialect));
  found_();
  publish();
}

void TreePanel::poll() {
  for (const auto& [sid, subsystem] : discovery_.subsystems())
    for (const auto& [nid, node] : subsystem.nodes)
      for (const auto& [key, c] : node.components) {
        session().send(c.address, jaus::msg::QueryComponentStatus{});
        session().send(c.address, jaus::msg::QueryComponentControl{});
      }
}

TreeFrame TreePanel::tree() const {
  TreeFrame frame;
  for (const auto& [sid, subsystem] : discovery_.subsystems()) {
    TreeSubsystem s{sid, subsystem.identification ? subsystem.identification->name : std::string(), {}};
    for (const auto& [nid, node] : subsystem.nodes) {
      TreeNode n{nid, node.identification ? node.identification->name : std::string(), {}};
      for (const auto& [key, c] : node.components) {
        TreeComponent tc{c.address, c.identification ? c.identification->name : std::string(), "unknown", {}, 0};
        if (auto it = live_.find(c.address); it != live_.end()) {
          tc.state = state_name(it->second.status);
          tc.controller = it->second.controller;
          tc.authority = it->second.authority;
        }
        n.components.push_back(std::move(tc));
      }
      s.nodes.push_back(std::move(n));
    }
    frame.subsystems.push_back(std::move(s));
  }
  return frame;
}

void TreePanel::publish() {
  auto text = format_frame(tree());
  if (text == last_tree_) return;
  last_tree_ = std::move(text);
  pages().send(kEveryPage, last_tree_);
}

}  // namespace jaus::console
