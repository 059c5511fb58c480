// The mobility services of the JSS face (AS6009 mobility v1.0, docs/jss.md
// "Mobility services"), one translator per file: each turns its JSS messages into the RA
// component's messages, sent as the client's alias, and the component's
// reports back into JSS. mobility_translators() (builtin_translators.hpp)
// registers them all; the factories and the pure conversions are declared
// here for it and for the tests.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>

#include "jaus/core/component_ids.hpp"
#include "jaus/jss/all.hpp"
#include "jaus/jss_face/translator.hpp"
#include "jaus/messages/all.hpp"

namespace jaus::jss_face {

std::unique_ptr<ServiceTranslator> make_primitive_driver_translator();
std::unique_ptr<ServiceTranslator> make_velocity_state_translator();
std::unique_ptr<ServiceTranslator> make_local_pose_translator();
std::unique_ptr<ServiceTranslator> make_global_pose_translator();

// JSS Set Wrench Effort as RA takes it: the six propulsive efforts rescaled,
// within one JSS step of 0 exactly 0; resistive efforts and presence copied.
msg::SetWrenchEffort wrench_effort_to_ra(const jss::msg::SetWrenchEffort& jss);
// A JSS local waypoint as RA waypoint `number`: X, Y, angles with JSS's
// near-zero made 0, Z clamped to RA's -10 km..35 km; the tolerances stay in
// the face (RA has none).
msg::SetLocalWaypoint local_waypoint_to_ra(const jss::msg::SetLocalWaypoint& jss, std::uint16_t number);

}  // namespace jaus::jss_face
