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

}  // namespace

Discovery discover(OcuSession& session, rt::Duration wait) {
  Discovery discovery(session.self());
  const auto dialect = session.options().dialect;
  const auto watcher = session.watch([&](const Header& h) { send_queries(session, discovery.heard(h.source)); });
  const auto listener = session.listen(
      [&](const Received& r) { send_queries(session, discovery.received(r.header, r.payload, dialect)); });
  send_queries(session, discovery.start());
  session.run_for(wait);
  session.unlisten(watcher);
  session.unlisten(listener);
  return discovery;
}

}  // namespace jaus::ocu
