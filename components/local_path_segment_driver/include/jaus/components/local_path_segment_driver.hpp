// The local path segment driver (component 48, issue 30): follows a path of
// Part 3's local path segments (Set Local Path Segment 0x0410: P1, P2 in the
// vehicle's local frame, x north, y east, and a weighting factor 0..500) as
// rational quadratic Bezier curves (guidance/path_segment.hpp), P0 of segment
// 0 being the vehicle's local position when the route starts. Route, travel
// speed and numbering: path_segment_driver.hpp and path_segment_list.hpp. The
// optional z values are stored and echoed, not followed (a ground vehicle).
#pragma once

#include "jaus/components/path_segment_driver.hpp"
#include "jaus/messages/platform_messages.hpp"

namespace jaus::components {

class LocalPathSegmentDriver final : public PathSegmentDriver {
 public:
  LocalPathSegmentDriver(rt::ComponentConfig config, rt::Environment env, PoseSource& pose,
                         const PathSegmentDriverOptions& options);

  std::size_t segment_count() const override { return list_.count(); }
  const PathSegmentList<msg::LocalPathSegmentBody>& segments() const { return list_; }
  Expected<guidance::Point2> position_in_route(const PoseSample& sample) const override;

 protected:
  Expected<guidance::Point2> start_route(const PoseSample& start) override;
  Expected<std::vector<guidance::SegmentSpec>> route_segments() const override;
  void clear_segments() override { list_.clear(); }

 private:
  PathSegmentList<msg::LocalPathSegmentBody> list_;
};

}  // namespace jaus::components
