// Velocity State Sensor 1.0 on the RA velocity state sensor (42), docs/jss.md
// "Sensors": the query and report are RA's; encoding in JSS rescales
// (RA +-65.534 m/s and +-32.767 rad/s lie within JSS's ranges).
#include "mobility_translators.hpp"
#include "mobility_translators_report.hpp"

namespace jaus::jss_face {

std::unique_ptr<ServiceTranslator> make_velocity_state_translator() {
  using Translator = mobility::ReportTranslator<jss::msg::QueryVelocityState, jss::msg::ReportVelocityState>;
  return std::make_unique<Translator>("velocity state sensor", component_id::kVelocityStateSensor,
                                      std::vector<ServiceUri>{{"urn:jaus:jss:mobility:VelocityStateSensor", 1, 0}});
}

}  // namespace jaus::jss_face
