// What the tshark tests share: where tshark and the generated plugin are, a
// scratch directory, tshark's JSON of a capture and the codec's JSON of a
// message (from jausctl).
#pragma once

#include <unistd.h>

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "field_values.hpp"
#include "run_program.hpp"

namespace jaus::test {

class TsharkSession {
 public:
  explicit TsharkSession(const std::string& name)
      : dir_(std::filesystem::temp_directory_path() / ("jaus-wireshark-" + name + "-" + std::to_string(::getpid()))) {
    std::filesystem::create_directories(dir_);
  }
  ~TsharkSession() {
    std::error_code ignored;
    std::filesystem::remove_all(dir_, ignored);
  }
  TsharkSession(const TsharkSession&) = delete;
  TsharkSession& operator=(const TsharkSession&) = delete;

  static std::optional<std::string> tshark() { return find_on_path("tshark"); }
  const std::filesystem::path& dir() const { return dir_; }

  // One JSON object per packet (its "jaus" or "clearpath" layer), or a failure message.
  std::vector<Json> dissect(const std::filesystem::path& pcap, const std::vector<std::string>& prefs,
                            std::string& failure) {
    std::vector<std::string> argv = {*tshark(), "-n", "-X", std::string("lua_script:") + JAUS_WIRESHARK_PLUGIN};
    for (const auto& p : prefs) argv.insert(argv.end(), {"-o", p});
    argv.insert(argv.end(), {"-r", pcap.string(), "-T", "json", "--no-duplicate-keys", "-J", "jaus clearpath"});
    const auto result = run_program(argv, dir_ / "tshark.json", std::chrono::seconds(60));
    if (result.exit_code != 0 || result.err.find("Lua: ") != std::string::npos) {
      failure =
          "tshark failed (exit " + (result.exit_code ? std::to_string(*result.exit_code) : "none") + "): " + result.err;
      return {};
    }
    const auto json = Json::parse(result.out, nullptr, false);
    if (!json.is_array()) {
      failure = "tshark printed no JSON array: " + result.out.substr(0, 200);
      return {};
    }
    std::vector<Json> layers;
    for (const auto& packet : json) {
      const auto& all = packet["_source"]["layers"];
      layers.push_back(all.contains("jaus") ? all["jaus"] : all.contains("clearpath") ? all["clearpath"] : Json());
    }
    return layers;
  }

  // `jausctl ARGS...` printing JSON: the JSON, or null with `failure` set.
  Json jausctl_json(const std::vector<std::string>& args, std::string& failure) {
    std::string key;
    for (const auto& a : args) key += a + " ";
    if (const auto it = decoded_.find(key); it != decoded_.end()) return it->second;
    std::vector<std::string> argv = {JAUSCTL_PATH};
    argv.insert(argv.end(), args.begin(), args.end());
    const auto result = run_program(argv, dir_ / "jausctl.json", std::chrono::seconds(30));
    if (result.exit_code != 0) {
      failure = "jausctl failed: " + result.err;
      return Json();
    }
    return decoded_[key] = Json::parse(result.out, nullptr, false);
  }

 private:
  std::filesystem::path dir_;
  std::map<std::string, Json> decoded_;  // the same message in both framings is decoded once
};

// Skips the test, saying why, when tshark is not installed (scripts/setup.sh installs it).
#define JAUS_REQUIRE_TSHARK()                                                                    \
  do {                                                                                           \
    if (!::jaus::test::TsharkSession::tshark())                                                  \
      GTEST_SKIP() << "tshark is not installed (apt-get install tshark; scripts/setup.sh does)"; \
  } while (0)

}  // namespace jaus::test
