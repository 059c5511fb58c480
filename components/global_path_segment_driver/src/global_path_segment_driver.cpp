#include "jaus/components/global_path_segment_driver.hpp"

#include "jaus/wire/describe.hpp"

namespace jaus::components {

namespace {
// Presence bits of Set/Report Global Path Segment: 0 P1's elevation, 1 P2's.
constexpr std::uint32_t kGlobalSegmentFields = 0x03;

Error no_position() {
  return make_error(ErrorCode::invalid_argument, "the pose source gives no global position");
}
}  // namespace

GlobalPathSegmentDriver::GlobalPathSegmentDriver(rt::ComponentConfig config, rt::Environment env, PoseSource& pose,
                                                 const PathSegmentDriverOptions& options)
    : PathSegmentDriver(std::move(config), std::move(env), pose, options), list_(options.max_path_segments) {
  handle<msg::SetGlobalPathSegment>(Access::controller, false,
                                    [this](const Header& h, const msg::SetGlobalPathSegment& m) {
                                      segment_set(h, m.path_segment_number, list_.set(m));
                                    });
  handle<msg::QueryGlobalPathSegment>(
      Access::anyone, false, [this](const Header& h, const msg::QueryGlobalPathSegment& q) {
        const msg::GlobalPathSegmentBody* segment = list_.at(q.path_segment_number);
        if (!segment) return segment_query_unanswered(h, q.path_segment_number);
        msg::ReportGlobalPathSegment report;
        static_cast<msg::GlobalPathSegmentBody&>(report) = *segment;
        wire::mask_presence(report, q.presence_vector);
        send(h.source, report);
      });
  declare_input_presence(msg::SetGlobalPathSegment::code, kGlobalSegmentFields);
  declare_input_presence(msg::QueryGlobalPathSegment::code, kGlobalSegmentFields);
}

// The frame's datum is where the vehicle is: P0 is its origin.
Expected<guidance::Point2> GlobalPathSegmentDriver::start_route(const PoseSample& start) {
  if (!start.position) return unexpected(no_position());
  frame_.emplace(*start.position);
  return guidance::Point2{0, 0};
}

guidance::Point2 GlobalPathSegmentDriver::in_route(double latitude_deg, double longitude_deg) const {
  // On the frame's tangent plane: elevations are not followed.
  const LocalPosition p = frame_->to_local(GeoPosition{latitude_deg, longitude_deg, frame_->datum().altitude_m});
  return {p.x_m, p.y_m};
}

Expected<guidance::Point2> GlobalPathSegmentDriver::position_in_route(const PoseSample& sample) const {
  if (!frame_) return unexpected(make_error(ErrorCode::invalid_argument, "no route started"));
  if (!sample.position) return unexpected(no_position());
  return in_route(sample.position->latitude_deg, sample.position->longitude_deg);
}

Expected<std::vector<guidance::SegmentSpec>> GlobalPathSegmentDriver::route_segments() const {
  if (!frame_) return unexpected(make_error(ErrorCode::invalid_argument, "no route started"));
  std::vector<guidance::SegmentSpec> specs;
  specs.reserve(list_.count());
  for (const auto& s : list_.segments())
    specs.push_back({in_route(s.p1_latitude_deg, s.p1_longitude_deg), in_route(s.p2_latitude_deg, s.p2_longitude_deg),
                     s.weighting_factor});
  return specs;
}

}  // namespace jaus::components
