// Local Pose Sensor 1.0 on the RA local pose sensor, docs/jss.md "Sensors":
// the query and report are RA's, read in the JSS dialect (RA's Z range lies within
// JSS's). Set Local Pose is not supported: RA has no message to move the
// local frame, and a frame offset kept in the face would have to reach every
// consumer of the RA frame (the RA waypoint drivers, RA clients of the same
// vehicle) to stay one frame; so it is left to the face's unsupported count
// (JSS has no "not supported" reply for commands) and logged with why.
#include "jaus/components_jss/local_pose_sensor_jss.hpp"

#include "jaus/core/component_ids.hpp"
#include "jaus/jss_face/report_translator.hpp"

namespace jaus::components_jss {
namespace {

using namespace jss_face;

class LocalPoseTranslator final
    : public kit::ReportTranslator<jss::msg::QueryLocalPose, jss::msg::ReportLocalPose> {
 public:
  LocalPoseTranslator()
      : ReportTranslator("local pose sensor", component_id::kLocalPoseSensor,
                         {ServiceUri{"urn:jaus:jss:mobility:LocalPoseSensor", 1, 0}}) {}

 protected:
  bool command(const JssInbound& m, FacePort& port) override {
    if (m.message_id == jss::msg::SetLocalPose::code)
      log().repeated(port, "Set Local Pose not supported", rt::LogLevel::warn, [&] {
        return "Set Local Pose from " + kit::who(m) +
               " not supported (RA has no way to move the local frame; poses stay in the vehicle's frame)";
      });
    return false;
  }
};

}  // namespace

jss_face::Translators local_pose_sensor_translators(const jss_face::FaceConfig&) {
  jss_face::Translators translators;
  translators.push_back(std::make_unique<LocalPoseTranslator>());
  return translators;
}

}  // namespace jaus::components_jss
