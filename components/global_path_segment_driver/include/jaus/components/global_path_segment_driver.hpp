// The global path segment driver (component 47, issue 30): follows a path of
// Part 3's global path segments (Set Global Path Segment 0x040F: P1, P2 as
// WGS 84 latitude and longitude, and a weighting factor 0..500) as rational
// quadratic Bezier curves (guidance/path_segment.hpp). The route is followed
// in a LocalFrame (local_frame.hpp) whose datum is the vehicle's global
// position when the route starts (P0 of segment 0, Part 3's "current location
// of the platform"); the points and the vehicle's position are projected into
// it. Route, travel speed and numbering: path_segment_driver.hpp and
// path_segment_list.hpp. The optional elevations are stored and echoed, not
// followed (a ground vehicle).
#pragma once

#include <optional>

#include "jaus/components/local_frame.hpp"
#include "jaus/components/path_segment_driver.hpp"
#include "jaus/messages/platform_messages.hpp"

namespace jaus::components {

class GlobalPathSegmentDriver final : public PathSegmentDriver {
 public:
  GlobalPathSegmentDriver(rt::ComponentConfig config, rt::Environment env, PoseSource& pose,
                          const PathSegmentDriverOptions& options);

  std::size_t segment_count() const override { return list_.count(); }
  const PathSegmentList<msg::GlobalPathSegmentBody>& segments() const { return list_; }
  Expected<guidance::Point2> position_in_route(const PoseSample& sample) const override;

 protected:
  Expected<guidance::Point2> start_route(const PoseSample& start) override;
  Expected<std::vector<guidance::SegmentSpec>> route_segments() const override;
  void clear_segments() override { list_.clear(); }

 private:
  guidance::Point2 in_route(double latitude_deg, double longitude_deg) const;

  PathSegmentList<msg::GlobalPathSegmentBody> list_;
  std::optional<LocalFrame> frame_;  // the route's, from its start
};

}  // namespace jaus::components
