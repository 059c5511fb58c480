// Primitive Driver 1.0 on the RA primitive driver, docs/jss.md "Primitive Driver":
// Set Wrench Effort goes to the RA component as the client's alias, so the
// RA rules decide (control, Ready, the command timeout, every stop path);
// the body is RA's, decoded in the JSS dialect (unsigned), and the six
// propulsive efforts get JSS's near-zero made exactly 0. Query / Report Wrench Effort are the RA component's.
#include "jaus/components_jss/primitive_driver_jss.hpp"

#include "jaus/core/component_ids.hpp"
#include "jaus/jss_face/report_translator.hpp"
#include "jaus/jss_face/scaling.hpp"

namespace jaus::components_jss {
namespace {

using namespace jss_face;
using kit::ReportTranslator;

class PrimitiveDriverTranslator final
    : public ReportTranslator<jss::msg::QueryWrenchEffort, jss::msg::ReportWrenchEffort> {
 public:
  PrimitiveDriverTranslator()
      : ReportTranslator("primitive driver", component_id::kPrimitiveDriver,
                         {ServiceUri{"urn:jaus:jss:mobility:PrimitiveDriver", 1, 0}}) {}

 protected:
  bool handles_command(std::uint16_t message_id) const override {
    return message_id == jss::msg::SetWrenchEffort::code;
  }
  bool command(const JssInbound& m, FacePort& port) override {
    if (m.message_id != jss::msg::SetWrenchEffort::code) return false;
    auto set = kit::decode_jss_body<jss::msg::SetWrenchEffort>(m.body);
    if (!set) {
      kit::log_malformed(port, m, jss::msg::SetWrenchEffort::name, set.error());
      return true;
    }
    kit::send_ra(port, m, wrench_effort_to_ra(*set), log());
    return true;
  }
};

}  // namespace

msg::SetWrenchEffort wrench_effort_to_ra(const jss::msg::SetWrenchEffort& jss) {
  msg::SetWrenchEffort ra = jss;  // one body, decoded in the JSS dialect
  for (auto* effort : {&ra.propulsive_linear_effort_x_percent, &ra.propulsive_linear_effort_y_percent,
                       &ra.propulsive_linear_effort_z_percent, &ra.propulsive_rotational_effort_x_percent,
                       &ra.propulsive_rotational_effort_y_percent, &ra.propulsive_rotational_effort_z_percent})
    *effort = jss_face::scaling::effort_to_ra(*effort);
  return ra;
}

jss_face::Translators primitive_driver_translators(const jss_face::FaceConfig&) {
  jss_face::Translators translators;
  translators.push_back(std::make_unique<PrimitiveDriverTranslator>());
  return translators;
}

}  // namespace jaus::components_jss
