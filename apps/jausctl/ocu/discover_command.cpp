// `jausctl discover`: heartbeats and replies feed the Discovery model, which
// says what to ask next; after --wait, what was found is printed.
#include "jaus/ocu/discovery.hpp"
#include "discovery_output.hpp"
#include "ocu_commands.hpp"

#include "jaus/messages/discovery_messages.hpp"

namespace jausctl::ocu {

namespace {

void send_queries(OcuSession& session, const std::vector<DiscoveryQuery>& queries) {
  for (const auto& q : queries) {
    switch (q.kind) {
      case DiscoveryQuery::Kind::identification:
        session.send(q.to, jaus::msg::QueryIdentification{{q.field}});
        break;
      case DiscoveryQuery::Kind::configuration:
        session.send(q.to, jaus::msg::QueryConfiguration{{q.field}});
        break;
      case DiscoveryQuery::Kind::services:
        session.send(q.to, jaus::msg::QueryServices{});
        break;
    }
  }
}

}  // namespace

int run_discover(OcuSession& session, const DiscoverOptions& options, CommandIo io) {
  Discovery discovery(session.self());
  const auto dialect = session.options().dialect;
  const auto watcher = session.watch([&](const jaus::Header& h) { send_queries(session, discovery.heard(h.source)); });
  const auto listener = session.listen(
      [&](const Received& r) { send_queries(session, discovery.received(r.header, r.payload, dialect)); });
  send_queries(session, discovery.start());
  // Discovery is a snapshot: everything heard within the wait, nothing after.
  session.run_for(options.wait);
  session.unlisten(watcher);
  session.unlisten(listener);

  if (discovery.subsystems().empty()) {
    if (session.interrupted()) {
      io.err << "jausctl discover: interrupted\n";
      return kExitFailure;
    }
    std::string asked;
    for (const auto& peer : session.options().to) asked += (asked.empty() ? "" : ", ") + jaus::transport::to_string(peer);
    io.err << "jausctl discover: no JAUS node heard within " << seconds_text(options.wait) << " (asked " << asked
           << ")\n";
    return kExitFailure;
  }
  if (options.json)
    io.out << discovery_json(discovery).dump(2, ' ', false, Json::error_handler_t::replace) << "\n";
  else
    io.out << discovery_table(discovery);
  return kExitOk;
}

}  // namespace jausctl::ocu
