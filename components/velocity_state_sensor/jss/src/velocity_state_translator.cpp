// Velocity State Sensor 1.0 on the RA velocity state sensor, docs/jss.md
// "Sensors": the query and report are RA's; encoding in JSS rescales
// (RA +-65.534 m/s and +-32.767 rad/s lie within JSS's ranges).
#include "jaus/components_jss/velocity_state_sensor_jss.hpp"

#include "jaus/core/component_ids.hpp"
#include "jaus/jss_face/report_translator.hpp"

namespace jaus::components_jss {

jss_face::Translators velocity_state_sensor_translators(const jss_face::FaceConfig&) {
  using Translator =
      jss_face::kit::ReportTranslator<jss::msg::QueryVelocityState, jss::msg::ReportVelocityState>;
  jss_face::Translators translators;
  translators.push_back(std::make_unique<Translator>(
      "velocity state sensor", component_id::kVelocityStateSensor,
      std::vector<jss_face::ServiceUri>{{"urn:jaus:jss:mobility:VelocityStateSensor", 1, 0}}));
  return translators;
}

}  // namespace jaus::components_jss
