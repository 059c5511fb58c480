#include "jaus/components/local_path_segment_driver.hpp"

#include "jaus/wire/describe.hpp"

namespace jaus::components {

namespace {
// Presence bits of Set/Report Local Path Segment: 0 P1's z, 1 P2's z.
constexpr std::uint32_t kLocalSegmentFields = 0x03;

Expected<guidance::Point2> local_point(const PoseSample& sample) {
  if (!sample.local_position)
    return unexpected(make_error(ErrorCode::invalid_argument, "the pose source gives no local position"));
  return guidance::Point2{sample.local_position->x_m, sample.local_position->y_m};
}
}  // namespace

LocalPathSegmentDriver::LocalPathSegmentDriver(rt::ComponentConfig config, rt::Environment env, PoseSource& pose,
                                               const PathSegmentDriverOptions& options)
    : PathSegmentDriver(std::move(config), std::move(env), pose, options), list_(options.max_path_segments) {
  handle<msg::SetLocalPathSegment>(Access::controller, false,
                                   [this](const Header& h, const msg::SetLocalPathSegment& m) {
                                     segment_set(h, m.path_segment_number, list_.set(m));
                                   });
  handle<msg::QueryLocalPathSegment>(Access::anyone, false, [this](const Header& h, const msg::QueryLocalPathSegment& q) {
    const msg::LocalPathSegmentBody* segment = list_.at(q.path_segment_number);
    if (!segment) return segment_query_unanswered(h, q.path_segment_number);
    msg::ReportLocalPathSegment report;
    static_cast<msg::LocalPathSegmentBody&>(report) = *segment;
    wire::mask_presence(report, q.presence_vector);
    send(h.source, report);
  });
  declare_input_presence(msg::SetLocalPathSegment::code, kLocalSegmentFields);
  declare_input_presence(msg::QueryLocalPathSegment::code, kLocalSegmentFields);
}

Expected<guidance::Point2> LocalPathSegmentDriver::start_route(const PoseSample& start) { return local_point(start); }

Expected<guidance::Point2> LocalPathSegmentDriver::position_in_route(const PoseSample& sample) const {
  return local_point(sample);
}

Expected<std::vector<guidance::SegmentSpec>> LocalPathSegmentDriver::route_segments() const {
  std::vector<guidance::SegmentSpec> specs;
  specs.reserve(list_.count());
  for (const auto& s : list_.segments())
    specs.push_back({{s.p1_x_m, s.p1_y_m}, {s.p2_x_m, s.p2_y_m}, s.weighting_factor});
  return specs;
}

}  // namespace jaus::components
