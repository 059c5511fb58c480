// `jausctl clearpath decode|encode|list`, run in-process.
#include <gtest/gtest.h>

#include <sstream>

#include <nlohmann/json.hpp>

#include "commands.hpp"

namespace {

struct Run {
  int exit_code = -1;
  std::string out;
  std::string err;
};

Run run(std::vector<std::string> args, const std::string& stdin_text = "") {
  CLI::App app{"jausctl"};
  app.require_subcommand(1);
  Run r;
  r.exit_code = jausctl::kExitOk;
  jausctl::add_clearpath_commands(app, r.exit_code);
  std::istringstream in(stdin_text);
  std::ostringstream out, err;
  auto* old_in = std::cin.rdbuf(in.rdbuf());
  auto* old_out = std::cout.rdbuf(out.rdbuf());
  auto* old_err = std::cerr.rdbuf(err.rdbuf());
  std::vector<const char*> argv{"jausctl"};
  for (const auto& a : args) argv.push_back(a.c_str());
  try {
    app.parse(static_cast<int>(argv.size()), argv.data());
  } catch (const CLI::ParseError& e) {
    r.exit_code = app.exit(e) == 0 ? 0 : jausctl::kExitBadInput;
  }
  std::cin.rdbuf(old_in);
  std::cout.rdbuf(old_out);
  std::cerr.rdbuf(old_err);
  r.out = out.str();
  r.err = err.str();
  return r;
}

}  // namespace

TEST(JausctlClearpath, DecodePrintsJson) {
  const auto r = run({"clearpath", "decode", "AA0FF00041E2010001020255F0D81027F5E5"});
  ASSERT_EQ(r.exit_code, jausctl::kExitOk) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["type"], "0x0202");
  EXPECT_EQ(j["name"], "set_differential_output");
  EXPECT_EQ(j["timestamp"], 123457);
  EXPECT_EQ(j["flags"], 1);
  EXPECT_EQ(j["version"], 0);
  EXPECT_DOUBLE_EQ(j["fields"]["left"].get<double>(), -100.0);
  EXPECT_DOUBLE_EQ(j["fields"]["right"].get<double>(), 100.0);
}

TEST(JausctlClearpath, DecodeRecognisesAnAckByItsSize) {
  const auto r = run({"clearpath", "decode", "AA0DF20040E20100000202550000F1B5"});
  ASSERT_EQ(r.exit_code, jausctl::kExitOk) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["name"], "ack");
  EXPECT_EQ(j["acknowledges"], "set_differential_output");
}

TEST(JausctlClearpath, EncodeReadsJsonFromStdin) {
  const auto r = run({"clearpath", "encode"},
                     R"({"name":"set_differential_output","timestamp":1000,"fields":{"left":50.0,"right":-25.0}})");
  ASSERT_EQ(r.exit_code, jausctl::kExitOk) << r.err;
  EXPECT_EQ(r.out, "AA0FF000E80300000002025588133CF69427\n");
}

TEST(JausctlClearpath, BadInputExitsTwoWithOneLine) {
  for (const auto& args : std::vector<std::vector<std::string>>{
           {"clearpath", "decode", "zz"},
           {"clearpath", "decode", "AA0FF00041E2010001020255F0D81027F5E6"},  // bad CRC
           {"clearpath", "decode", "AA0DF2004000000000002155000000"}}) {
    const auto r = run(args);
    EXPECT_EQ(r.exit_code, jausctl::kExitBadInput) << args.back();
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_TRUE(r.out.empty());
  }
  for (const std::string input : {"not json", R"({"name":"set_velocity","fields":{"translational":1}})",
                                  R"({"name":"set_velocity","fields":{"translational":500,"rotational":0,"acceleration":0}})",
                                  R"({"name":"nope"})"}) {
    const auto r = run({"clearpath", "encode"}, input);
    EXPECT_EQ(r.exit_code, jausctl::kExitBadInput) << input;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
}

TEST(JausctlClearpath, ListNamesEveryType) {
  const auto r = run({"clearpath", "list"});
  ASSERT_EQ(r.exit_code, jausctl::kExitOk);
  EXPECT_NE(r.out.find("0x0204  command  set_velocity"), std::string::npos);
  EXPECT_NE(r.out.find("0x9022  data  end_effector_pose"), std::string::npos);
  EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 109);
}

TEST(JausctlClearpath, FirmwareWriteTimeAndGearByNameBothWays) {
  // 0x8003 with write time 2024-03-05 14:07 (0x03062B87), as the platform sends it.
  const auto encoded = run({"clearpath", "encode"}, R"({"name":"firmware_info","fields":{"firmware_major":1,
      "firmware_minor":2,"protocol_major":3,"protocol_minor":4,"write_time":"2024-03-05T14:07"}})");
  ASSERT_EQ(encoded.exit_code, jausctl::kExitOk) << encoded.err;
  EXPECT_EQ(encoded.out, "AA13EC00000000000003805501020304872B0603E4D1\n");
  const auto decoded = run({"clearpath", "decode", "AA13EC00000000000003805501020304872B0603E4D1"});
  ASSERT_EQ(decoded.exit_code, jausctl::kExitOk) << decoded.err;
  EXPECT_EQ(nlohmann::json::parse(decoded.out)["fields"]["write_time"], "2024-03-05T14:07");

  const auto gear = run({"clearpath", "encode"}, R"({"name":"change_gear","fields":{"gear":"park"}})");
  ASSERT_EQ(gear.exit_code, jausctl::kExitOk) << gear.err;
  const auto gear_json = run({"clearpath", "decode", gear.out.substr(0, gear.out.size() - 1)});
  ASSERT_EQ(gear_json.exit_code, jausctl::kExitOk) << gear_json.err;
  EXPECT_EQ(nlohmann::json::parse(gear_json.out)["fields"]["gear"], "park");

  // A packed value out of the document's ranges is encoded only when asked to.
  const std::string raw = R"({"name":"firmware_info","fields":{"firmware_major":1,"firmware_minor":2,
      "protocol_major":3,"protocol_minor":4,"write_time":4294967295}})";
  const auto refused = run({"clearpath", "encode"}, raw);
  EXPECT_EQ(refused.exit_code, jausctl::kExitBadInput);
  EXPECT_NE(refused.err.find("write_time"), std::string::npos) << refused.err;
  const auto allowed = run({"clearpath", "encode", "--allow-out-of-range"}, raw);
  ASSERT_EQ(allowed.exit_code, jausctl::kExitOk) << allowed.err;
  const auto shown = run({"clearpath", "decode", allowed.out.substr(0, allowed.out.size() - 1)});
  ASSERT_EQ(shown.exit_code, jausctl::kExitOk) << shown.err;
  EXPECT_EQ(nlohmann::json::parse(shown.out)["fields"]["write_time"], 4294967295u);

  const auto bad = run({"clearpath", "encode"}, R"({"name":"change_gear","fields":{"gear":"drive"}})");
  EXPECT_EQ(bad.exit_code, jausctl::kExitBadInput);
  EXPECT_NE(bad.err.find("unknown name 'drive' (expected one of: park, neutral, or a number)"), std::string::npos)
      << bad.err;
}
