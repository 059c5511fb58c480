// Communications subgroup: 0x0200-0x03FF, 0x2200-0x23FF, 0x4200-0x43FF.
#pragma once

#include "jaus/messages/common.hpp"

namespace jaus::msg {

// Data link states (Set: 0 off, 1 on, 2 standby; Report adds 3 loss of command).
inline constexpr auto kSetDataLinkState = wire::enum_of<std::uint8_t>({{0, "off"}, {1, "on"}, {2, "standby"}});
inline constexpr auto kDataLinkState =
    wire::enum_of<std::uint8_t>({{0, "off"}, {1, "on"}, {2, "standby"}, {3, "loss_of_command"}});

struct DataLinkStateBody {
  std::uint8_t state = 0;
  bool operator==(const DataLinkStateBody&) const = default;
  static constexpr auto describe() {
    return std::make_tuple(wire::field("state", &DataLinkStateBody::state, kSetDataLinkState));
  }
};

struct DataLinkIdBody {
  std::uint8_t data_link_id = 0;
  bool operator==(const DataLinkIdBody&) const = default;
  static constexpr auto describe() {
    return std::make_tuple(wire::field("data_link_id", &DataLinkIdBody::data_link_id, Byte{}));
  }
};

struct DataLinkStatusBody {
  std::uint8_t data_link_id = 0;
  std::uint8_t state = 0;
  bool operator==(const DataLinkStatusBody&) const = default;
  static constexpr auto describe() {
    return std::make_tuple(wire::field("data_link_id", &DataLinkStatusBody::data_link_id, Byte{}),
                           wire::field("state", &DataLinkStatusBody::state, kDataLinkState));
  }
};

using SetDataLinkStatus = Message<0x0200, "Set Data Link Status", DataLinkStateBody>;
using SetDataLinkSelect = Message<0x0201, "Set Data Link Select", DataLinkIdBody>;
using QueryDataLinkStatus = Message<0x2200, "Query Data Link Status", DataLinkIdBody>;
using QuerySelectedDataLinkStatus = Message<0x2201, "Query Selected Data Link Status", Empty>;
using QueryHeartbeatPulse = Message<0x2202, "Query Heartbeat Pulse", Empty>;
using ReportDataLinkStatus = Message<0x4200, "Report Data Link Status", DataLinkStatusBody>;
using ReportSelectedDataLinkStatus = Message<0x4201, "Report Selected Data Link Status", DataLinkIdBody>;
using ReportHeartbeatPulse = Message<0x4202, "Report Heartbeat Pulse", Empty>;

using CommunicationsMessages =
    TypeList<SetDataLinkStatus, SetDataLinkSelect, QueryDataLinkStatus, QuerySelectedDataLinkStatus,
             QueryHeartbeatPulse, ReportDataLinkStatus, ReportSelectedDataLinkStatus, ReportHeartbeatPulse>;

}  // namespace jaus::msg
