// Every vector of the common open RA 3.3 implementation decodes (openjaus
// dialect), and its values match what that implementation was given, within
// one scale step (the step comes from the message descriptions). Their field
// names are mapped to ours here; a field of ours that no vector value covers
// fails the test, so nothing is compared by accident of omission.
#include <gtest/gtest.h>

#include <cctype>
#include <map>

#include <nlohmann/json.hpp>

#include "jaus/base/hex.hpp"
#include "jaus/messages/catalogue.hpp"
#include "vector_compare.hpp"
#include "vector_file.hpp"

namespace jaus::test {
namespace {

using Json = nlohmann::ordered_json;

// ---- their value syntax: 12, -1.5, 0x4B01, [a,b], [[..],[..]], {k=v,...} ----
Json parse_value(std::string_view s, std::size_t& i);

Json parse_scalar(std::string_view s, std::size_t& i) {
  const std::size_t start = i;
  while (i < s.size() && s[i] != ',' && s[i] != ']' && s[i] != '}' && s[i] != ';') ++i;
  const std::string text(s.substr(start, i - start));
  if (text.size() > 2 && text[0] == '0' && (text[1] == 'x' || text[1] == 'X')) return std::stoull(text, nullptr, 16);
  char* end = nullptr;
  const double d = std::strtod(text.c_str(), &end);
  if (!text.empty() && end == text.c_str() + text.size()) {
    if (text.find_first_of(".eE") == std::string::npos) return std::stoll(text);
    return d;
  }
  return text;
}

Json parse_value(std::string_view s, std::size_t& i) {
  if (i < s.size() && s[i] == '[') {
    Json out = Json::array();
    ++i;
    while (i < s.size() && s[i] != ']') {
      out.push_back(parse_value(s, i));
      if (i < s.size() && s[i] == ',') ++i;
    }
    ++i;
    return out;
  }
  if (i < s.size() && s[i] == '{') {
    Json out = Json::object();
    ++i;
    while (i < s.size() && s[i] != '}') {
      const auto eq = s.find('=', i);
      const std::string key(s.substr(i, eq - i));
      i = eq + 1;
      out[key] = parse_value(s, i);
      if (i < s.size() && s[i] == ',') ++i;
    }
    ++i;
    return out;
  }
  return parse_scalar(s, i);
}

// "a=1;b=[1,2];time={...}" -> {"a":1, ...}; values in a form we do not parse stay text.
std::map<std::string, Json> parse_fields(std::string_view s) {
  std::map<std::string, Json> out;
  std::size_t i = 0;
  while (i < s.size()) {
    const auto eq = s.find('=', i);
    const std::string key(s.substr(i, eq - i));
    i = eq + 1;
    const std::size_t start = i;
    Json value = parse_value(s, i);
    if (i < s.size() && s[i] != ';') {  // trailing text, e.g. "(S.N.C.I)": keep the raw text
      while (i < s.size() && s[i] != ';') ++i;
      value = std::string(s.substr(start, i - start));
    }
    out[key] = value;
    if (i < s.size() && s[i] == ';') ++i;
  }
  return out;
}

std::string snake_case(const std::string& camel) {
  std::string out;
  for (char c : camel) {
    if (std::isupper(static_cast<unsigned char>(c))) {
      out += '_';
      out += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    } else {
      out += c;
    }
  }
  return out;
}

const std::map<std::string, std::string> kNames = {
    {"transitionToEmergency", "emergency_code"}, {"clearEmergency", "emergency_code"},
    {"serviceConnectionCommandCode", "command_code"}, {"requestedPeriodicUpdateRateHertz", "periodic_rate_hz"},
    {"confirmedPeriodicUpdateRateHertz", "confirmed_rate_hz"}, {"authorityCode", "authority"},
    {"dataLinkState", "state"}, {"speedMps", "speed_mps"}, {"altitudeMeters", "altitude_m"},
    {"headingRadians", "heading_rad"}, {"rollRadians", "roll_rad"}, {"pitchRadians", "pitch_rad"},
    {"yawRadians", "yaw_rad"}, {"latitudeDegrees", "latitude_deg"}, {"longitudeDegrees", "longitude_deg"},
    {"elevationMeters", "elevation_m"}, {"xM", "x_m"}, {"yM", "y_m"}, {"zM", "z_m"},
    {"p1LatitudeDeg", "p1_latitude_deg"}, {"p1LongitudeDeg", "p1_longitude_deg"}, {"p1AltitudeM", "p1_elevation_m"},
    {"p2LatitudeDeg", "p2_latitude_deg"}, {"p2LongitudeDeg", "p2_longitude_deg"}, {"p2AltitudeM", "p2_elevation_m"},
    {"p1XM", "p1_x_m"}, {"p1YM", "p1_y_m"}, {"p1ZM", "p1_z_m"}, {"p2XM", "p2_x_m"}, {"p2YM", "p2_y_m"},
    {"p2ZM", "p2_z_m"}, {"jointEffort", "efforts_percent"}, {"jointPosition", "positions_rad"},
    {"jointForceTorque", "force_torques_nm"}, {"xAngular", "angular_x_rps"}, {"yAngular", "angular_y_rps"},
    {"zAngular", "angular_z_rps"}, {"xLinear", "linear_x_mps"}, {"yLinear", "linear_y_mps"},
    {"zLinear", "linear_z_mps"}, {"cameraID", "camera_id"}, {"horizontalFovRadians", "horizontal_fov_rad"},
    {"verticalFovRadians", "vertical_fov_rad"}, {"frameRate", "frame_rate_fps"}, {"shutterSpeed", "shutter_inverse_s"},
    {"engineTemperatureCelsius", "engine_temperature_c"}, {"odometerMeters", "odometer_m"},
    {"positionRmsMeters", "position_rms_m"}, {"attitudeRmsRadians", "attitude_rms_rad"},
    {"velocityXMps", "velocity_x_mps"}, {"velocityYMps", "velocity_y_mps"}, {"velocityZMps", "velocity_z_mps"},
    {"velocityRmsMps", "velocity_rms_mps"}, {"rangeMeters", "range_m"}, {"rangeErrorMeters", "range_error_m"},
    {"bearingRadians", "bearing_rad"}, {"bearingErrorRadians", "bearing_error_rad"},
    {"inclinationRadians", "elevation_rad"}, {"inclinationErrorRadians", "elevation_error_rad"},
    {"confirmedUpdateRate", "confirmed_rate_hz"}, {"reportMessageCode", "report_code"},
    {"eventSequenceNumber", "sequence_number"}};

Json time_stamp(const Json& t) {
  return Json{{"day", t["day"]}, {"hour", t["hour"]}, {"minute", t["min"]}, {"second", t["sec"]},
              {"millisecond", t["ms"]}};
}

int bit(const std::map<std::string, Json>& f, const char* name) { return f.at(name).get<int>() ? 1 : 0; }

// Values we expect in our JSON form, built from the vector's own values.
Json expected_fields(const std::string& code, const std::map<std::string, Json>& f, const Json& ours) {
  Json out = Json::object();
  if (code == "0406" || code == "4406") {
    out["main_propulsion"] = bit(f, "mainPropulsion") | bit(f, "mainFuelSupply") << 1 | bit(f, "auxFuelSupply") << 2 |
                             bit(f, "powerAuxDevices") << 3 | bit(f, "startingDevice") << 4 |
                             bit(f, "coldStart") << 5 | bit(f, "automaticStart") << 6 | bit(f, "automaticStop") << 7;
    out["parking_brake_and_horn"] = bit(f, "parkingBrake") | bit(f, "horn") << 1;
    out["gear"] = f.at("gear");
    out["transfer_case"] = f.at("transferCase");
    return out;
  }
  if (code == "0805") {
    for (const char* k : {"cameraID", "horizontalFovRadians", "verticalFovRadians", "frameRate", "shutterSpeed"})
      out[kNames.at(k)] = f.at(k);
    for (const char* k : {"horizontalResolution", "verticalResolution", "focusPercent", "irisPercent", "gainPercent"})
      out[snake_case(k)] = f.at(k);
    const char* imagery[] = {"autoFocus", "autoIris", "imageStabilization", "whiteBalance", "syncFlash",
                             "redEye", "autoShutter", "videoAutoGain", "interlacedVideo"};
    const char* audio[] = {"audioEnabled", "audioAutoGain", "stereoAudio", "directionalAudio",
                           "frontMicrophone", "rearMicrophone", "leftMicrophone", "rightMicrophone"};
    int imagery_bits = 0, audio_bits = 0;
    for (int i = 0; i < 9; ++i) imagery_bits |= bit(f, imagery[i]) << i;
    for (int i = 0; i < 8; ++i) audio_bits |= bit(f, audio[i]) << i;
    out["imagery_control"] = imagery_bits;
    out["audio_control"] = audio_bits;
    return out;
  }
  if (code == "0607") {
    out["joint_count"] = f.at("numJoints");
    out["poses"] = Json::array();
    for (std::size_t p = 0; p < f.at("poseTime").size(); ++p) {
      Json pose{{"time_s", f.at("poseTime")[p]}, {"joints", Json::array()}};
      for (std::size_t j = 0; j < f.at("numJoints").get<std::size_t>(); ++j)
        pose["joints"].push_back({{"position_rad", f.at("position")[p][j]},
                                  {"max_velocity_rps", f.at("maxVelocity")[p][j]},
                                  {"max_acceleration_rps2", f.at("maxAcceleration")[p][j]},
                                  {"max_deceleration_rps2", f.at("maxDeceleration")[p][j]}});
      out["poses"].push_back(pose);
    }
    return out;
  }
  if (code == "4600") {
    // Their values: revolute joints in rad, prismatic in mm; ours in rad or m.
    const auto& type = f.at("jointType");
    auto unit = [&](std::size_t joint, double v) { return type[joint] == 2 ? v / 1000.0 : v; };
    const std::size_t n = f.at("numJoints").get<std::size_t>();
    out["joint_count"] = n;
    out["last_joint_type"] = type[n - 1];
    out["last_joint_offset_rad_or_m"] = unit(n - 1, f.at("jointOffset")[n - 1].get<double>());
    out["last_joint_min_rad_or_m"] = unit(n - 1, f.at("jointMinValue")[n - 1].get<double>());
    out["last_joint_max_rad_or_m"] = unit(n - 1, f.at("jointMaxValue")[n - 1].get<double>());
    out["last_joint_max_velocity_rps_or_mps"] = unit(n - 1, f.at("jointMaxVelocity")[n - 1].get<double>());
    // The line lists the frame twice; the later values are the ones it sent.
    out["frame_x_m"] = 1.5;
    out["frame_y_m"] = -2.25;
    out["frame_z_m"] = 10;
    out["frame_quaternion_d"] = -0.25;
    out["frame_quaternion_a"] = 0.125;
    out["frame_quaternion_b"] = -0.5;
    out["frame_quaternion_c"] = 0.75;
    out["joints"] = Json::array();
    for (std::size_t j = 0; j + 1 < n; ++j)
      out["joints"].push_back({{"type", type[j]},
                               {"link_length_m", f.at("linkLength")[j].get<double>() / 1000.0},
                               {"twist_angle_rad", f.at("twistAngle")[j]},
                               {"offset_rad_or_m", unit(j, f.at("jointOffset")[j].get<double>())},
                               {"min_rad_or_m", unit(j, f.at("jointMinValue")[j].get<double>())},
                               {"max_rad_or_m", unit(j, f.at("jointMaxValue")[j].get<double>())},
                               {"max_velocity_rps_or_mps", unit(j, f.at("jointMaxVelocity")[j].get<double>())}});
    return out;
  }
  if (code == "4807") {
    out["camera_id"] = f.at("cameraID");
    out["image_format"] = f.at("videoFormat");
    out["data"] = f.at("data");
    return out;
  }
  if (code == "400D") {
    out["controller"] = std::to_string(f.at("subsystemId").get<int>()) + "." + std::to_string(f.at("nodeId").get<int>()) +
                        "." + std::to_string(f.at("componentId").get<int>()) + "." +
                        std::to_string(f.at("instanceId").get<int>());
    out["authority"] = f.at("authorityCode");
    return out;
  }
  if (code == "4604") {
    out["x_m"] = f.at("x");
    out["y_m"] = f.at("y");
    out["z_m"] = f.at("z");
    return out;
  }
  if (code == "4B00") {
    out["query_type"] = f.at("queryType");
    out["authority"] = f.at("authority");
    out["type"] = f.at("type");
    out["identification"] = "OJSubsystem";
    return out;
  }
  if (code == "4B01" || code == "41F1") {
    // nodes=[{id=1,cmpts=[1.1,35.1,33.2]},...]: component.instance pairs.
    const Json configuration = code == "4B01" ? Json{{"nodes", Json::array({{{"node_id", 1}, {"components", {{{"component_id", 1}, {"instance", 1}}, {{"component_id", 35}, {"instance", 1}}, {{"component_id", 33}, {"instance", 2}}}}},
                                                                           {{"node_id", 3}, {"components", {{{"component_id", 1}, {"instance", 1}}, {{"component_id", 38}, {"instance", 1}}}}}})}}
                                              : Json{};
    if (code == "4B01") return configuration;
    out["event_id"] = f.at("eventId");
    out["report_code"] = 0x4B01;
    out["sequence_number"] = f.at("eventSequenceNumber");
    // ReportConfiguration{nodes=[{id=1,cmpts=[1.1,38.1]}]}: 1 node, id 1, 2 components.
    out["report_message"] = "01010201012601";
    return out;
  }
  if (code == "4B02") {
    out["subsystems"] = Json::array({"1.1.35.1", "7.2.35.1"});
    return out;
  }
  if (code == "4B03") {
    out["services"] = Json::array(
        {{{"type", 38},
          {"inputs", Json::array({{{"command_code", 0x2402}, {"presence_vector", 0x1FF}}})},
          {"outputs", Json::array({{{"command_code", 0x4402}, {"presence_vector", 0x1FF}},
                                   {{"command_code", 0x4002}, {"presence_vector", 0}}})}}});
    return out;
  }
  if (code == "01F0") {
    out["request_id"] = f.at("requestId");
    out["report_code"] = f.at("reportMessageCode");
    out["event_type"] = f.at("eventType");
    out["query_message"] = "02";  // QueryConfiguration{queryField=2}
    return out;
  }
  if (code == "0011") {
    const Json& t = f.at("time");
    out["time"] = time_stamp(t);
    out["date"] = {{"year", t["year"]}, {"month", t["month"].get<int>() + 1}, {"day", t["day"]}};  // theirs is 0-based
    return out;
  }

  for (const auto& [name, value] : f) {
    if (name == "_hdr" || name == "numJoints") continue;
    if (name == "presenceVector") {
      if (ours.contains("presence_vector")) out["presence_vector"] = value;
      continue;  // otherwise derived from the present fields
    }
    if (name == "time") {
      out["time_stamp"] = time_stamp(value);
      continue;
    }
    if (name == "queryField") {
      out[code == "2B00" ? "query_type" : "query_field"] = value;
      continue;
    }
    if (name == "audioFormat" || name == "imageFormat") {
      const std::string base = name == "audioFormat" ? "audio_format_" : "image_format_";
      for (std::size_t i = 0; i < value.size(); ++i) out[base + std::to_string(i + 1)] = value[i];
      continue;
    }
    const auto mapped = kNames.find(name);
    out[mapped != kNames.end() ? mapped->second : snake_case(name)] = value;
  }
  return out;
}

void expect_header(const std::string& spec, const Header& h, const std::string& where) {
  // prio6,ack0,sc0,exp0,ver2,dst1.1.33.1,src2.1.40.1,seq0x0A0B
  EXPECT_NE(spec.find("prio" + std::to_string(h.priority) + ","), std::string::npos) << where;
  EXPECT_NE(spec.find("ack" + std::to_string(static_cast<int>(h.ack_nak)) + ","), std::string::npos) << where;
  EXPECT_NE(spec.find(std::string("sc") + (h.service_connection ? "1" : "0")), std::string::npos) << where;
  EXPECT_NE(spec.find("ver" + std::to_string(h.version)), std::string::npos) << where;
  EXPECT_NE(spec.find("dst" + h.destination.to_string()), std::string::npos) << where;
  EXPECT_NE(spec.find("src" + h.source.to_string()), std::string::npos) << where;
  EXPECT_EQ(h.sequence, 0x0A0B) << where;
}

class OpenJausVectors : public ::testing::TestWithParam<Vector> {};

TEST_P(OpenJausVectors, DecodeToTheValuesTheyWereGiven) {
  const Vector& v = GetParam();
  const auto bytes = parse_hex(v.hex);
  ASSERT_TRUE(bytes) << bytes.error().message();
  auto packet = decode_packet(*bytes);
  ASSERT_TRUE(packet) << packet.error().message();
  const auto fields = parse_fields(v.fields);
  expect_header(fields.at("_hdr").get<std::string>(), packet->header, v.code);
  EXPECT_EQ(packet->header.command_code, std::stoul(v.code, nullptr, 16));

  auto ours = msg::message_to_json(*bytes, wire::Dialect::openjaus);
  ASSERT_TRUE(ours) << v.code << ": " << ours.error().message();
  const Json expected = expected_fields(v.code, fields, (*ours)["fields"]);
  // Every field we decoded is covered by one of theirs.
  for (const auto& [key, value] : (*ours)["fields"].items())
    EXPECT_TRUE(expected.contains(key)) << v.code << ": our field '" << key << "' has no vector value";

  // The typed comparison, as the message type of the code (vector_compare.hpp).
  const bool found = compare_with_vector(packet->header.command_code, expected, packet->payload, v.code);
  EXPECT_TRUE(found);
}

INSTANTIATE_TEST_SUITE_P(Files, OpenJausVectors, ::testing::ValuesIn(all_vectors()),
                         [](const auto& param_info) { return "code_" + param_info.param.code; });

}  // namespace
}  // namespace jaus::test
