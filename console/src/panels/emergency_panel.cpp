#include "jaus/console/panels/emergency_panel.hpp"

#include <algorithm>

#include "jaus/messages/all.hpp"

namespace jaus::console {

EmergencyPanel::~EmergencyPanel() { wildcards_.clear(); }  // their timers and listeners go with them

void EmergencyPanel::page_opened(PageId page) {
  for (const auto& [target, active] : emergencies_)
    if (active) pages().to_page(page, EmergencyStateFrame{target, true, {session().self()}});
}

void EmergencyPanel::send_to_every_member(const jaus::Address& to, jaus::Header header,
                                          std::vector<std::uint8_t> payload, const std::string& what) {
  // Finished ones go first (never from their own callback).
  std::erase_if(wildcards_, [](const auto& w) { return w->finished(); });
  // Every component `to` names, found or not yet (a stop is broadcast too,
  // until they all confirm): ocu/wildcard_command.hpp (issue 49).
  std::weak_ptr<int> alive = alive_;
  auto& command = *wildcards_.emplace_back(std::make_unique<jaus::ocu::WildcardCommand>(
      session(), to, header, std::move(payload), jaus::ocu::WildcardPolicy{},
      [this, alive, what](const jaus::ocu::WildcardResult& result) {
        if (alive.expired()) return;
        const auto confirmed = result.confirmed();
        const auto unconfirmed = result.unconfirmed();
        std::string text = what + ": confirmed by " + std::to_string(confirmed.size()) + " component(s)";
        for (std::size_t i = 0; i < confirmed.size(); ++i) text += (i ? ", " : " (") + confirmed[i].to_string();
        if (!confirmed.empty()) text += ")";
        if (!unconfirmed.empty()) {
          text += "; NOT by";
          for (const auto& a : unconfirmed) text += " " + a.to_string();
        }
        if (confirmed.empty() && unconfirmed.empty()) text += ": no component answered";
        pages().event(confirmed.empty() || !unconfirmed.empty() ? EventLevel::error : EventLevel::info, text);
      }));
  command.start();
}

template <class M>
void EmergencyPanel::send_must_arrive(const jaus::Address& to, const M& message, const std::string& what) {
  std::vector<std::uint8_t> payload(jaus::kMaxPayloadSize);
  const auto size = jaus::wire::encode_payload(message, payload);
  if (!size) return;
  payload.resize(*size);
  jaus::Header header;
  header.command_code = M::code;
  header.priority = M::code == jaus::msg::SetEmergency::code ? jaus::priority::kSafetyCritical : jaus::priority::kDefault;
  header.destination = to;
  header.source = session().self();
  header.data_size = static_cast<std::uint16_t>(payload.size());
  if (to.is_broadcast()) return send_to_every_member(to, header, std::move(payload), what);
  std::weak_ptr<int> alive = alive_;
  // Set Emergency keeps trying harder than Clear Emergency, both at the pace
  // of the measured round trip, as the session's settings say (jaus-console's
  // --stop-give-up-after and the like; jaus/ocu/must_arrive.hpp).
  const auto policy = jaus::ocu::MustArrivePolicy::for_code(M::code, session().options().must_arrive);
  session().node().send_acknowledged(
      header, payload, policy, [this, alive, what](const jaus::node::AckResolution& resolution) {
        if (alive.expired()) return;
        const bool arrived = resolution.outcome == jaus::node::AckOutcome::acknowledged;
        pages().event(arrived ? EventLevel::info : EventLevel::error,
                      what + ": " + std::string(jaus::node::to_string(resolution.outcome)) + " after " +
                          std::to_string(resolution.transmissions) + " transmission(s)");
      });
}

void EmergencyPanel::on_frame(PageId page, const EmergencyFrame& frame) {
  const auto& target = frame.target;
  const std::string who = target.is_broadcast() ? std::string("all") : target.to_string();
  if (frame.set) {
    send_must_arrive(target, jaus::msg::SetEmergency{{1}}, "Set Emergency to " + who);
    emergencies_[target] = true;
    pages().to_all(EmergencyStateFrame{target, true, {session().self()}});
    pages().event(EventLevel::warn, "emergency set on " + who + " (page " + std::to_string(page) + ")");
    // Nothing drives into an emergency: stop what this console drives there.
    drive_.stop_reached_by(target, "emergency");
    return;
  }
  send_must_arrive(target, jaus::msg::ClearEmergency{{1}}, "Clear Emergency to " + who);
  emergencies_.erase(target);
  pages().to_all(EmergencyStateFrame{target, false, {}});
  pages().event(EventLevel::info,
                "emergency cleared on " + who + " by this console (page " + std::to_string(page) + ")");
}

}  // namespace jaus::console
