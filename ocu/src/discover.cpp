#include "jaus/ocu/discover.hpp"

#include "jaus/messages/discovery_messages.hpp"

namespace jaus::ocu {

namespace {

void send_queries(OcuSession& session, const std::vector<DiscoveryQuery>& queries) {
  for (const auto& q : queries) {
    switch (q.kind) {
      case DiscoveryQuery::Kind::identification:
        session.send(q.to, msg::QueryIdentification{{q.field}});
        break;
      case DiscoveryQuery::Kind::configuration:
        session.send(q.to, msg::QueryConfiguration{{q.field}});
        break;
      case DiscoveryQuery::Kind::services:
        session.send(q.to, msg::QueryServices{});
        break;
      case DiscoveryQuery::Kind::subsystem_list:
        session.send(q.to, msg::QuerySubsystemList{});
        break;
    }
  }
}

// Questions lost on a lossy link (or their answers) are asked again this
// often while the wait lasts; the first broadcast too (a node that missed it
// is also found by its heartbeats).
constexpr rt::Duration kAskAgainEvery = std::chrono::milliseconds(500);

}  // namespace

Discovery discover(OcuSession& session, rt::Duration wait) {
  Discovery discovery(session.self());
  const auto dialect = session.options().dialect;
  const auto watcher = session.watch([&](const Header& h) { send_queries(session, discovery.heard(h.source)); });
  const auto listener = session.listen(
      [&](const Received& r) { send_queries(session, discovery.received(r.header, r.payload, dialect)); });
  send_queries(session, discovery.start());
  const auto until = session.clock().now() + wait;
  for (;;) {
    const auto now = session.clock().now();
    if (now >= until || session.interrupted()) break;
    session.run_for(std::min(kAskAgainEvery, until - now));
    if (session.clock().now() >= until || session.interrupted()) break;
    send_queries(session, discovery.start());
    send_queries(session, discovery.unanswered());
  }
  session.unlisten(watcher);
  session.unlisten(listener);
  return discovery;
}

}  // namespace jaus::ocu
