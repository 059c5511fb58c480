// What the catalogue says of each JSS message beyond its layout: the service
// that defines it (docs/jss.md, "What is supported") and one sentence of what it does.
// A test checks that every described message has its line here and back.
#pragma once

#include <cstdint>
#include <string_view>

namespace jaus::jss::detail {

struct MessageNote {
  std::uint16_t id;
  std::string_view service_uri;
  std::string_view summary;
};

inline constexpr std::string_view kAccessControl = "urn:jaus:jss:core:AccessControl";
inline constexpr std::string_view kManagement = "urn:jaus:jss:core:Management";
inline constexpr std::string_view kTime = "urn:jaus:jss:core:Time";
inline constexpr std::string_view kLiveness = "urn:jaus:jss:core:Liveness";
inline constexpr std::string_view kEvents = "urn:jaus:jss:core:Events";
inline constexpr std::string_view kDiscovery = "urn:jaus:jss:core:Discovery";
inline constexpr std::string_view kPrimitiveDriver = "urn:jaus:jss:mobility:PrimitiveDriver";
inline constexpr std::string_view kVelocityStateSensor = "urn:jaus:jss:mobility:VelocityStateSensor";
inline constexpr std::string_view kLocalPoseSensor = "urn:jaus:jss:mobility:LocalPoseSensor";
inline constexpr std::string_view kGlobalPoseSensor = "urn:jaus:jss:mobility:GlobalPoseSensor";
inline constexpr std::string_view kLocalWaypointDriver = "urn:jaus:jss:mobility:LocalWaypointDriver";
inline constexpr std::string_view kListManager = "urn:jaus:jss:mobility:ListManager";
inline constexpr std::string_view kLocalWaypointListDriver = "urn:jaus:jss:mobility:LocalWaypointListDriver";

inline constexpr MessageNote kMessageNotes[] = {
    {0x0001, kAccessControl, "The controller lowers or raises the component's current authority (default <= value <= its own)."},
    {0x0002, kManagement, "The controller shuts the component down (final)."},
    {0x0003, kManagement, "The controller puts the component in Standby."},
    {0x0004, kManagement, "The controller takes the component from Standby to Ready."},
    {0x0005, kManagement, "The controller resets the component (Init, then Standby); control is released."},
    {0x0006, kManagement, "Anyone stops the component (Emergency); only its sender clears it."},
    {0x0007, kManagement, "The sender of Set Emergency clears its emergency."},
    {0x000D, kAccessControl, "Asks for (or keeps, within the timeout) control at an authority."},
    {0x000E, kAccessControl, "The controller gives control up; answered by Reject Control 0."},
    {0x000F, kAccessControl, "Answers Request Control: accepted, not available or insufficient authority."},
    {0x0010, kAccessControl, "Control ended (released, preempted, timed out) or is not available."},
    {0x0011, kTime, "The controller sets the component's clock."},
    {0x01F0, kEvents, "Creates a periodic or every-change event on an embedded query."},
    {0x01F1, kEvents, "Changes an event (type, rate, query); restarts its timeout."},
    {0x01F2, kEvents, "Cancels an event."},
    {0x01F3, kEvents, "Confirms Create/Update/Cancel Event with the event ID and the rate used."},
    {0x01F4, kEvents, "Refuses Create/Update/Cancel Event, with a code and text."},
    {0x01F6, kEvents, "Asks for a command's result as an event (v1.1; refused here)."},
    {0x2001, kAccessControl, "Asks the current authority."},
    {0x2002, kManagement, "Asks the component's state."},
    {0x2003, kAccessControl, "Asks the control timeout."},
    {0x200D, kAccessControl, "Asks who controls the component."},
    {0x2011, kTime, "Asks the component's time and date."},
    {0x21F0, kEvents, "Asks the events by query message ID, type, event ID or all."},
    {0x21F2, kEvents, "Asks how long an event lives without Update Event (v1.1)."},
    {0x2202, kLiveness, "Asks for a heartbeat."},
    {0x2402, kGlobalPoseSensor, "Asks the global pose fields of the presence vector."},
    {0x2403, kLocalPoseSensor, "Asks the local pose fields of the presence vector."},
    {0x2404, kVelocityStateSensor, "Asks the velocity state fields of the presence vector."},
    {0x2405, kPrimitiveDriver, "Asks the wrench effort fields of the presence vector."},
    {0x240A, kLocalWaypointDriver, "Asks the travel speed."},
    {0x240D, kLocalWaypointDriver, "Asks the current waypoint's fields of the presence vector."},
    {0x2412, kGlobalPoseSensor, "Asks the magnetic variation."},
    {0x241A, kListManager, "Asks one list element by UID."},
    {0x241B, kListManager, "Asks the UIDs of the list's elements."},
    {0x241C, kListManager, "Asks how many elements the list has."},
    {0x241E, kLocalWaypointListDriver, "Asks the element being executed."},
    {0x2B00, kDiscovery, "Asks the identification of the system, subsystem, node or component."},
    {0x2B01, kDiscovery, "Asks the nodes and components of the subsystem or node."},
    {0x2B02, kDiscovery, "Asks the known subsystems."},
    {0x2B03, kDiscovery, "Asks the services of the listed nodes and components (255 or none: all)."},
    {0x2B04, kDiscovery, "Asks the services of subsystems, nodes and components, with URI filters (v1.1)."},
    {0x4001, kAccessControl, "The current authority."},
    {0x4002, kManagement, "The component's state (0 init ... 5 emergency)."},
    {0x4003, kAccessControl, "The control timeout in seconds (0: none)."},
    {0x400D, kAccessControl, "The controller's JSS ID (0.0.0: none) and authority."},
    {0x4011, kTime, "The component's time and date."},
    {0x41F0, kEvents, "The events asked for: type, ID and query."},
    {0x41F1, kEvents, "An event's report, embedded whole, with the event's sequence number."},
    {0x41F2, kEvents, "The event timeout in minutes (0: none)."},
    {0x41F6, kEvents, "A command event's result (v1.1)."},
    {0x4202, kLiveness, "A heartbeat."},
    {0x4402, kGlobalPoseSensor, "Latitude, longitude, altitude, attitude, their accuracy and time."},
    {0x4403, kLocalPoseSensor, "Position and attitude in the local frame, their accuracy and time."},
    {0x4404, kVelocityStateSensor, "Linear velocities and angular rates in the vehicle frame, accuracy and time."},
    {0x4405, kPrimitiveDriver, "The wrench effort being applied."},
    {0x440A, kLocalWaypointDriver, "The travel speed."},
    {0x440D, kLocalWaypointDriver, "The current waypoint."},
    {0x4412, kGlobalPoseSensor, "The magnetic variation."},
    {0x441A, kListManager, "One list element."},
    {0x441B, kListManager, "The UIDs of the list's elements."},
    {0x441C, kListManager, "How many elements the list has."},
    {0x441E, kLocalWaypointListDriver, "The element being executed (0: none)."},
    {0x4B00, kDiscovery, "Type and name of the system, subsystem, node or component asked."},
    {0x4B01, kDiscovery, "The nodes and components of the subsystem or node."},
    {0x4B02, kDiscovery, "The known subsystems, each with the component to ask for its configuration."},
    {0x4B03, kDiscovery, "The services (URI and version) of each node's components."},
    {0x4B04, kDiscovery, "The services (URI and version) per subsystem, node and component (v1.1)."},
    {0x0402, kGlobalPoseSensor, "The controller sets the global pose (redefines the frame)."},
    {0x0403, kLocalPoseSensor, "The controller sets the local pose (redefines the local frame)."},
    {0x0405, kPrimitiveDriver, "The controller commands propulsive and resistive effort (Ready only)."},
    {0x040A, kLocalWaypointDriver, "The controller sets the travel speed (Ready, with a waypoint)."},
    {0x040D, kLocalWaypointDriver, "The controller sets the one waypoint to drive to."},
    {0x0412, kGlobalPoseSensor, "The controller sets the magnetic variation."},
    {0x041A, kListManager, "The controller inserts or replaces list elements; confirmed or rejected."},
    {0x041B, kListManager, "The controller deletes list elements (65535: all); confirmed or rejected."},
    {0x041C, kListManager, "Confirms Set Element or Delete Element."},
    {0x041D, kListManager, "Rejects Set Element or Delete Element, with a code."},
    {0x041E, kLocalWaypointListDriver, "The controller starts the list at an element at a speed, or changes the speed."},
    {0x0B00, kDiscovery, "A component registers its services with the discovery service."},
};

}  // namespace jaus::jss::detail
