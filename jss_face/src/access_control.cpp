// Access Control (docs/jss.md, "Access Control") on every component but the node manager,
// translated onto the RA component's own arbitration from the client's
// alias: one controller for both dialects, the RA authority rule, the RA
// controller timeout (a JSS client keeps control by sending within it, as
// AS5710 says: re-sending Request Control does), Reject on loss.
//   Request Control  -> RA Request Component Control (Confirm codes are the same);
//                       from a client outside transport.control_from (or one
//                       the node cannot record): Confirm Control 1 (NOT_AVAILABLE)
//                       from the face, logged with the client's JSS ID and host
//   Release Control  -> RA Release Component Control; Reject Control 0 to the
//                       client (RA answers a release with nothing)
//   RA Reject Component Control (empty) -> Reject Control 0 (CONTROL_RELEASED)
//   Query Control    -> RA Query Component Control; the controller's RA
//                       address in the report becomes its JSS ID
//   Query Timeout    -> Report Timeout (the RA controller timeout)
//   Query Authority  -> RA Query Component Authority; reported as the current
//                       authority (the controller's while controlled, AS5710)
//   Set Authority    -> from the controller: RA Request Component Control at
//                       the new authority (its Confirm is not passed on: JSS
//                       Set Authority has no reply)
//   RA Query Component Status to the alias (the controller check) -> Query Status
#include <set>

#include "core_translators.hpp"
#include "jaus/jss/messages/core.hpp"
#include "jaus/messages/core_messages.hpp"
#include "jaus/node/node.hpp"

namespace jaus::jss_face {
namespace {

namespace jss_msg = jss::msg;
namespace ra = jaus::msg;

class AccessControlTranslator final : public ServiceTranslator {
 public:
  std::string_view name() const override { return "access control"; }
  std::vector<ServiceUri> services(std::uint8_t ra_id) const override {
    if (ra_id == component_id::kNodeManager) return {};
    return {core_service("AccessControl")};
  }
  bool handles(std::uint16_t message_id, std::uint8_t ra_id) const override {
    return ra_id != component_id::kNodeManager &&
           is_one_of<jss_msg::SetAuthority, jss_msg::RequestControl, jss_msg::ReleaseControl, jss_msg::QueryAuthority,
                     jss_msg::QueryTimeout, jss_msg::QueryControl>(message_id);
  }

  bool from_jss(const JssInbound& m, FacePort& port) override {
    if (!handles(m.message_id, m.ra_component.component)) return false;
    switch (m.message_id) {
      case jss_msg::RequestControl::code:
        if (!decode_jss<jss_msg::RequestControl>(m, port)) return true;
        if (m.standing != rt::SenderStanding::trusted) {
          // Not allowed to command from where it is: Confirm Control 1
          // (NOT_AVAILABLE), not the RA refusal's 2, which JSS reads as
          // "insufficient authority" (a higher authority would not help).
          // The component is not asked: the refusal is the face's, and the
          // client takes no alias slot for it.
          port.refused(m.origin.client, "Request Control of " + m.our_component.to_string(),
                       "sender " + std::string(rt::to_string(m.standing)) + "; Confirm Control 1 (not available)");
          reply_jss(port, m.origin, m.our_component, jss_msg::ConfirmControl{{jss_msg::confirm_control::kNotAvailable}});
          return true;
        }
        // Same byte: the authority.
        port.send_ra(m.origin, m.ra_component, ra::RequestComponentControl::code, m.body, m.standing);
        return true;
      case jss_msg::ReleaseControl::code: {
        if (!decode_jss<jss_msg::ReleaseControl>(m, port)) return true;
        const auto controller = controller_of(m, port);
        port.send_ra(m.origin, m.ra_component, ra::ReleaseComponentControl::code, {}, m.standing);
        // JSS answers a release with Reject Control 0 (RA answers nothing):
        // the controller's release, or a release of a component nobody controls.
        if (!controller || *controller == m.origin.client)
          reply_jss(port, m.origin, m.our_component, jss_msg::RejectControl{{jss_msg::reject_control::kControlReleased}});
        return true;
      }
      case jss_msg::QueryControl::code:
        if (decode_jss<jss_msg::QueryControl>(m, port))
          port.send_ra(m.origin, m.ra_component, ra::QueryComponentControl::code, {}, m.standing);
        return true;
      case jss_msg::QueryAuthority::code:
        if (decode_jss<jss_msg::QueryAuthority>(m, port))
          port.send_ra(m.origin, m.ra_component, ra::QueryComponentAuthority::code, {}, m.standing);
        return true;
      case jss_msg::QueryTimeout::code:
        if (decode_jss<jss_msg::QueryTimeout>(m, port))
          reply_jss(port, m.origin, m.our_component, jss_msg::ReportTimeout{{port.config().controller_timeout_s}});
        return true;
      case jss_msg::SetAuthority::code: {
        // Controller only (others are ignored without reply, as JSS commands are).
        if (!decode_jss<jss_msg::SetAuthority>(m, port)) return true;
        const auto controller = controller_of(m, port);
        if (!controller || *controller != m.origin.client) return true;
        silent_confirms_.insert({m.origin.client, m.our_component});
        port.send_ra(m.origin, m.ra_component, ra::RequestComponentControl::code, m.body, m.standing);
        return true;
      }
      default:
        return false;
    }
  }

  bool from_ra(const RaOutbound& m, FacePort& port) override {
    switch (m.header.command_code) {
      case ra::ConfirmComponentControl::code: {
        const auto confirm = decode_ra<ra::ConfirmComponentControl>(m);
        if (!confirm) return false;
        if (silent_confirms_.erase({m.to.client, m.our_component}) > 0) return true;  // Set Authority's
        reply_jss(port, m.to, m.our_component, jss_msg::ConfirmControl{{confirm->response_code}});
        return true;
      }
      case ra::RejectComponentControl::code:
        silent_confirms_.erase({m.to.client, m.our_component});
        reply_jss(port, m.to, m.our_component, jss_msg::RejectControl{{jss_msg::reject_control::kControlReleased}});
        return true;
      case ra::ReportComponentControl::code: {
        const auto report = decode_ra<ra::ReportComponentControl>(m);
        if (!report) return false;
        jss_msg::ReportControl jss_report;
        if (report->controller != Address{}) jss_report.controller = port.jss_id_for(report->controller);
        jss_report.authority = report->authority;
        reply_jss(port, m.to, m.our_component, jss_report);
        return true;
      }
      case ra::ReportComponentAuthority::code: {
        const auto report = decode_ra<ra::ReportComponentAuthority>(m);
        if (!report) return false;
        // JSS reports the *current* authority: the controller's while the
        // component is controlled, its own (RA's answer) while it is free.
        std::uint8_t authority = report->authority;
        if (const rt::Component* component = port.node().find(m.header.source);
            component != nullptr && component->control().controller())
          authority = component->control().controller()->authority;
        reply_jss(port, m.to, m.our_component, jss_msg::ReportAuthority{{authority}});
        return true;
      }
      case ra::QueryComponentStatus::code:
        // The RA component checks that its (alias) controller is alive.
        reply_jss(port, m.to, m.our_component, jss_msg::QueryStatus{});
        return true;
      default:
        return false;
    }
  }

  void forget(const jss::JssId& client_node) override {
    std::erase_if(silent_confirms_, [&](const auto& entry) { return client_node.matches(entry.first); });
  }

 private:
  // The JSS ID of the RA component's controller (nullopt: not controlled).
  static std::optional<jss::JssId> controller_of(const JssInbound& m, FacePort& port) {
    const rt::Component* component = port.node().find(m.ra_component);
    if (component == nullptr || !component->control().controller()) return std::nullopt;
    return port.jss_id_for(component->control().controller()->address);
  }

  // (client, our component) whose next Confirm Component Control answers a
  // Set Authority (bounded by clients x components: one entry per pair).
  std::set<std::pair<jss::JssId, jss::JssId>> silent_confirms_;
};

}  // namespace

std::unique_ptr<ServiceTranslator> make_access_control_translator() {
  return std::make_unique<AccessControlTranslator>();
}

}  // namespace jaus::jss_face
