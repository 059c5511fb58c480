// JSS Discovery v1.1 (docs/jss.md, "Discovery"): services are URIs with versions,
// not RA message codes; subsystem IDs are u16; components carry an instance
// byte only for legacy RA components (0 otherwise).
#pragma once

#include "jaus/jss/messages/common.hpp"

namespace jaus::jss::msg {

using jaus::msg::kIdentificationType;
namespace identification = jaus::msg::identification;  // kSystem, kSubsystem, kNode, kComponent

// Report Identification type.
namespace identification_type {
inline constexpr std::uint16_t kVehicle = 10001;
inline constexpr std::uint16_t kOcu = 20001;
inline constexpr std::uint16_t kOtherSubsystem = 30001;
inline constexpr std::uint16_t kNode = 40001;
inline constexpr std::uint16_t kPayload = 50001;
inline constexpr std::uint16_t kComponent = 60001;
}  // namespace identification_type
inline constexpr auto kJssIdentificationType =
    wire::enum_of<std::uint16_t>({{identification_type::kVehicle, "vehicle"},
                                  {identification_type::kOcu, "ocu"},
                                  {identification_type::kOtherSubsystem, "other_subsystem"},
                                  {identification_type::kNode, "node"},
                                  {identification_type::kPayload, "payload"},
                                  {identification_type::kComponent, "component"}});

struct ReportIdentificationBody {
  std::uint8_t query_type = identification::kSubsystem;  // echoes the query
  std::uint16_t type = identification_type::kVehicle;
  std::string identification;  // up to 255 characters
  bool operator==(const ReportIdentificationBody&) const = default;
  static constexpr auto describe() {
    using B = ReportIdentificationBody;
    return std::make_tuple(wire::field("query_type", &B::query_type, kIdentificationType),
                           wire::field("type", &B::type, kJssIdentificationType),
                           wire::field("identification", &B::identification, codec::Str8{}));
  }
};

// A service: URI and version (docs/jss.md, "What is supported").
struct ServiceRecord {
  std::string uri;  // "urn:jaus:jss:mobility:PrimitiveDriver"
  std::uint8_t major_version = 1;
  std::uint8_t minor_version = 0;
  bool operator==(const ServiceRecord&) const = default;
  static constexpr auto describe() {
    using B = ServiceRecord;
    return std::make_tuple(wire::field("uri", &B::uri, codec::Str8{}),
                           wire::field("major_version", &B::major_version, Byte{}),
                           wire::field("minor_version", &B::minor_version, Byte{}));
  }
};
using ServiceRecords = wire::Records<wire::Prefix<std::uint8_t>, ServiceRecord>;

struct RegisterServicesBody {
  std::vector<ServiceRecord> services;
  bool operator==(const RegisterServicesBody&) const = default;
  static constexpr auto describe() {
    return std::make_tuple(wire::field("services", &RegisterServicesBody::services, ServiceRecords{}));
  }
};

// Report Configuration.
struct ConfigurationComponent {
  std::uint8_t component_id = 0;
  std::uint8_t instance_id = 0;  // 0: a JSS component (legacy RA components only carry one)
  bool operator==(const ConfigurationComponent&) const = default;
  static constexpr auto describe() {
    using B = ConfigurationComponent;
    return std::make_tuple(wire::field("component_id", &B::component_id, Byte{}),
                           wire::field("instance_id", &B::instance_id, Byte{}));
  }
};
struct ConfigurationNode {
  std::uint8_t node_id = 0;
  std::vector<ConfigurationComponent> components;
  bool operator==(const ConfigurationNode&) const = default;
  static constexpr auto describe() {
    using B = ConfigurationNode;
    return std::make_tuple(
        wire::field("node_id", &B::node_id, Byte{}),
        wire::field("components", &B::components, wire::Records<wire::Prefix<std::uint8_t>, ConfigurationComponent>{}));
  }
};
struct ReportConfigurationBody {
  std::vector<ConfigurationNode> nodes;
  bool operator==(const ReportConfigurationBody&) const = default;
  static constexpr auto describe() {
    return std::make_tuple(wire::field("nodes", &ReportConfigurationBody::nodes,
                                       wire::Records<wire::Prefix<std::uint8_t>, ConfigurationNode>{}));
  }
};

// Report Subsystem List: per subsystem, the component to send Query Configuration to.
struct ReportSubsystemListBody {
  std::vector<JssId> subsystems;
  bool operator==(const ReportSubsystemListBody&) const = default;
  static constexpr auto describe() {
    return std::make_tuple(wire::field("subsystems", &ReportSubsystemListBody::subsystems,
                                       wire::Array<wire::Prefix<std::uint8_t>, codec::IdCodec>{}));
  }
};

// Query Services: nodes and their components to report (255 = all; an
// empty node list, as IOP's fallback sends, means all too).
struct QueryServicesNode {
  std::uint8_t node_id = JssId::kAll;
  std::vector<std::uint8_t> component_ids;
  bool operator==(const QueryServicesNode&) const = default;
  static constexpr auto describe() {
    using B = QueryServicesNode;
    return std::make_tuple(wire::field("node_id", &B::node_id, Byte{}),
                           wire::field("component_ids", &B::component_ids,
                                       wire::Array<wire::Prefix<std::uint8_t>, Byte>{}));
  }
};
struct QueryServicesBody {
  std::vector<QueryServicesNode> nodes;
  bool operator==(const QueryServicesBody&) const = default;
  static constexpr auto describe() {
    return std::make_tuple(wire::field("nodes", &QueryServicesBody::nodes,
                                       wire::Records<wire::Prefix<std::uint8_t>, QueryServicesNode>{}));
  }
};

// Report Services (and the inner levels of Report Service List).
struct ServicesComponent {
  std::uint8_t component_id = 0;
  std::uint8_t instance_id = 0;
  std::vector<ServiceRecord> services;
  bool operator==(const ServicesComponent&) const = default;
  static constexpr auto describe() {
    using B = ServicesComponent;
    return std::make_tuple(wire::field("component_id", &B::component_id, Byte{}),
                           wire::field("instance_id", &B::instance_id, Byte{}),
                           wire::field("services", &B::services, ServiceRecords{}));
  }
};
struct ServicesNode {
  std::uint8_t node_id = 0;
  std::vector<ServicesComponent> components;
  bool operator==(const ServicesNode&) const = default;
  static constexpr auto describe() {
    using B = ServicesNode;
    return std::make_tuple(
        wire::field("node_id", &B::node_id, Byte{}),
        wire::field("components", &B::components, wire::Records<wire::Prefix<std::uint8_t>, ServicesComponent>{}));
  }
};
using ServicesNodes = wire::Records<wire::Prefix<std::uint8_t>, ServicesNode>;
struct ReportServicesBody {
  std::vector<ServicesNode> nodes;
  bool operator==(const ReportServicesBody&) const = default;
  static constexpr auto describe() {
    return std::make_tuple(wire::field("nodes", &ReportServicesBody::nodes, ServicesNodes{}));
  }
};

// Query Service List (v1.1): subsystems (65535 = all), nodes (255 = all),
// components (255 = all) with an optional URI search filter.
struct ServiceListQueryComponent {
  std::uint8_t component_id = JssId::kAll;
  std::optional<std::string> search_filter;
  bool operator==(const ServiceListQueryComponent&) const = default;
  static constexpr auto describe() {
    using B = ServiceListQueryComponent;
    return std::make_tuple(wire::presence_vector<std::uint8_t>(),
                           wire::field("component_id", &B::component_id, Byte{}),
                           wire::optional(0, "search_filter", &B::search_filter, codec::Str8{}));
  }
};
struct ServiceListQueryNode {
  std::uint8_t node_id = JssId::kAll;
  std::vector<ServiceListQueryComponent> components;
  bool operator==(const ServiceListQueryNode&) const = default;
  static constexpr auto describe() {
    using B = ServiceListQueryNode;
    return std::make_tuple(
        wire::field("node_id", &B::node_id, Byte{}),
        wire::field("components", &B::components,
                    wire::Records<wire::Prefix<std::uint8_t>, ServiceListQueryComponent>{}));
  }
};
struct ServiceListQuerySubsystem {
  std::uint16_t subsystem_id = JssId::kAllSubsystems;
  std::vector<ServiceListQueryNode> nodes;
  bool operator==(const ServiceListQuerySubsystem&) const = default;
  static constexpr auto describe() {
    using B = ServiceListQuerySubsystem;
    return std::make_tuple(
        wire::field("subsystem_id", &B::subsystem_id, UShort{}),
        wire::field("nodes", &B::nodes, wire::Records<wire::Prefix<std::uint8_t>, ServiceListQueryNode>{}));
  }
};
struct QueryServiceListBody {
  std::vector<ServiceListQuerySubsystem> subsystems;
  bool operator==(const QueryServiceListBody&) const = default;
  static constexpr auto describe() {
    return std::make_tuple(wire::field("subsystems", &QueryServiceListBody::subsystems,
                                       wire::Records<wire::Prefix<std::uint16_t>, ServiceListQuerySubsystem>{}));
  }
};

// Report Service List (v1.1): Report Services' nodes, per subsystem.
struct ServiceListSubsystem {
  std::uint16_t subsystem_id = 0;
  std::vector<ServicesNode> nodes;
  bool operator==(const ServiceListSubsystem&) const = default;
  static constexpr auto describe() {
    using B = ServiceListSubsystem;
    return std::make_tuple(wire::field("subsystem_id", &B::subsystem_id, UShort{}),
                           wire::field("nodes", &B::nodes, ServicesNodes{}));
  }
};
struct ReportServiceListBody {
  std::vector<ServiceListSubsystem> subsystems;
  bool operator==(const ReportServiceListBody&) const = default;
  static constexpr auto describe() {
    return std::make_tuple(wire::field("subsystems", &ReportServiceListBody::subsystems,
                                       wire::Records<wire::Prefix<std::uint16_t>, ServiceListSubsystem>{}));
  }
};

using RegisterServices = Message<0x0B00, "Register Services", RegisterServicesBody>;
using jaus::msg::QueryIdentification;
using jaus::msg::QueryConfiguration;
using jaus::msg::QuerySubsystemList;
using QueryServices = Message<0x2B03, "Query Services", QueryServicesBody>;
using QueryServiceList = Message<0x2B04, "Query Service List", QueryServiceListBody>;
using ReportIdentification = Message<0x4B00, "Report Identification", ReportIdentificationBody>;
using ReportConfiguration = Message<0x4B01, "Report Configuration", ReportConfigurationBody>;
using ReportSubsystemList = Message<0x4B02, "Report Subsystem List", ReportSubsystemListBody>;
using ReportServices = Message<0x4B03, "Report Services", ReportServicesBody>;
using ReportServiceList = Message<0x4B04, "Report Service List", ReportServiceListBody>;

using DiscoveryMessages =
    TypeList<RegisterServices, QueryIdentification, QueryConfiguration, QuerySubsystemList, QueryServices,
             QueryServiceList, ReportIdentification, ReportConfiguration, ReportSubsystemList, ReportServices,
             ReportServiceList>;

}  // namespace jaus::jss::msg
