// What the pose and velocity sensors share: they read one PoseSource, answer
// their queries and feed their service connections from its newest sample,
// and watch it for staleness.
//
// Presence (Part 3, Query Global Pose / Local Pose / Velocity State): a
// report carries the fields the query (or the service connection) asks for
// AND that the component provides AND that the current sample has. A field the
// source lacks is absent, never filled in; the query's vector is never echoed.
//
// Staleness: until the first fresh sample the component stays in Initialize.
// Afterwards, when the newest sample is stale_after old or older, the
// component declares a failure (Ready or Standby -> Failure); once a fresh
// sample arrives it clears it (Failure -> the Ready or Standby it interrupted). While fresh, the watch wakes at
// the moment the newest sample would turn stale, so detection is exact; while
// stale, or while a declared failure waits to be cleared, it polls every
// stale_after / 4 (at least 10 ms). Every entry into Ready or Standby (end of
// initialisation, Resume, Clear Emergency), and a return from Emergency to the
// failure it interrupted, checks at once: the sensor is never Ready with a
// stale source, nor kept in Failure with a fresh one.
//
// Reports keep the newest sample's values with its own time stamp even when it
// is stale: the time stamp says how old it is, Report Component Status says
// Failure, and the last known pose of a vehicle whose source died is worth
// more to an operator than nothing.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <optional>

#include "jaus/components/pose_source.hpp"
#include "jaus/core/time_stamp.hpp"
#include "jaus/runtime/component.hpp"
#include "jaus/runtime/component_kind.hpp"

namespace jaus::components {

struct SensorOptions {
  // A sample this old (runtime clock, from PoseSample::taken_at) is stale.
  rt::Duration stale_after = std::chrono::seconds(1);
};
// The sensors' options as a configuration writes them: stale_after_s, a
// number of seconds > 0 and <= 60.
Expected<SensorOptions> sensor_options(const rt::KindOptions& options);

// The RA time stamp (UTC; milliseconds .. day of month) of a UTC time.
TimeStamp time_stamp_of(rt::UtcTime utc);

class SensorComponent : public rt::Component {
 public:
  SensorComponent(rt::ComponentConfig config, rt::Environment env, PoseSource& source, SensorOptions options);
  ~SensorComponent() override;

  const SensorOptions& sensor_options() const { return options_; }
  // The result of the last staleness check (true before the first).
  bool source_stale() const { return stale_; }

 protected:
  bool initialize() override;
  // Entering Ready or Standby checks the source at once (and starts the watch).
  void state_changed(rt::PrimaryStatus before, rt::PrimaryStatus after) override;

  PoseSource& source() { return source_; }

  // The fields of Report a source has, as its presence bits: those of its
  // current sample, made into a report by `build`; every field of Report while
  // the source has no sample yet (PoseSource says nothing of what it has
  // otherwise; each report still leaves out what its sample lacks).
  template <class Report>
  std::uint32_t available_fields(const std::function<Report(const PoseSample&)>& build) {
    using Body = typename Report::body_type;
    if (const auto sample = source_.sample()) return wire::presence_of(static_cast<const Body&>(build(*sample)));
    return wire::optional_mask<Body>();
  }

  // Answers Query from anyone and provides Report on service connections (at
  // most at the source's update rate), both built by `build` from the current
  // sample and limited to `available`. Without a sample the report carries no
  // field (presence vector 0): an answer that says "nothing known yet" rather
  // than silence, which a querying OCU would take for a lost component.
  template <class Query, class Report>
  void serve(std::uint32_t available, std::function<Report(const PoseSample&)> build) {
    auto current = [this, available, build = std::move(build)] {
      Report report{};
      if (const auto sample = source_.sample()) report = build(*sample);
      wire::mask_presence(report, available);
      return report;
    };
    handle<Query>(Access::anyone, false, [this, current](const Header& h, const Query& query) {
      Report report = current();
      wire::mask_presence(report, query.presence_vector);
      send(h.source, report);
    });
    provide<Report>(available, current, source_.update_rate_hz());
    declare_input_presence(Query::code, available);  // Report Services: the fields a query can get
  }

 private:
  rt::Duration check_period() const;
  void arm_watch(rt::TimePoint when);
  void check_source();

  PoseSource& source_;
  SensorOptions options_;
  rt::TimerId watch_timer_ = rt::kNoTimer;
  bool stale_ = true;
};

}  // namespace jaus::components
