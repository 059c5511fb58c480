// What the configuration reader (config_file.cpp) and the validation
// (jausd_config.cpp) share: the ranges a value must be in, where the file
// declared what (for errors that span keys), and the check of a whole
// configuration. Private to apps/jausd.
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "config_reader.hpp"
#include "jausd_config.hpp"

namespace jausd::config_rules {

using yaml_reader::NumberRange;

// Ranges shared by the file reader (which reports the line) and validate().
inline constexpr long long kAddressMin = 1, kAddressMax = 254;  // subsystem, node, component ID, instance
inline constexpr std::size_t kMaxIdentification = 80;           // Report Identification carries 80 bytes
inline constexpr double kMaxSeconds = 86400;                     // keeps every duration representable
inline constexpr std::size_t kMaxConnectionsLimit = 255;
inline constexpr std::size_t kMaxPeersLimit = 65535;
// The unverified endpoints' budgets (bytes, bytes a second): up to 1 MiB per
// endpoint, 16 MiB all together; 0 allows nothing beyond what they sent.
inline constexpr long long kMaxUnverifiedBytes = 1 << 20;
inline constexpr long long kMaxUnverifiedTotalBytes = 16 << 20;
// The send budget: a radio of 16 kbit/s to 10 Gbit/s (0: none); each class
// of what waits holds 8 KiB (two full packets) to 64 MiB.
inline constexpr long long kMinSendRateKbit = 16, kMaxSendRateKbit = 10'000'000;
inline constexpr long long kMinSendQueueBytes = 8192, kMaxSendQueueBytes = 64 << 20;
// SO_RCVBUF asked of the sockets: 0 (the system's default) to 256 MiB.
inline constexpr long long kMaxReceiveBufferBytes = 256 << 20;
// 254 subsystems x 254 nodes x a few components is the most JAUS IDs name;
// the floor leaves room for this node's own peers and one OCU.
inline constexpr std::size_t kMinLivenessEntries = 16;
inline constexpr std::size_t kMaxLivenessEntries = 1u << 20;

inline constexpr std::array<std::string_view, 4> kLogLevels{"debug", "info", "warn", "error"};
inline constexpr std::array<std::string_view, 2> kDialects{"ra", "openjaus"};
inline constexpr std::array<std::string_view, 2> kFramings{"opc", "judp"};
inline constexpr std::array<std::string_view, 2> kEmergencyScopes{"vehicle", "component"};

inline constexpr NumberRange kHeartbeatRange{0, false, 100, "a number > 0 and <= 100"};
// The simulated vehicle: each range is what the reports can encode or what keeps the model sane.
inline constexpr NumberRange kSpeedRange{0, false, 65.534, "a number > 0 and <= 65.534"};
inline constexpr NumberRange kYawRateRange{0, false, 32.767, "a number > 0 and <= 32.767"};
inline constexpr NumberRange kSteeringRange{0, false, 1.5, "a number > 0 and <= 1.5"};
inline constexpr NumberRange kLengthRange{0, false, 65.535, "a number > 0 and <= 65.535"};
inline constexpr NumberRange kAccelerationRange{0, false, 100, "a number > 0 and <= 100"};
inline constexpr NumberRange kUpdateRateRange{0, false, 1000, "a number > 0 and <= 1000"};
inline constexpr NumberRange kAccuracyRange{0, true, 100, "a number 0..100"};
inline constexpr NumberRange kPercentRange{0, true, 100, "a number 0..100"};
inline constexpr NumberRange kLatitudeRange{-90, true, 90, "a number -90..90"};
inline constexpr NumberRange kLongitudeRange{-180, true, 180, "a number -180..180"};
inline constexpr NumberRange kAltitudeRange{-10000, true, 35000, "a number -10000..35000"};
inline constexpr NumberRange kHeadingRange{-360, true, 360, "a number of degrees -360..360"};
inline constexpr std::array<std::string_view, 2> kSteerings{"differential", "ackermann"};
inline constexpr std::size_t kMaxPlatformName = 15;  // Report Platform Specifications' name field
inline constexpr NumberRange kTimeoutRange{0, true, kMaxSeconds, "a number of seconds 0..86400"};
inline constexpr NumberRange kPositiveTimeoutRange{0, false, kMaxSeconds, "a number of seconds > 0 and <= 86400"};
inline constexpr NumberRange kRateRange{0, false, 1092, "a number > 0 and <= 1092"};
inline constexpr NumberRange kTotalRateRange{0, false, 1'000'000, "a number > 0 and <= 1000000"};
inline constexpr NumberRange kDeadmanPeriodsRange{1, true, 1000, "a number 1..1000"};
// The JSS face: subsystem IDs are 16-bit there (65535 = all); event IDs and
// alias slots are 8-bit; AS5669A peers take up to 4079 contents bytes a packet.
inline constexpr long long kJssSubsystemMax = 65534;
inline constexpr long long kMaxJssClients = 254;
inline constexpr long long kMaxJssEvents = 65535;
inline constexpr long long kMaxJssEventsPerClient = 255;
inline constexpr long long kMinPacketContents = 64, kMaxPacketContents = 4079;
inline constexpr NumberRange kPollPeriodRange{0.01, true, 10, "a number of seconds 0.01..10"};

// Empty when `text` is a valid identification string, else what is wrong.
std::string identification_problem(std::string_view key, std::string_view text);

struct Issue {
  int line = 0;
  std::string what;
};

// Lines of what the file declared, for cross-field errors (0 = unknown).
struct SourceLines {
  int control = 0;          // the 'control' key
  int service_connections = 0;  // the 'service_connections' key
  int components = 0;       // the 'components' key
  int cameras = 0;          // the 'cameras' key
  int manipulator = 0;      // the 'manipulator' key
  int platform = 0;         // the 'platform' key
  int clearpath = 0;        // the 'clearpath' key
  std::vector<int> peers;   // one per transport.peers entry
  int jss = 0;              // the 'jss' key
};

// The first thing wrong with `c`: its line when `lines` knows it (0: none).
std::optional<Issue> check(const JausdConfig& c, const SourceLines& lines);

}  // namespace jausd::config_rules
