// `jausctl discover`: what the OCU library's discovery finds within --wait,
// printed as a table or JSON.
#include "jaus/ocu/discover.hpp"
#include "discovery_output.hpp"
#include "ocu_commands.hpp"

namespace jausctl::ocu {

int run_discover(OcuSession& session, const DiscoverOptions& options, CommandIo io) {
  const Discovery discovery = jaus::ocu::discover(session, options.wait);
  if (discovery.subsystems().empty()) {
    if (session.interrupted()) {
      io.err << "jausctl discover: interrupted\n";
      return kExitFailure;
    }
    std::string asked;
    for (const auto& peer : session.options().to) asked += (asked.empty() ? "" : ", ") + jaus::transport::to_string(peer);
    if (const auto& group = session.options().multicast)
      asked += (asked.empty() ? "the multicast group " : " and the multicast group ") + jaus::transport::to_string(*group);
    io.err << "jausctl discover: no JAUS node heard within " << seconds_text(options.wait) << " (asked " << asked
           << ")\n";
    return kExitFailure;
  }
  if (options.json)
    io.out << discovery_json(discovery).dump(2, ' ', false, Json::error_handler_t::replace) << "\n";
  else
    io.out << discovery_table(discovery);
  if (discovery.components_left_out() > 0)
    io.err << "jausctl discover: " << discovery.components_left_out()
           << " components left out (more than a subsystem or a system is believed to have)\n";
  return kExitOk;
}

}  // namespace jausctl::ocu
