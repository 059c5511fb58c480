// RA 3.2/3.3 dynamic configuration (discovery): 0x2B00-0x2B03, 0x4B00-0x4B03.
// Layouts: docs/wire-format.md, "Liveness and discovery".
#pragma once

#include "jaus/messages/common.hpp"

namespace jaus::msg {

// Query Identification type / Report Identification query type.
namespace identification {
inline constexpr std::uint8_t kSystem = 1;
inline constexpr std::uint8_t kSubsystem = 2;
inline constexpr std::uint8_t kNode = 3;
inline constexpr std::uint8_t kComponent = 4;
}  // namespace identification
inline constexpr auto kIdentificationType = wire::enum_of<std::uint8_t>({{identification::kSystem, "system"},
                                                                         {identification::kSubsystem, "subsystem"},
                                                                         {identification::kNode, "node"},
                                                                         {identification::kComponent, "component"}});
// Query Configuration asks for a subsystem's or a node's configuration.
inline constexpr auto kConfigurationField =
    wire::enum_of<std::uint8_t>({{identification::kSubsystem, "subsystem"}, {identification::kNode, "node"}});

struct QueryIdentificationBody {
  std::uint8_t query_type = identification::kSubsystem;
  bool operator==(const QueryIdentificationBody&) const = default;
  static constexpr auto describe() {
    return std::make_tuple(wire::field("query_type", &QueryIdentificationBody::query_type, kIdentificationType));
  }
};

// type: 10001+ vehicle, 20001+ OCU, 30001+ other subsystem, 40001+ node, 50001+ payload.
struct IdentificationBody {
  std::uint8_t query_type = identification::kSubsystem;
  std::uint8_t authority = 0;
  std::uint16_t type = 0;
  std::string identification;  // sent as 80 bytes NUL padded; shorter accepted
  bool operator==(const IdentificationBody&) const = default;
  static constexpr auto describe() {
    using B = IdentificationBody;
    return std::make_tuple(wire::field("query_type", &B::query_type, kIdentificationType),
                           wire::field("authority", &B::authority, Byte{}), wire::field("type", &B::type, UShort{}),
                           wire::field("identification", &B::identification, wire::Text<80, true>{}));
  }
};

// Query Configuration field: 2 subsystem, 3 node.
struct QueryConfigurationBody {
  std::uint8_t query_field = identification::kSubsystem;
  bool operator==(const QueryConfigurationBody&) const = default;
  static constexpr auto describe() {
    return std::make_tuple(wire::field("query_field", &QueryConfigurationBody::query_field, kConfigurationField));
  }
};

struct ComponentEntry {
  std::uint8_t component_id = 0;
  std::uint8_t instance = 1;
  bool operator==(const ComponentEntry&) const = default;
  static constexpr auto describe() {
    return std::make_tuple(wire::field("component_id", &ComponentEntry::component_id, Byte{}),
                           wire::field("instance", &ComponentEntry::instance, Byte{}));
  }
};

struct NodeEntry {
  std::uint8_t node_id = 0;
  std::vector<ComponentEntry> components;
  bool operator==(const NodeEntry&) const = default;
  static constexpr auto describe() {
    return std::make_tuple(
        wire::field("node_id", &NodeEntry::node_id, Byte{}),
        wire::field("components", &NodeEntry::components, wire::Records<wire::Prefix<std::uint8_t>, ComponentEntry>{}));
  }
};

struct ConfigurationBody {
  std::vector<NodeEntry> nodes;
  bool operator==(const ConfigurationBody&) const = default;
  static constexpr auto describe() {
    return std::make_tuple(
        wire::field("nodes", &ConfigurationBody::nodes, wire::Records<wire::Prefix<std::uint8_t>, NodeEntry>{}));
  }
};

struct SubsystemListBody {
  std::vector<Address> subsystems;  // one address per known subsystem
  bool operator==(const SubsystemListBody&) const = default;
  static constexpr auto describe() {
    return std::make_tuple(
        wire::field("subsystems", &SubsystemListBody::subsystems,
                    wire::Array<wire::Prefix<std::uint8_t>, wire::AddressCodec>{}));
  }
};

struct ServiceMessageEntry {
  std::uint16_t command_code = 0;
  std::uint32_t presence_vector = 0;
  bool operator==(const ServiceMessageEntry&) const = default;
  static constexpr auto describe() {
    return std::make_tuple(wire::field("command_code", &ServiceMessageEntry::command_code, UShort{}),
                           wire::field("presence_vector", &ServiceMessageEntry::presence_vector, UInt{}));
  }
};

struct ServiceEntry {
  std::uint16_t type = 0;  // component ID, 0 = core service
  std::vector<ServiceMessageEntry> inputs;
  std::vector<ServiceMessageEntry> outputs;
  bool operator==(const ServiceEntry&) const = default;
  static constexpr auto describe() {
    using Messages = wire::Records<wire::Prefix<std::uint8_t>, ServiceMessageEntry>;
    return std::make_tuple(wire::field("type", &ServiceEntry::type, UShort{}),
                           wire::field("inputs", &ServiceEntry::inputs, Messages{}),
                           wire::field("outputs", &ServiceEntry::outputs, Messages{}));
  }
};

struct ServicesBody {
  std::vector<ServiceEntry> services;
  bool operator==(const ServicesBody&) const = default;
  static constexpr auto describe() {
    return std::make_tuple(
        wire::field("services", &ServicesBody::services, wire::Records<wire::Prefix<std::uint8_t>, ServiceEntry>{}));
  }
};

using QueryIdentification = Message<0x2B00, "Query Identification", QueryIdentificationBody>;
using QueryConfiguration = Message<0x2B01, "Query Configuration", QueryConfigurationBody>;
using QuerySubsystemList = Message<0x2B02, "Query Subsystem List", Empty>;
using QueryServices = Message<0x2B03, "Query Services", Empty>;
using ReportIdentification = Message<0x4B00, "Report Identification", IdentificationBody>;
using ReportConfiguration = Message<0x4B01, "Report Configuration", ConfigurationBody>;
using ReportSubsystemList = Message<0x4B02, "Report Subsystem List", SubsystemListBody>;
using ReportServices = Message<0x4B03, "Report Services", ServicesBody>;

using DiscoveryMessages = TypeList<QueryIdentification, QueryConfiguration, QuerySubsystemList, QueryServices,
                                   ReportIdentification, ReportConfiguration, ReportSubsystemList, ReportServices>;

}  // namespace jaus::msg
