// Every frame Clearpath's reference client produced (tests/data) decodes to
// the values it was made from and re-encodes byte for byte.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "jaus/clearpath/codec.hpp"
#include "jaus/clearpath/crc.hpp"
#include "jaus/clearpath/frame.hpp"
#include "jaus/clearpath/message_json.hpp"

namespace cp = jaus::clearpath;
using nlohmann::json;

namespace {

struct ReferenceLine {
  std::uint16_t type = 0;
  std::map<std::string, std::string> attributes;  // dir, kind, ts, ...
  std::vector<std::uint8_t> frame;
};

std::vector<std::uint8_t> from_hex(const std::string& hex) {
  std::vector<std::uint8_t> out;
  for (std::size_t i = 0; i + 1 < hex.size(); i += 2)
    out.push_back(static_cast<std::uint8_t>(std::stoul(hex.substr(i, 2), nullptr, 16)));
  return out;
}

std::vector<ReferenceLine> load_reference_frames() {
  std::ifstream in(std::string(JAUS_TEST_DATA_DIR) + "/clearpath-reference-frames.txt");
  std::vector<ReferenceLine> lines;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    const auto first = line.find("  ");
    const auto last = line.rfind("  ");
    ReferenceLine ref;
    ref.type = static_cast<std::uint16_t>(std::stoul(line.substr(0, first), nullptr, 16));
    std::stringstream fields(line.substr(first + 2, last - first - 2));
    std::string item;
    while (std::getline(fields, item, ';')) {
      const auto eq = item.find('=');
      if (eq != std::string::npos) ref.attributes[item.substr(0, eq)] = item.substr(eq + 1);
    }
    ref.frame = from_hex(line.substr(last + 2));
    lines.push_back(std::move(ref));
  }
  return lines;
}

// Expected decoded values (JSON "fields"), written out from each line's FIELDS.
const std::map<std::string, json>& expected_fields() {
  static const json constants = json::parse(R"({
    "left":  {"p":2.5,"i":0.25,"d":-0.5,"feed_forward":1.0,"stiction":12.5,"integral_limit":50.0},
    "right": {"p":3.0,"i":0.5,"d":-0.25,"feed_forward":1.5,"stiction":10.0,"integral_limit":75.0}})");
  static const std::map<std::string, json> table = {
      {"0x0002/command", {{"name", "Husky42"}, {"name_nul_terminated", true}}},
      {"0x0201/command", constants},
      {"0x0204/command", {{"translational", 1.25}, {"rotational", -0.5}, {"acceleration", 0.75}}},
      {"0x0210/command", {{"forward", 1.0}, {"reverse", 0.5}}},
      {"0x0211/command", {{"forward", 2.0}, {"reverse", 1.0}}},
      {"0x0212/command", {{"with_flags", true}, {"flags", 0}, {"gear", -2}}},
      {"0x2000/command", {{"passcode", 0x3A18}}},
      {"0x2001/command", {{"passcode", 0x3A18}, {"source", 2}}},
      {"0x2002/command", {{"passcode", 0x3A18}}},
      {"0x0202/command", {{"left", -100.0}, {"right", 100.0}}},
      {"0x4001/request", {{"subscription", 0}}},
      {"0x4003/request", {{"subscription", 0}}},
      {"0x4004/request", {{"subscription", 10}}},
      {"0x4006/request", {{"subscription", 0}}},
      {"0x4200/request", {{"subscription", 20}}},
      {"0x4201/request", {{"subscription", 0}}},
      {"0x4202/request", {{"subscription", 50}}},
      {"0x4203/request", {{"subscription", 25}}},
      {"0x4205/request", {{"subscription", 0}}},
      {"0x4212/request", {{"subscription", 2}}},
      {"0x4500/request", {{"subscription", 15}}},
      {"0x4600/request", {{"subscription", 30}}},
      {"0x4601/request", {{"subscription", 40}}},
      {"0x4801/request", {{"subscription", 65535}}},
      {"0x4802/request", {{"subscription", 0}}},
      {"0x8000/data", json::object()},
      {"0x8002/data", {{"name", "Clearpath1"}, {"name_nul_terminated", false}}},
      {"0x8004/data", json::parse(R"({"uptime_ms":11259375,"voltages":[24.5,12.25,5.0],"currents":[1.5,-0.25],
                                       "temperatures":[35.5,40.25,22.0,30.0]})")},
      {"0x8005/data", json::parse(R"({"batteries":[{"charge":87.5,"capacity":400,"description":193},
                                                   {"charge":50.0,"capacity":200,"description":130}]})")},
      {"0x8010/data", {{"flags", 9}}},
      {"0x8201/data", constants},
      {"0x8203/data", {{"steering", -12.5}, {"throttle", -30.0}, {"brake", 5.0}}},
      {"0x8205/data", {{"translational", 0.5}, {"radius", -2.5}, {"acceleration", 0.25}}},
      {"0x8210/data", {{"forward", 1.0}, {"reverse", 0.5}}},
      {"0x8212/data", {{"flags", 2}, {"gear", 3}}},
      {"0x8500/data", {{"distances", {1.25, 0.5}}}},
      {"0x8501/data", json::parse(R"({"ranges":[{"distance":1.25,"acquired":1000},{"distance":0.5,"acquired":16909060}]})")},
      {"0x8600/data", {{"roll", 0.125}, {"pitch", -0.25}, {"yaw", 1.5}}},
      {"0x8601/data", {{"roll_rate", 0.5}, {"pitch_rate", -1.25}, {"yaw_rate", 2.0}}},
      {"0x8602/data", {{"x", 0.25}, {"y", -0.5}, {"z", 9.75}}},
      {"0x8606/data", {{"x", 0.125}, {"y", -0.375}, {"z", 0.5}}},
      {"0x8800/data", json::parse(R"({"encoders":[{"travel":12.5,"speed":0.5},{"travel":-3.25,"speed":-0.125}]})")},
      {"0x8802/data", json::parse(R"({"encoders":[{"ppr":1000,"scale":0.5},{"ppr":2048,"scale":-0.25}]})")},
      {"0x0202/ack", {{"result", 0}}},
  };
  return table;
}

void expect_same(const json& expected, const json& actual, const std::string& where) {
  if (expected.is_number() && actual.is_number()) {
    EXPECT_NEAR(expected.get<double>(), actual.get<double>(), 1e-9) << where;
  } else if (expected.is_object()) {
    ASSERT_TRUE(actual.is_object()) << where;
    EXPECT_EQ(expected.size(), actual.size()) << where << ": " << actual.dump();
    for (const auto& [key, value] : expected.items()) {
      ASSERT_TRUE(actual.contains(key)) << where << "." << key;
      expect_same(value, actual[key], where + "." + key);
    }
  } else if (expected.is_array()) {
    ASSERT_TRUE(actual.is_array()) << where;
    ASSERT_EQ(expected.size(), actual.size()) << where;
    for (std::size_t i = 0; i < expected.size(); ++i)
      expect_same(expected[i], actual[i], where + "[" + std::to_string(i) + "]");
  } else {
    EXPECT_EQ(expected, actual) << where;
  }
}

std::string key_of(const ReferenceLine& ref) {
  char type[8];
  std::snprintf(type, sizeof type, "0x%04X", ref.type);
  return std::string(type) + "/" + ref.attributes.at("kind");
}

}  // namespace

TEST(ClearpathCrc, CheckValueAndWorkedExample) {
  const std::string check = "123456789";
  EXPECT_EQ(cp::clearpath_crc(std::span(reinterpret_cast<const std::uint8_t*>(check.data()), check.size())), 0x29B1);
  // docs/clearpath-protocol.md ("Frame"): Set Differential Output 50 % / -25 %, timestamp 1000.
  const std::vector<std::uint8_t> expected = {0xAA, 0x0F, 0xF0, 0x00, 0xE8, 0x03, 0x00, 0x00, 0x00,
                                              0x02, 0x02, 0x55, 0x88, 0x13, 0x3C, 0xF6, 0x94, 0x27};
  cp::SetDifferentialOutput out;
  out.left = 50.0;
  out.right = -25.0;
  auto bytes = cp::encode(cp::Envelope{{0, 1000, 0, 0}, cp::AnyMessage{out}});
  ASSERT_TRUE(bytes) << bytes.error().message();
  EXPECT_EQ(*bytes, expected);
}

TEST(ClearpathReferenceFrames, FileHasEveryLine) {
  EXPECT_EQ(load_reference_frames().size(), expected_fields().size());
}

TEST(ClearpathReferenceFrames, DecodeToTheirValuesAndReencodeByteExact) {
  for (const auto& ref : load_reference_frames()) {
    const std::string key = key_of(ref);
    SCOPED_TRACE(key);
    const auto frame = cp::decode_frame(ref.frame);
    ASSERT_TRUE(frame) << frame.error().message();
    EXPECT_EQ(frame->header.type, ref.type);
    EXPECT_EQ(frame->header.timestamp, std::stoul(ref.attributes.at("ts")));
    EXPECT_EQ(frame->header.version, 0);

    const auto direction =
        ref.attributes.at("dir") == "p2h" ? cp::Direction::from_platform : cp::Direction::to_platform;
    const auto envelope = cp::decode(*frame, direction);
    ASSERT_TRUE(envelope) << envelope.error().message();
    EXPECT_EQ(envelope->message.holds<cp::Ack>(), ref.attributes.at("kind") == "ack");

    const json decoded = cp::to_json(*envelope);
    const auto expected = expected_fields().find(key);
    ASSERT_NE(expected, expected_fields().end()) << "no expectation for " << key;
    expect_same(expected->second, decoded["fields"], key);

    const auto reencoded = cp::encode(*envelope);
    ASSERT_TRUE(reencoded) << reencoded.error().message();
    EXPECT_EQ(*reencoded, ref.frame);

    // And again through JSON, as jausctl does it.
    const auto from_json = cp::envelope_from_json(decoded);
    ASSERT_TRUE(from_json) << from_json.error().message();
    const auto via_json = cp::encode(*from_json);
    ASSERT_TRUE(via_json);
    EXPECT_EQ(*via_json, ref.frame);
  }
}

TEST(ClearpathReferenceFrames, HeaderFlagsOfDifferentialOutputSuppressAck) {
  for (const auto& ref : load_reference_frames()) {
    if (ref.type != 0x0202 || ref.attributes.at("kind") != "command") continue;
    const auto frame = cp::decode_frame(ref.frame);
    ASSERT_TRUE(frame);
    EXPECT_EQ(frame->header.flags, cp::kFlagSuppressAck);
  }
}

TEST(ClearpathDecode, ChangeGearAcceptsTheDocumentsOneByteForm) {
  const std::vector<std::uint8_t> payload = {0xFE};
  const auto message = cp::decode_payload(0x0212, payload, cp::Direction::to_platform);
  ASSERT_TRUE(message);
  const auto& gear = message->get<cp::ChangeGear>();
  EXPECT_FALSE(gear.with_flags);
  EXPECT_EQ(gear.gear, -2);
  EXPECT_EQ(*cp::encode_payload(*message), payload);
}

TEST(ClearpathDecode, LayoutErrorsAreValuesThatSayWhere) {
  const std::vector<std::uint8_t> short_payload = {0x88, 0x13, 0x3C};
  const auto r = cp::decode_payload(0x0202, short_payload, cp::Direction::to_platform);
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().code, jaus::ErrorCode::truncated);
  EXPECT_EQ(r.error().field, "right");
  EXPECT_EQ(r.error().offset, 2u);

  const std::vector<std::uint8_t> long_payload = {0x88, 0x13, 0x3C, 0xF6, 0x00};
  const auto l = cp::decode_payload(0x0202, long_payload, cp::Direction::to_platform);
  ASSERT_FALSE(l);
  EXPECT_EQ(l.error().code, jaus::ErrorCode::trailing_bytes);

  // System status claiming 3 voltages but carrying one.
  const std::vector<std::uint8_t> counted = {0, 0, 0, 0, 3, 0x10, 0x00};
  const auto c = cp::decode_payload(0x8004, counted, cp::Direction::from_platform);
  ASSERT_FALSE(c);
  EXPECT_EQ(c.error().field, "voltages");

  const auto unknown = cp::decode_payload(0x2100, {}, cp::Direction::to_platform);
  ASSERT_FALSE(unknown);
  EXPECT_EQ(unknown.error().code, jaus::ErrorCode::unknown_message);
}

TEST(ClearpathDecode, FromPlatformACommandTypeIsAnAck) {
  const std::vector<std::uint8_t> payload = {0x08, 0x00};
  const auto m = cp::decode_payload(0x0204, payload, cp::Direction::from_platform);
  ASSERT_TRUE(m);
  EXPECT_EQ(m->get<cp::Ack>().result, cp::kAckOutOfRange);
  EXPECT_EQ(cp::describe_ack_result(cp::kAckOutOfRange | cp::kAckBadChecksum), "bad checksum|out of range");
}

TEST(ClearpathRanges, OutOfRangeFieldsAreNamed) {
  cp::SetVelocity v;
  v.translational = 1.0;
  v.acceleration = -1.0;  // a magnitude: [0, 320]
  const auto e = cp::check_ranges(cp::AnyMessage{v});
  ASSERT_FALSE(e);
  EXPECT_EQ(e.error().code, jaus::ErrorCode::out_of_range);
  EXPECT_EQ(e.error().field, "acceleration");

  cp::SetDifferentialControl c;
  c.right.stiction = 150;
  const auto nested = cp::check_ranges(cp::AnyMessage{c});
  ASSERT_FALSE(nested);
  EXPECT_EQ(nested.error().field, "right.stiction");

  cp::ResetProcessor reset;
  reset.passcode = 1;
  EXPECT_FALSE(cp::check_ranges(cp::AnyMessage{reset}));
  EXPECT_TRUE(cp::check_ranges(cp::AnyMessage{cp::ResetProcessor{}}));
}

TEST(ClearpathEncode, UnrepresentableValuesAreErrors) {
  cp::SetVelocity v;
  v.translational = 400.0;  // 40000 does not fit a signed short
  const auto r = cp::encode_payload(cp::AnyMessage{v});
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().code, jaus::ErrorCode::bad_value);
  EXPECT_EQ(r.error().field, "translational");

  v.translational = std::nan("");
  EXPECT_FALSE(cp::encode_payload(cp::AnyMessage{v}));

  cp::ProcessorStatus big;
  big.errors.assign(200, 1);  // 401 bytes: more than one frame carries
  const auto too_large = cp::encode_payload(cp::AnyMessage{big});
  ASSERT_FALSE(too_large);
  EXPECT_EQ(too_large.error().code, jaus::ErrorCode::payload_too_large);
}

TEST(ClearpathEncode, RoundsToNearestInsteadOfTruncating) {
  cp::SetDifferentialOutput out;
  out.left = 0.129;   // 12.9 -> 13, a truncating encoder sends 12
  out.right = -0.129;
  const auto payload = cp::encode_payload(cp::AnyMessage{out});
  ASSERT_TRUE(payload);
  EXPECT_EQ(*payload, (std::vector<std::uint8_t>{13, 0, 0xF3, 0xFF}));
}
