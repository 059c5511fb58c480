// What the scenarios do with the in-process OCU: a component's status asked
// until an answer gets through a lossy link, control requested the same way,
// Set Wrench Effort prepared, and percentiles of measured times.
#pragma once

#include <algorithm>
#include <cmath>
#include <chrono>
#include <optional>
#include <vector>

#include "jaus/messages/all.hpp"
#include "jaus/ocu/control_hold.hpp"
#include "jaus/ocu/message_json.hpp"
#include "jaus/ocu/session.hpp"

namespace jaus::test::network {

// The primary status (bits 0-3), asked up to `tries` times `wait` apart.
inline std::optional<jaus::msg::PrimaryStatus> primary_status(jaus::ocu::OcuSession& session, const jaus::Address& of,
                                                              int tries = 10,
                                                              jaus::rt::Duration wait = std::chrono::milliseconds(300)) {
  for (int i = 0; i < tries; ++i) {
    auto reply = session.request(of, jaus::msg::QueryComponentStatus{}, {jaus::msg::ReportComponentStatus::code}, wait);
    if (!reply) continue;
    jaus::msg::ReportComponentStatus report{};
    if (!jaus::wire::decode_payload_into(reply->payload, report, jaus::wire::Dialect::ra, jaus::kHeaderSize)) continue;
    return static_cast<jaus::msg::PrimaryStatus>(report.primary_status & 0x0F);
  }
  return std::nullopt;
}

// Waits (running the session) until `of` reports `status`.
inline bool wait_for_primary_status(jaus::ocu::OcuSession& session, const jaus::Address& of,
                                    jaus::msg::PrimaryStatus status, std::chrono::milliseconds deadline) {
  const auto until = std::chrono::steady_clock::now() + deadline;
  while (std::chrono::steady_clock::now() < until) {
    if (primary_status(session, of, 1) == status) return true;
    session.run_for(std::chrono::milliseconds(50));
  }
  return false;
}

// Request Component Control until granted (a request or its confirmation may be lost), at most `tries` times.
inline bool take_control(jaus::ocu::ControlHold& hold, int tries = 10) {
  for (int i = 0; i < tries; ++i) {
    const auto r = hold.request(std::chrono::seconds(1));
    if (r.outcome == jaus::ocu::ControlHold::Outcome::granted) return true;
    if (r.outcome != jaus::ocu::ControlHold::Outcome::no_reply) return false;
  }
  return false;
}

inline jaus::ocu::PreparedMessage wrench_effort(int forward_percent) {
  const jaus::ocu::Json message{{"name", "Set Wrench Effort"},
                                {"fields", {{"propulsive_linear_effort_x_percent", forward_percent}}}};
  return *jaus::ocu::prepare_message(message, jaus::wire::Dialect::ra);
}

inline double milliseconds(jaus::rt::Duration d) { return std::chrono::duration<double, std::milli>(d).count(); }

// The p-th percentile (0..100) of `values`, nearest rank.
inline double percentile(std::vector<double> values, double p) {
  if (values.empty()) return 0;
  std::sort(values.begin(), values.end());
  const auto rank = static_cast<std::size_t>(std::max(1.0, std::ceil(p / 100.0 * static_cast<double>(values.size()))));
  return values[std::min(rank, values.size()) - 1];
}

}  // namespace jaus::test::network
