// Management (jss-notes.md 3.4) on every component but the node manager: the
// commands are the same bytes in both dialects and go to the RA component
// from the client's alias, so its rules hold: Resume, Standby, Shutdown and
// Reset from the controller only; Set Emergency from anyone, a hold that only
// the same alias's Clear Emergency (or the local clear) releases - nothing a
// JSS client does undoes a stop it did not make. Query Status -> RA Query
// Component Status; Report Component Status -> Report Status (the state in
// the low nibble, the u32 reserved: 0). A client's Report Status (its answer
// to the controller check's Query Status) goes to the component as a sign of
// life.
#include "core_translators.hpp"
#include "face_bytes.hpp"

namespace jaus::jss_face {
namespace {

namespace id {
constexpr std::uint16_t kShutdown = 0x0002;
constexpr std::uint16_t kStandby = 0x0003;
constexpr std::uint16_t kResume = 0x0004;
constexpr std::uint16_t kReset = 0x0005;
constexpr std::uint16_t kSetEmergency = 0x0006;
constexpr std::uint16_t kClearEmergency = 0x0007;
constexpr std::uint16_t kQueryStatus = 0x2002;
constexpr std::uint16_t kReportStatus = 0x4002;
}  // namespace id

// Body size of each message this translator takes.
std::optional<std::size_t> body_size_of(std::uint16_t message_id) {
  switch (message_id) {
    case id::kShutdown:
    case id::kStandby:
    case id::kResume:
    case id::kReset:
    case id::kQueryStatus:
      return 0;
    case id::kSetEmergency:
    case id::kClearEmergency:
      return 2;
    case id::kReportStatus:
      return 5;
    default:
      return std::nullopt;
  }
}

class ManagementTranslator final : public ServiceTranslator {
 public:
  std::string_view name() const override { return "management"; }
  std::vector<ServiceUri> services(std::uint8_t ra_id) const override {
    if (ra_id == kNodeManagerId) return {};
    return {core_service("Management")};
  }
  bool handles(std::uint16_t message_id, std::uint8_t ra_id) const override {
    return ra_id != kNodeManagerId && body_size_of(message_id).has_value();
  }

  bool from_jss(const JssInbound& m, FacePort& port) override {
    if (!handles(m.message_id, m.ra_component.component)) return false;
    if (m.body.size() != *body_size_of(m.message_id)) {
      port.malformed("JSS message " + hex_id(m.message_id) + " from " + m.origin.client.to_string(),
                     std::to_string(m.body.size()) + " body bytes where " +
                         std::to_string(*body_size_of(m.message_id)) + " belong");
      return true;
    }
    // Same code, same bytes (RA Report Component Status included).
    port.send_ra(m.origin, m.ra_component, m.message_id, m.body, m.standing);
    return true;
  }

  bool from_ra(const RaOutbound& m, FacePort& port) override {
    if (m.header.command_code != id::kReportStatus || m.payload.size() != 5) return false;
    port.reply(m.to, m.our_component, ContentsWriter(id::kReportStatus).u8(m.payload[0] & 0x0F).u32(0));
    return true;
  }
};

}  // namespace

std::unique_ptr<ServiceTranslator> make_management_translator() { return std::make_unique<ManagementTranslator>(); }

}  // namespace jaus::jss_face
