// Shared vocabulary of the JSS message descriptions (namespace jaus::jss::msg).
// JSS scaled integers are all unsigned (docs/jss.md, "Scaled values"): wire::Scaled with
// an unsigned type gives exactly their encoding (step (hi - lo) / (2^n - 1),
// bias lo, rounded; checked against that page's examples in
// tests/jss/codec). Where a JSS body is byte for byte an RA body (empty
// bodies, authority, emergency code, time, a query's presence vector), the RA
// body is reused: its codec is already compiled in jaus_core. A message whose
// code, name and body are the RA's is the RA's message type itself (a
// using-declaration, e.g. jss::msg::SetEmergency is msg::SetEmergency).
#pragma once

#include <cstdint>
#include <numbers>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include "jaus/jss/codecs.hpp"
#include "jaus/messages/core_messages.hpp"
#include "jaus/messages/discovery_messages.hpp"
#include "jaus/wire/message.hpp"
#include "jaus/wire/named_codecs.hpp"

namespace jaus::jss::msg {

using jaus::msg::TypeList;
using wire::Empty;
using wire::Message;
using wire::NamedValue;

using Byte = wire::Int<std::uint8_t>;
using UShort = wire::Int<std::uint16_t>;
using UInt = wire::Int<std::uint32_t>;

// RA bodies with the same bytes.
using jaus::msg::AuthorityBody;                        // u8 authority
using jaus::msg::EmergencyBody;                        // u16 emergency code, bit 0 stop
using jaus::msg::TimeBody;                             // PV u8, ?0 time stamp, ?1 date stamp
using QueryPresence8Body = jaus::msg::PresenceQueryBody<std::uint8_t>;
using QueryPresence16Body = jaus::msg::PresenceQueryBody<std::uint16_t>;
using jaus::msg::QueryConfigurationBody;               // u8 query field: 2 subsystem, 3 node
using jaus::msg::QueryIdentificationBody;              // u8 query type: 1 system ... 4 component

inline constexpr double kPi = std::numbers::pi;

// Scaled ranges JSS uses in several messages (all unsigned).
inline constexpr wire::Scaled<std::uint16_t> kEventRate{0, 1092};            // Hz
inline constexpr wire::Scaled<std::uint16_t> kAngle{-kPi, kPi};              // rad
inline constexpr wire::Scaled<std::uint16_t> kAttitudeRms{0, kPi};           // rad
inline constexpr wire::Scaled<std::uint32_t> kPositionRms{0, 100};           // m
inline constexpr wire::Scaled<std::uint32_t> kLocalXYZ{-100'000, 100'000};   // m
inline constexpr wire::Scaled<std::uint16_t> kTravelSpeed{0, 327.67};        // m/s

// Report Status (the same 0-5 as RA's primary status).
using jaus::msg::kComponentStates;

}  // namespace jaus::jss::msg
