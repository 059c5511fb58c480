// clearpath-sim as a process: its hardware inputs typed on stdin (`pause on`,
// `estop off`, `status`), answered with JSON lines, kept apart from what a
// client's Set Safety System (0x0010) writes; --events lines on the steady clock.
// The client is raw UDP frames from the Clearpath codec, from 127.0.0.39.
#include <gtest/gtest.h>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <filesystem>
#include <functional>
#include <memory>
#include <sstream>
#include <thread>

#include <nlohmann/json.hpp>

#include "child_process.hpp"
#include "jaus/clearpath/codec.hpp"

namespace jaus::test {
namespace {

using namespace std::chrono_literals;
using Json = nlohmann::json;
namespace cp = jaus::clearpath;

constexpr const char* kSimAddress = "127.0.0.38";
constexpr std::uint16_t kSimPort = 7300;
constexpr const char* kClientAddress = "127.0.0.39";

std::int64_t steady_ns_now() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

// A Clearpath host on UDP: one command at a time, waiting for its ACK.
class RawClient {
 public:
  RawClient() {
    fd_ = ::socket(AF_INET, SOCK_DGRAM, 0);
    sockaddr_in self = address(kClientAddress, 0);
    ::bind(fd_, reinterpret_cast<sockaddr*>(&self), sizeof self);
    timeval timeout{0, 300'000};
    ::setsockopt(fd_, SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof timeout);
  }
  ~RawClient() { ::close(fd_); }
  RawClient(const RawClient&) = delete;
  RawClient& operator=(const RawClient&) = delete;

  // The ACK's result, or nullopt if none came (a few tries).
  std::optional<std::uint16_t> command(const cp::AnyMessage& message) {
    for (int attempt = 0; attempt < 5; ++attempt) {
      const auto frame = cp::encode(cp::Envelope{{cp::kDefaultVersion, ++timestamp_, 0, 0}, message});
      if (!frame) return std::nullopt;
      const sockaddr_in sim = address(kSimAddress, kSimPort);
      ::sendto(fd_, frame->data(), frame->size(), 0, reinterpret_cast<const sockaddr*>(&sim), sizeof sim);
      std::uint8_t buffer[512];
      for (ssize_t n; (n = ::recv(fd_, buffer, sizeof buffer, 0)) > 0;) {
        const auto got = cp::decode_frame(std::span<const std::uint8_t>(buffer, static_cast<std::size_t>(n)));
        if (!got || got->header.timestamp != timestamp_) continue;  // data of a subscription, or a late ACK
        const auto envelope = cp::decode(*got, cp::Direction::from_platform);
        if (envelope && envelope->message.holds<cp::Ack>()) return envelope->message.get<cp::Ack>().result;
      }
    }
    return std::nullopt;
  }

 private:
  static sockaddr_in address(const char* ip, std::uint16_t port) {
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_port = htons(port);
    ::inet_pton(AF_INET, ip, &a.sin_addr);
    return a;
  }
  int fd_ = -1;
  std::uint32_t timestamp_ = 0;
};

class ClearpathSimInputs : public ::testing::Test {
 protected:
  void start(std::vector<std::string> more = {"--status-every", "0.1", "--events"}) {
    dir_ = std::filesystem::temp_directory_path() / ("jaus-sim-inputs-" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir_);
    std::vector<std::string> args{CLEARPATH_SIM_PATH, "--udp", std::string(kSimAddress) + ":" + std::to_string(kSimPort),
                                  "--log-level", "warn"};
    args.insert(args.end(), more.begin(), more.end());
    sim_ = std::make_unique<ChildProcess>(args, (dir_ / "sim.log").string(), ChildProcess::Stdin::pipe);
    ASSERT_TRUE(sim_->started());
    ASSERT_TRUE(client_.command(cp::RequestEcho{}).has_value()) << sim_->output();  // serving
  }
  void TearDown() override {
    sim_.reset();
    std::error_code ignored;
    std::filesystem::remove_all(dir_, ignored);
  }

  // Every JSON line printed so far that has `key`, oldest first; an event
  // ({"event":"input","input":...}) only when asked for "event".
  std::vector<Json> lines_with(const std::string& key) const {
    std::vector<Json> out;
    std::istringstream lines(sim_->output());
    for (std::string l; std::getline(lines, l);) {
      if (l.empty() || l.front() != '{') continue;
      const Json j = Json::parse(l, nullptr, false);
      if (j.is_discarded() || !j.contains(key)) continue;
      if (key != "event" && j.contains("event")) continue;
      out.push_back(j);
    }
    return out;
  }
  // Types a line and returns the first new line with `key` (the answer).
  std::optional<Json> type(const std::string& line, const std::string& key) {
    const auto before = lines_with(key).size();
    if (!sim_->write_stdin(line + "\n")) return std::nullopt;
    return wait_for(key, [&](const std::vector<Json>& all) { return all.size() > before; }, before);
  }
  // Waits until a line with `key` after the first `skip` ones satisfies `good`.
  std::optional<Json> wait_for(const std::string& key, const std::function<bool(const std::vector<Json>&)>& good,
                               std::size_t skip = 0, std::chrono::milliseconds deadline = 10s) const {
    const auto until = std::chrono::steady_clock::now() + deadline;
    while (std::chrono::steady_clock::now() < until) {
      const auto all = lines_with(key);
      if (all.size() > skip && good(all)) return all[skip];
      std::this_thread::sleep_for(20ms);
    }
    return std::nullopt;
  }
  // Waits for a status line whose safety flags, the watchdog bit (0x01) aside, are `flags`.
  std::optional<Json> status_with(std::uint16_t flags) const {
    std::optional<Json> found;
    wait_for("status", [&](const std::vector<Json>& all) {
      const auto& s = all.back()["status"];
      if ((s["safety_flags"].get<int>() & ~0x01) != flags) return false;
      found = s;
      return true;
    });
    return found;
  }

  std::unique_ptr<ChildProcess> sim_;
  RawClient client_;

 private:
  std::filesystem::path dir_;
};

cp::SetSafetySystem safety(std::uint16_t flags) {
  cp::SetSafetySystem m;
  m.flags = flags;
  return m;
}

TEST_F(ClearpathSimInputs, APauseTypedOnStdinSurvivesSetSafetySystem) {
  start();
  const auto paused = type("pause on", "input");
  ASSERT_TRUE(paused) << sim_->output();
  EXPECT_EQ((*paused)["input"], "pause");
  EXPECT_EQ((*paused)["on"], true);
  EXPECT_TRUE((*paused)["safety_flags"].get<int>() & 0x10) << paused->dump();
  auto status = status_with(0x10);
  ASSERT_TRUE(status) << sim_->output();
  EXPECT_EQ((*status)["hardware_inputs"], 0x10);

  // The host's e-stop joins the pause.
  ASSERT_EQ(client_.command(safety(0x08)), 0);
  ASSERT_TRUE(status_with(0x18)) << sim_->output();
  // The host clearing its word: the pause stays.
  ASSERT_EQ(client_.command(safety(0)), 0);
  ASSERT_TRUE(status_with(0x10)) << sim_->output();
  ASSERT_EQ(client_.command(safety(0x08)), 0);
  ASSERT_TRUE(status_with(0x18)) << sim_->output();

  // Released on the platform: the host's e-stop alone.
  const auto released = type("pause off", "input");
  ASSERT_TRUE(released);
  EXPECT_EQ((*released)["on"], false);
  EXPECT_EQ((*released)["safety_flags"].get<int>() & ~0x01, 0x08) << released->dump();
  status = status_with(0x08);
  ASSERT_TRUE(status) << sim_->output();
  EXPECT_EQ((*status)["hardware_inputs"], 0);
}

// `pause for MS`: pressed at once, released by the simulator's own timer MS
// later (never sooner, whenever standard input is read): two answers, and the
// input events MS or more apart on its clock.
TEST_F(ClearpathSimInputs, APauseForATimeIsReleasedByTheSimulatorItself) {
  start();
  const auto before = lines_with("input").size();
  ASSERT_TRUE(sim_->write_stdin("pause for 50\n"));
  const auto answers = wait_for("input", [&](const std::vector<Json>& all) { return all.size() >= before + 2; }, before);
  ASSERT_TRUE(answers) << sim_->output();
  const auto inputs = lines_with("input");
  EXPECT_EQ(inputs[before]["on"], true);
  EXPECT_TRUE(inputs[before]["safety_flags"].get<int>() & 0x10) << inputs[before].dump();
  EXPECT_EQ(inputs[before + 1]["on"], false);
  EXPECT_EQ(inputs[before + 1]["safety_flags"].get<int>() & 0x10, 0) << inputs[before + 1].dump();
  std::vector<std::int64_t> edges;
  for (const auto& e : lines_with("event"))
    if (e["event"] == "input" && e["input"] == "pause") edges.push_back(e["steady_ns"].get<std::int64_t>());
  ASSERT_EQ(edges.size(), 2u) << sim_->output();
  EXPECT_GE(edges[1] - edges[0], 50'000'000);
  // Out of range or not a number: an error, nothing pressed.
  ASSERT_TRUE(type("pause for 0", "error"));
  ASSERT_TRUE(type("pause for 10001", "error"));
  ASSERT_TRUE(type("estop for x", "error"));
  const auto status = status_with(0);
  ASSERT_TRUE(status) << sim_->output();
  EXPECT_EQ((*status)["hardware_inputs"], 0);
}

TEST_F(ClearpathSimInputs, AnUnknownLineIsAnErrorAndChangesNothing) {
  start();
  ASSERT_TRUE(type("estop on", "input"));
  const auto error = type("xyz", "error");
  ASSERT_TRUE(error) << sim_->output();
  EXPECT_EQ((*error)["error"], "unknown input line 'xyz': expected estop on|off, pause on|off, estop|pause for MS, deaf on|off");
  ASSERT_TRUE(type("pause sideways", "error"));
  const auto status = status_with(0x08);
  ASSERT_TRUE(status) << sim_->output();
  EXPECT_EQ((*status)["hardware_inputs"], 0x08);
  EXPECT_TRUE(sim_->running());
}

TEST_F(ClearpathSimInputs, EventsCarryTheSteadyClockOfThisMachine) {
  start();
  const auto before = steady_ns_now();
  ASSERT_TRUE(type("estop on", "input"));
  const auto after = steady_ns_now();
  // The events come out before the answer.
  std::optional<Json> pressed, changed;
  for (const auto& e : lines_with("event")) {
    if (e["event"] == "input") pressed = e;
    if (e["event"] == "safety" && (e["flags"].get<int>() & 0x08)) changed = e;
  }
  ASSERT_TRUE(pressed && changed) << sim_->output();
  EXPECT_EQ((*pressed)["input"], "estop");
  EXPECT_EQ((*pressed)["on"], true);
  EXPECT_GE((*pressed)["steady_ns"].get<std::int64_t>(), before);
  EXPECT_LE((*pressed)["steady_ns"].get<std::int64_t>(), after);
  EXPECT_EQ((*changed)["steady_ns"], (*pressed)["steady_ns"]);
}

TEST_F(ClearpathSimInputs, StatusPrintsAtOnceAndTheEndOfInputIsNoReasonToExit) {
  start({});  // no --status-every: only asked for
  const auto status = type("status", "status");
  ASSERT_TRUE(status) << sim_->output();
  EXPECT_EQ((*status)["status"]["hardware_inputs"], 0);
  EXPECT_TRUE((*status)["status"].contains("safety_flags"));
  sim_->close_stdin();  // as with stdin at /dev/null
  std::this_thread::sleep_for(300ms);
  EXPECT_TRUE(sim_->running());
  EXPECT_EQ(client_.command(safety(0x08)), 0) << sim_->output();
}

// A one-way line: --deaf-after S, then the platform ignores every frame it
// receives (no ACK, nothing applied) until `deaf off`; `deaf on` again at once.
TEST_F(ClearpathSimInputs, DeafAfterIgnoresEveryFrameUntilDeafOff) {
  start({"--status-every", "0.1", "--deaf-after", "4"});
  // The e-stop bit, set while it hears and again until it no longer does.
  const auto until = std::chrono::steady_clock::now() + 30s;
  bool unheard = false;
  while (!unheard && std::chrono::steady_clock::now() < until) {
    unheard = !client_.command(safety(0x08)).has_value();
    if (!unheard) std::this_thread::sleep_for(100ms);
  }
  ASSERT_TRUE(unheard) << sim_->output();
  const auto deaf = wait_for("status", [](const std::vector<Json>& all) { return all.back()["status"]["deaf"] == true; });
  ASSERT_TRUE(deaf) << sim_->output();
  // A release it does not hear is neither answered nor applied.
  EXPECT_FALSE(client_.command(safety(0)).has_value()) << sim_->output();
  std::this_thread::sleep_for(300ms);
  EXPECT_TRUE(status_with(0x08)) << sim_->output();
  const auto hears = type("deaf off", "deaf");
  ASSERT_TRUE(hears) << sim_->output();
  EXPECT_EQ((*hears)["deaf"], false);
  EXPECT_EQ(client_.command(safety(0)), 0) << sim_->output();
  EXPECT_TRUE(status_with(0)) << sim_->output();
  const auto deaf_again = type("deaf on", "deaf");
  ASSERT_TRUE(deaf_again) << sim_->output();
  EXPECT_EQ((*deaf_again)["deaf"], true);
  EXPECT_FALSE(client_.command(safety(0x08)).has_value()) << sim_->output();
  std::this_thread::sleep_for(300ms);
  EXPECT_TRUE(status_with(0)) << sim_->output();
}

}  // namespace
}  // namespace jaus::test
