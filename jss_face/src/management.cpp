// Management (docs/jss.md, "Management") on every component but the node manager: the
// commands are the same bytes in both dialects and go to the RA component
// from the client's alias, so its rules hold: Resume, Shutdown and Reset from
// the controller only (Standby from anyone: it only stops, RA's rule); Set
// Emergency from anyone, a hold that only the same alias's Clear Emergency
// (or the local clear) releases - nothing a JSS client does undoes a stop it
// did not make. Query Status -> RA Query Component Status; Report Component
// Status -> Report Status (the state in the low nibble, the u32 reserved: 0).
// A client's Report Status (its answer to the controller check's Query
// Status) goes to the component as a sign of life.
#include "core_translators.hpp"
#include "jaus/jss/messages/core.hpp"
#include "jaus/messages/core_messages.hpp"

namespace jaus::jss_face {
namespace {

namespace jss_msg = jss::msg;

// Checks the body is M's, then hands the same bytes to the RA component.
template <class M>
void forward(const JssInbound& m, FacePort& port) {
  if (decode_jss<M>(m, port)) port.send_ra(m.origin, m.ra_component, M::code, m.body, m.standing);
}

class ManagementTranslator final : public ServiceTranslator {
 public:
  std::string_view name() const override { return "management"; }
  std::vector<ServiceUri> services(std::uint8_t ra_id) const override {
    if (ra_id == component_id::kNodeManager) return {};
    return {core_service("Management")};
  }
  bool handles(std::uint16_t message_id, std::uint8_t ra_id) const override {
    return ra_id != component_id::kNodeManager &&
           is_one_of<jss_msg::Shutdown, jss_msg::Standby, jss_msg::Resume, jss_msg::Reset, jss_msg::SetEmergency,
                     jss_msg::ClearEmergency, jss_msg::QueryStatus, jss_msg::ReportStatus>(message_id);
  }

  bool from_jss(const JssInbound& m, FacePort& port) override {
    if (!handles(m.message_id, m.ra_component.component)) return false;
    switch (m.message_id) {
      case jss_msg::Shutdown::code: forward<jss_msg::Shutdown>(m, port); break;
      case jss_msg::Standby::code: forward<jss_msg::Standby>(m, port); break;
      case jss_msg::Resume::code: forward<jss_msg::Resume>(m, port); break;
      case jss_msg::Reset::code: forward<jss_msg::Reset>(m, port); break;
      case jss_msg::SetEmergency::code: forward<jss_msg::SetEmergency>(m, port); break;
      case jss_msg::ClearEmergency::code: forward<jss_msg::ClearEmergency>(m, port); break;
      case jss_msg::QueryStatus::code: forward<jss_msg::QueryStatus>(m, port); break;
      case jss_msg::ReportStatus::code: forward<jss_msg::ReportStatus>(m, port); break;  // = RA Report Component Status
      default: return false;
    }
    return true;
  }

  bool from_ra(const RaOutbound& m, FacePort& port) override {
    if (m.header.command_code != jaus::msg::ReportComponentStatus::code) return false;
    const auto status = decode_ra<jaus::msg::ReportComponentStatus>(m);
    if (!status) return false;
    jss_msg::ReportStatus report;
    report.status = static_cast<std::uint8_t>(status->primary_status & 0x0F);
    report.reserved = 0;
    reply_jss(port, m.to, m.our_component, report);
    return true;
  }
};

}  // namespace

std::unique_ptr<ServiceTranslator> make_management_translator() { return std::make_unique<ManagementTranslator>(); }

}  // namespace jaus::jss_face
