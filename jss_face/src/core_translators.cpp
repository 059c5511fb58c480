// core_translators() and the Transport/Events lister: the face itself does
// the transport (face.cpp) and runs events (face_events.cpp); every
// component lists both services.
#include "core_translators.hpp"

namespace jaus::jss_face {
namespace {

class TransportEventsTranslator final : public ServiceTranslator {
 public:
  std::string_view name() const override { return "transport and events"; }
  std::vector<ServiceUri> services(std::uint8_t) const override {
    return {core_service("Transport"), core_service("Events")};
  }
  bool handles(std::uint16_t, std::uint8_t) const override { return false; }
  bool from_jss(const JssInbound&, FacePort&) override { return false; }
  bool from_ra(const RaOutbound&, FacePort&) override { return false; }
};

}  // namespace

std::unique_ptr<ServiceTranslator> make_transport_events_translator() {
  return std::make_unique<TransportEventsTranslator>();
}

Translators core_translators(const FaceConfig& config) {
  Translators translators;
  translators.push_back(make_transport_events_translator());
  translators.push_back(make_access_control_translator());
  translators.push_back(make_management_translator());
  translators.push_back(make_liveness_translator());
  translators.push_back(make_discovery_translator(config));
  return translators;
}

}  // namespace jaus::jss_face
