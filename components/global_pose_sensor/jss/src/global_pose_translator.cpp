// Global Pose Sensor 1.0 on the RA global pose sensor, docs/jss.md "Sensors":
// the query and report are RA's, read in the JSS dialect (rescaled). Set Global Pose
// and the Geomagnetic Property messages are not supported: RA has no message
// for either, and a correction kept in the face would make JSS and RA clients
// of one vehicle see two positions; they are left to the face's unsupported
// count and logged with why (JSS has no "not supported" reply for commands).
#include "jaus/components_jss/global_pose_sensor_jss.hpp"

#include "jaus/core/component_ids.hpp"
#include "jaus/jss_face/report_translator.hpp"

namespace jaus::components_jss {
namespace {

using namespace jss_face;

class GlobalPoseTranslator final
    : public kit::ReportTranslator<jss::msg::QueryGlobalPose, jss::msg::ReportGlobalPose> {
 public:
  GlobalPoseTranslator()
      : ReportTranslator("global pose sensor", component_id::kGlobalPoseSensor,
                         {ServiceUri{"urn:jaus:jss:mobility:GlobalPoseSensor", 1, 0}}) {}

 protected:
  bool command(const JssInbound& m, FacePort& port) override {
    const bool set_pose = m.message_id == jss::msg::SetGlobalPose::code;
    const bool geomagnetic = m.message_id == jss::msg::SetGeomagneticProperty::code ||
                             m.message_id == jss::msg::QueryGeomagneticProperty::code;
    if (set_pose || geomagnetic)
      log().repeated(port, "global pose settings not supported", rt::LogLevel::warn, [&] {
        return std::string(set_pose ? "Set Global Pose" : "Geomagnetic Property") + " from " + kit::who(m) +
               " not supported (the RA global pose sensor has no such setting)";
      });
    return false;
  }
};

}  // namespace

jss_face::Translators global_pose_sensor_translators(const jss_face::FaceConfig&) {
  jss_face::Translators translators;
  translators.push_back(std::make_unique<GlobalPoseTranslator>());
  return translators;
}

}  // namespace jaus::components_jss
