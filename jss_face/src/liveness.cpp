// Liveness (docs/jss.md, "Liveness"): every component answers Query Heartbeat
// Pulse itself (the RA component would answer the same, but the face knows
// it is alive). No unsolicited heartbeat: JSS has none.
#include "core_translators.hpp"
#include "jaus/jss/messages/core.hpp"

namespace jaus::jss_face {
namespace {

namespace jss_msg = jss::msg;

class LivenessTranslator final : public ServiceTranslator {
 public:
  std::string_view name() const override { return "liveness"; }
  std::vector<ServiceUri> services(std::uint8_t) const override { return {core_service("Liveness")}; }
  bool handles(std::uint16_t id, std::uint8_t) const override { return id == jss_msg::QueryHeartbeatPulse::code; }
  bool from_jss(const JssInbound& m, FacePort& port) override {
    if (m.message_id != jss_msg::QueryHeartbeatPulse::code) return false;
    if (decode_jss<jss_msg::QueryHeartbeatPulse>(m, port)) reply_jss(port, m.origin, m.our_component, jss_msg::ReportHeartbeatPulse{});
    return true;
  }
  bool from_ra(const RaOutbound&, FacePort&) override { return false; }
};

}  // namespace

std::unique_ptr<ServiceTranslator> make_liveness_translator() { return std::make_unique<LivenessTranslator>(); }

}  // namespace jaus::jss_face
