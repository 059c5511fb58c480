// A component scripted on a memory network link (6.1.40.1) that never
// checks a payload, the flaw the robustness cases look for: it
// answers Query Identification with or without its query type, acts on a
// Set Emergency of any size, and answers any message it does not know with
// Report Component Status. Otherwise it answers what learn_component() and
// the cases ask (identification, services, status) and keeps its emergency
// until a Clear Emergency.
#pragma once

#include "scripted_memory_peer.hpp"

namespace jaus::conform::test {

class LenientPeer final : public test_support::ScriptedMemoryPeer {
 public:
  static constexpr Address kAddress{6, 1, 40, 1};

  LenientPeer(rt::VirtualTime& time, testing::MemoryNetwork& network)
      : ScriptedMemoryPeer(time, network, kAddress.subsystem, kAddress.node) {}

 private:
  void on_packet(const Header& h, std::span<const std::uint8_t>) override {
    if (!h.destination.matches(kAddress)) return;
    using namespace msg;
    switch (h.command_code) {
      case QueryIdentification::code:  // the flaw: its query type is never read
        return reply(kAddress, h.source, ReportIdentification{{identification::kComponent, 0, 0, "lenient"}});
      case QueryServices::code: {
        ReportServices services;
        ServiceEntry core;
        for (const std::uint16_t code : {QueryIdentification::code, QueryComponentStatus::code, SetEmergency::code,
                                         ClearEmergency::code})
          core.inputs.push_back({code, 0});
        services.services.push_back(core);
        return reply(kAddress, h.source, services);
      }
      case QueryComponentStatus::code: {
        const auto state = emergency_ ? PrimaryStatus::emergency : PrimaryStatus::ready;
        return reply(kAddress, h.source, ReportComponentStatus{{static_cast<std::uint8_t>(state), 0}});
      }
      case SetEmergency::code:  // the flaw: acted on whatever its size
        emergency_ = true;
        return;
      case ClearEmergency::code:
        emergency_ = false;
        return;
      case ReportHeartbeatPulse::code:
        return;
      default:  // the flaw: anything else is answered as if understood
        return reply(kAddress, h.source, ReportComponentStatus{{static_cast<std::uint8_t>(PrimaryStatus::ready), 0}});
    }
  }

  bool emergency_ = false;
};

}  // namespace jaus::conform::test
