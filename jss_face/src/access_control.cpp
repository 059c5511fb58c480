// Access Control (jss-notes.md 3.3) on every component but the node manager,
// translated onto the RA component's own arbitration from the client's
// alias: one controller for both dialects, the RA authority rule, the RA
// controller timeout (a JSS client keeps control by sending within it, as
// AS5710 says: re-sending Request Control does), Reject on loss.
//   Request Control  -> RA Request Component Control (Confirm codes are the same)
//   Release Control  -> RA Release Component Control; Reject Control 0 to the
//                       client (RA answers a release with nothing)
//   RA Reject Component Control (empty) -> Reject Control 0 (CONTROL_RELEASED)
//   Query Control    -> RA Query Component Control; the controller's RA
//                       address in the report becomes its JSS ID
//   Query Timeout    -> Report Timeout (the RA controller timeout)
//   Query Authority  -> RA Query Component Authority
//   Set Authority    -> from the controller: RA Request Component Control at
//                       the new authority (its Confirm is not passed on: JSS
//                       Set Authority has no reply)
//   RA Query Component Status to the alias (the controller check) -> Query Status
#include <set>

#include "core_translators.hpp"
#include "face_bytes.hpp"
#include "jaus/node/node.hpp"

namespace jaus::jss_face {
namespace {

namespace id {
constexpr std::uint16_t kSetAuthority = 0x0001;
constexpr std::uint16_t kRequestControl = 0x000D;
constexpr std::uint16_t kReleaseControl = 0x000E;
constexpr std::uint16_t kConfirmControl = 0x000F;
constexpr std::uint16_t kRejectControl = 0x0010;
constexpr std::uint16_t kQueryAuthority = 0x2001;
constexpr std::uint16_t kQueryStatus = 0x2002;
constexpr std::uint16_t kQueryTimeout = 0x2003;
constexpr std::uint16_t kQueryControl = 0x200D;
constexpr std::uint16_t kReportAuthority = 0x4001;
constexpr std::uint16_t kReportTimeout = 0x4003;
constexpr std::uint16_t kReportControl = 0x400D;
}  // namespace id

constexpr std::uint8_t kControlReleased = 0;

class AccessControlTranslator final : public ServiceTranslator {
 public:
  std::string_view name() const override { return "access control"; }
  std::vector<ServiceUri> services(std::uint8_t ra_id) const override {
    if (ra_id == kNodeManagerId) return {};
    return {core_service("AccessControl")};
  }
  bool handles(std::uint16_t message_id, std::uint8_t ra_id) const override {
    if (ra_id == kNodeManagerId) return false;
    switch (message_id) {
      case id::kSetAuthority:
      case id::kRequestControl:
      case id::kReleaseControl:
      case id::kQueryAuthority:
      case id::kQueryTimeout:
      case id::kQueryControl:
        return true;
      default:
        return false;
    }
  }

  bool from_jss(const JssInbound& m, FacePort& port) override {
    if (!handles(m.message_id, m.ra_component.component)) return false;
    const std::size_t expected = (m.message_id == id::kSetAuthority || m.message_id == id::kRequestControl) ? 1 : 0;
    if (m.body.size() != expected) {
      port.malformed("JSS message " + hex_id(m.message_id) + " from " + m.origin.client.to_string(),
                     std::to_string(m.body.size()) + " body bytes where " + std::to_string(expected) + " belong");
      return true;
    }
    switch (m.message_id) {
      case id::kRequestControl:
        port.send_ra(m.origin, m.ra_component, id::kRequestControl, m.body, m.standing);
        return true;
      case id::kReleaseControl: {
        const auto controller = controller_of(m, port);
        port.send_ra(m.origin, m.ra_component, id::kReleaseControl, {}, m.standing);
        // JSS answers a release with Reject Control 0 (RA answers nothing):
        // the controller's release, or a release of a component nobody controls.
        if (!controller || *controller == m.origin.client)
          port.reply(m.origin, m.our_component, ContentsWriter(id::kRejectControl).u8(kControlReleased));
        return true;
      }
      case id::kQueryControl:
        port.send_ra(m.origin, m.ra_component, id::kQueryControl, {}, m.standing);
        return true;
      case id::kQueryAuthority:
        port.send_ra(m.origin, m.ra_component, id::kQueryAuthority, {}, m.standing);
        return true;
      case id::kQueryTimeout:
        port.reply(m.origin, m.our_component, ContentsWriter(id::kReportTimeout).u8(port.config().controller_timeout_s));
        return true;
      case id::kSetAuthority: {
        // Controller only (others are ignored without reply, as JSS commands are).
        const auto controller = controller_of(m, port);
        if (!controller || *controller != m.origin.client) return true;
        silent_confirms_.insert({m.origin.client, m.our_component});
        port.send_ra(m.origin, m.ra_component, id::kRequestControl, m.body, m.standing);
        return true;
      }
      default:
        return false;
    }
  }

  bool from_ra(const RaOutbound& m, FacePort& port) override {
    switch (m.header.command_code) {
      case id::kConfirmControl: {
        if (m.payload.size() != 1) return false;
        if (silent_confirms_.erase({m.to.client, m.our_component}) > 0) return true;  // Set Authority's
        port.reply(m.to, m.our_component, ContentsWriter(id::kConfirmControl).u8(m.payload[0]));
        return true;
      }
      case id::kRejectControl:
        silent_confirms_.erase({m.to.client, m.our_component});
        port.reply(m.to, m.our_component, ContentsWriter(id::kRejectControl).u8(kControlReleased));
        return true;
      case id::kReportControl: {
        if (m.payload.size() != 5) return false;
        // RA: subsystem, node, component, instance, authority (u8 each).
        const Address controller{m.payload[0], m.payload[1], m.payload[2], m.payload[3]};
        const jss::JssId jss = controller == Address{} ? jss::JssId{} : port.jss_id_for(controller);
        port.reply(m.to, m.our_component,
                   ContentsWriter(id::kReportControl).u16(jss.subsystem).u8(jss.node).u8(jss.component).u8(m.payload[4]));
        return true;
      }
      case id::kReportAuthority:
        if (m.payload.size() != 1) return false;
        port.reply(m.to, m.our_component, ContentsWriter(id::kReportAuthority).u8(m.payload[0]));
        return true;
      case id::kQueryStatus:
        // The RA component checks that its (alias) controller is alive.
        port.reply(m.to, m.our_component, ContentsWriter(id::kQueryStatus));
        return true;
      default:
        return false;
    }
  }

  void forget(const jss::JssId& client_node) override {
    std::erase_if(silent_confirms_, [&](const auto& entry) {
      return entry.first.subsystem == client_node.subsystem && entry.first.node == client_node.node;
    });
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
