// The built jausctl binary: bad input exits 2 with one line, silence exits 1
// with the timeout line, and the OCU commands work end to end against a node
// running on a thread of this process (SIGINT releases control).
#include <utility>  // Boost 1.74's Asio headers need it first

#include <gtest/gtest.h>

#include <boost/asio/executor_work_guard.hpp>
#include <boost/asio/ip/udp.hpp>
#include <boost/asio/post.hpp>
#include <csignal>
#include <future>
#include <nlohmann/json.hpp>
#include <thread>

#include "jausctl_process.hpp"
#include "target_node.hpp"

namespace jausctl::test {
namespace {

std::size_t line_count(const std::string& text) { return static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n')); }

// A UDP socket that receives and never answers: a port where a node "is" but is silent.
struct SilentPeer {
  boost::asio::io_context io;
  boost::asio::ip::udp::socket socket{io, boost::asio::ip::udp::endpoint(boost::asio::ip::make_address_v4("127.0.0.1"), 0)};
  std::string endpoint() const { return "127.0.0.1:" + std::to_string(socket.local_endpoint().port()); }
};

struct BadInput {
  std::vector<std::string> args;
  std::string error;  // the whole stderr line
};

// Test names and failures show the command line, not the struct's bytes.
void PrintTo(const BadInput& b, std::ostream* os) {
  *os << "jausctl";
  for (const auto& a : b.args) *os << " " << a;
}

class JausctlBadInput : public ::testing::TestWithParam<BadInput> {};

TEST_P(JausctlBadInput, ExitsTwoWithOneLineNamingTheProblem) {
  const auto r = run(GetParam().args);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err, GetParam().error + "\n");
  EXPECT_EQ(r.out, "");
}

INSTANTIATE_TEST_SUITE_P(
    Cases, JausctlBadInput,
    ::testing::Values(
        BadInput{{"status", "1.1.x.1"},
                 "jausctl status: bad address '1.1.x.1': expected S.N.C.I (subsystem.node.component.instance)"},
        BadInput{{"status", "1.1.0.1"}, "jausctl status: bad address '1.1.0.1': 0 is not a valid ID at any level"},
        BadInput{{"query", "1.1.35.1", "0x1234"},
                 "jausctl query: unknown message code 0x1234 (jausctl msg list shows every code)"},
        BadInput{{"query", "1.1.35.1", "0x2002", "--pv", "1"},
                 "jausctl query: Query Component Status (0x2002) has no presence vector (--pv)"},
        BadInput{{"query", "1.1.35.1", "0x2402", "--pv", "zz"},
                 "jausctl query: --pv: bad presence vector 'zz': expected hex such as 0x1F (at most 32 bits)"},
        BadInput{{"send", "1.1.35.1", "{\"code\":"}, "jausctl send: the message is not valid JSON"},
        BadInput{{"send", "1.1.35.1", "{\"code\":\"0x0006\",\"fields\":{\"emergency_code\":\"stop\"}}"},
                 "jausctl send: bad JSON: 'emergency_code': expected an object {stop, other_bits} or a number"},
        BadInput{{"send", "1.1.35.1", "{\"code\":\"0x1234\"}"},
                 "jausctl send: offset 0, field 'code': unknown command code (0x1234)"},
        BadInput{{"control", "1.1.35.1", "--authority", "256"},
                 "jausctl control: --authority: bad authority '256': expected 0..255"},
        BadInput{{"control", "1.1.255.1", "--authority", "5"},
                 "jausctl control: bad address '1.1.255.1': 255 (broadcast) is not allowed here"},
        BadInput{{"subscribe", "1.1.35.1", "0x2002", "--rate", "5"},
                 "jausctl subscribe: 0x2002 is a query: subscribe takes the report's code (0x4002)"},
        BadInput{{"subscribe", "1.1.35.1", "0x4002", "--rate", "-3"},
                 "jausctl subscribe: --rate: bad rate '-3': expected Hz, more than 0 and at most 1092"},
        BadInput{{"query", "1.1.37.1", "Query Camera Pose", "--save-image", "pose.png"},
                 "jausctl query: --save-image needs Query Image (0x2807)"},
        BadInput{{"subscribe", "1.1.37.1", "0x4800", "--rate", "1", "--save-image", "pose.png"},
                 "jausctl subscribe: --save-image needs Report Image (0x4807)"},
        BadInput{{"emergency", "1.1.35.1", "maybe"}, "jausctl emergency: bad action 'maybe': expected set or clear"},
        BadInput{{"status", "1.1.35.1", "--to", "localhost"},
                 "jausctl status: --to: bad endpoint 'localhost': expected an IPv4 address a.b.c.d[:port]"},
        BadInput{{"status", "1.1.35.1", "--timeout", "0"},
                 "jausctl status: --timeout: bad duration '0': expected seconds, more than 0 and at most 86400"},
        BadInput{{"emergency", "1.1.35.1", "set", "--stop-give-up-after", "0.05"},
                 "jausctl emergency: stop-give-up-after 50 ms is out of range 100 ms..3600 s"},
        BadInput{{"status", "1.1.35.1", "--rto-min", "3", "--rto-max", "1"},
                 "jausctl status: rto-max (1 s) is below rto-min (3 s)"},
        BadInput{{"send", "1.1.35.1", "{\"name\":\"Resume\"}", "--give-up-after", "soon"},
                 "jausctl send: --give-up-after: bad duration 'soon': expected seconds, more than 0"},
        BadInput{{"status", "1.1.35.1", "--as", "254.1.1.1"},
                 "jausctl status: --as: component 1 is the OCU's node manager; use another component ID (e.g. 40)"},
        BadInput{{"status", "1.1.35.1", "--framing", "udp"},
                 "jausctl status: --framing: bad framing 'udp': expected opc or judp"},
        BadInput{{"control", "1.1.35.1", "--authority", "5", "--resume-when-ready"},
                 "jausctl control: --resume-when-ready needs --send"},
        BadInput{{"control", "1.1.35.1"}, "jausctl: --authority is required (--help for usage)"}));

// The man page is made of these lines (one per option), and a terminal shows them unwrapped.
TEST(JausctlCli, EveryHelpLineFitsIn120Columns) {
  const std::vector<std::vector<std::string>> commands = {
      {},          {"discover"},  {"status"},    {"query"},           {"send"},         {"control"},
      {"subscribe"}, {"emergency"}, {"msg"},     {"clearpath"}};
  for (auto args : commands) {
    args.push_back("--help");
    const auto r = run(args);
    EXPECT_EQ(r.exit_code, 0) << args.front();
    std::istringstream in(r.out);
    for (std::string line; std::getline(in, line);) EXPECT_LE(line.size(), 120u) << line;
  }
}

TEST(JausctlCli, SilenceExitsOneWithTheTimeoutLine) {
  SilentPeer peer;
  const auto r = run({"status", "1.1.33.1", "--to", peer.endpoint(), "--timeout", "0.3"});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err, "jausctl status: no reply from 1.1.33.1 within 0.3 s\n");
  EXPECT_EQ(r.out, "");
}

TEST(JausctlCli, ABusyBindPortIsOneLine) {
  SilentPeer busy;
  const auto r = run({"status", "1.1.35.1", "--bind", busy.endpoint(), "--timeout", "0.3"});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err, "jausctl status: " + busy.endpoint() + " is already in use\n");
}

// A target node on its own thread, for the binary to talk to.
class JausctlEndToEnd : public ::testing::Test {
 protected:
  void SetUp() override {
    TargetOptions options{kControllerTimeout, false};
    options.primitive_driver = true;
    target = std::make_unique<TargetNode>(context, options);
    thread = std::thread([this] { context.run(); });
  }
  void TearDown() override {
    work.reset();
    context.stop();
    thread.join();
    target.reset();
  }
  std::string to() const { return "127.0.0.1:" + std::to_string(target->endpoint().port); }
  // Reads the target's state on its own thread.
  template <class F>
  auto on_target(F f) {
    std::packaged_task<decltype(f())()> task(f);
    auto result = task.get_future();
    boost::asio::post(context, [&task] { task(); });
    return result.get();
  }
  // Generous: a loaded 2-core machine under ASan can stall either process for a while.
  bool eventually(const std::function<bool()>& condition) {
    const auto deadline = std::chrono::steady_clock::now() + 10s;
    while (!on_target(condition)) {
      if (std::chrono::steady_clock::now() > deadline) return false;
      std::this_thread::sleep_for(10ms);
    }
    return true;
  }

  // The target checks its controller every 0.5 s: only a stall of about a
  // second would make it drop a jausctl that answers.
  static constexpr jaus::rt::Duration kControllerTimeout = 1500ms;
  boost::asio::io_context context;
  std::optional<boost::asio::executor_work_guard<boost::asio::io_context::executor_type>> work{context.get_executor()};
  std::unique_ptr<TargetNode> target;
  std::thread thread;
};

TEST_F(JausctlEndToEnd, Status) {
  const auto r = run({"status", "1.1.35.1", "--to", to(), "--timeout", "5"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["primary_status"], "ready");
}

TEST_F(JausctlEndToEnd, SendReadsStdinAndQueryPrintsTheReport) {
  // One ID for both runs: each jausctl run is a fresh ID otherwise, and only the holder clears its hold.
  auto r = run({"send", "1.1.35.1", "-", "--as", "254.3.40.1", "--to", to(), "--timeout", "0.2"},
               R"({"code":"0x0006","fields":{"emergency_code":1}})");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  ASSERT_TRUE(eventually([&] { return target->communicator().state() == jaus::msg::PrimaryStatus::emergency; }));
  r = run({"query", "1.1.35.1", "Query Component Status", "--to", to(), "--timeout", "5"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out)["fields"]["primary_status"], "emergency");
  r = run({"emergency", "1.1.35.1", "clear", "--as", "254.3.40.1", "--to", to(), "--timeout", "5"});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out, "1.1.35.1: emergency cleared by 254.3.40.1 (state Ready)\n");
}

// `send` of a command says the ID it acted as (on stderr: stdout is the reply's JSON).
TEST_F(JausctlEndToEnd, SendOfACommandSaysTheIdItActedAs) {
  const auto r = run({"send", "1.1.35.1", R"({"name":"Set Emergency","fields":{"emergency_code":1}})", "--as",
                      "254.4.40.1", "--to", to(), "--timeout", "0.2"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "jausctl send: Set Emergency to 1.1.35.1 by 254.4.40.1 (acknowledged)\n");
  const auto cleared = run({"emergency", "1.1.35.1", "clear", "--as", "254.4.40.1", "--to", to(), "--timeout", "5"});
  EXPECT_EQ(cleared.exit_code, 0) << cleared.err;
}

// Issue 49: one user's runs are one operator (the ID kept in its state
// directory): `set` then `clear` just works, without --as.
TEST_F(JausctlEndToEnd, SetThenClearWithoutAsIsOneOperator) {
  char dir_template[] = "/tmp/jausctl_state_XXXXXX";
  const std::string state = mkdtemp(dir_template);
  Jausctl set({"emergency", "1.1.35.1", "set", "--to", to(), "--timeout", "5"}, "", state);
  const auto s = set.finish();
  ASSERT_EQ(s.exit_code, 0) << s.err;
  const std::string kept = read_file(state + "/jaus/operator-id");
  ASSERT_FALSE(kept.empty());
  const std::string id = kept.substr(0, kept.find('\n'));
  EXPECT_EQ(s.out, "1.1.35.1: emergency set by " + id + " (state Emergency)\n");
  Jausctl clear({"emergency", "1.1.35.1", "clear", "--to", to(), "--timeout", "5"}, "", state);
  const auto c = clear.finish();
  EXPECT_EQ(c.exit_code, 0) << c.err;
  EXPECT_EQ(c.out, "1.1.35.1: emergency cleared by " + id + " (state Ready)\n");
  std::system(("rm -rf " + state).c_str());
}

// Two processes acting as one ID would get each other's replies: while one
// holds control as it, a second control is refused, naming --as; a stop is
// never refused: it shares the ID (so a plain clear releases it), and a
// shared command reads no reply as its own (the holder's status reports
// reach it too).
TEST_F(JausctlEndToEnd, WhileAnotherRunHoldsTheIdControlIsRefusedAndCommandsShareIt) {
  char dir_template[] = "/tmp/jausctl_state_XXXXXX";
  const std::string state = mkdtemp(dir_template);
  Jausctl control({"control", "1.1.35.1", "--authority", "9", "--to", to()}, "", state);
  ASSERT_TRUE(control.wait_for_output("granted"));
  const std::string kept = read_file(state + "/jaus/operator-id");
  const std::string id = kept.substr(0, kept.find('\n'));

  Jausctl second({"control", "1.1.33.1", "--authority", "9", "--to", to()}, "", state);
  const auto refused = second.finish();
  EXPECT_EQ(refused.exit_code, 1);
  EXPECT_NE(refused.err.find("jausctl control: " + id + " is in use by another process (pid "), std::string::npos)
      << refused.err;
  EXPECT_NE(refused.err.find("give another ID with --as"), std::string::npos) << refused.err;

  // The holder's Report Component Status (5 Hz) is addressed to the same ID: none is printed as a reply.
  Jausctl resume({"send", "1.1.35.1", R"({"name":"Resume"})", "--to", to(), "--timeout", "1"}, "", state);
  const auto shared = resume.finish();
  EXPECT_EQ(shared.exit_code, 0) << shared.err;
  EXPECT_EQ(shared.out, "");
  EXPECT_NE(shared.err.find("shared with it"), std::string::npos) << shared.err;
  EXPECT_NE(shared.err.find("jausctl send: Resume to 1.1.35.1 by " + id + " (acknowledged)\n"), std::string::npos)
      << shared.err;

  Jausctl set({"emergency", "1.1.35.1", "set", "--to", to(), "--timeout", "5"}, "", state);
  const auto stop = set.finish();
  ASSERT_EQ(stop.exit_code, 0) << stop.err;
  EXPECT_EQ(stop.out, "1.1.35.1: emergency set by " + id + " (state Emergency)\n");
  Jausctl clear({"emergency", "1.1.35.1", "clear", "--to", to(), "--timeout", "5"}, "", state);
  const auto cleared = clear.finish();
  EXPECT_EQ(cleared.exit_code, 0) << cleared.err;
  EXPECT_EQ(cleared.out, "1.1.35.1: emergency cleared by " + id + " (state Ready)\n");

  control.signal(SIGINT);
  control.finish();  // whatever the Emergency did to its control: it ends
  std::system(("rm -rf " + state).c_str());
}

TEST_F(JausctlEndToEnd, SubscribeCountsReportsAndTerminates) {
  const auto r =
      run({"subscribe", "1.1.38.1", "0x4402", "--rate", "10", "--count", "3", "--to", to(), "--timeout", "5"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(line_count(r.out), 3u);
  EXPECT_TRUE(eventually([&] { return target->pose_sensor().service_connections().active() == 0; }));
}

TEST_F(JausctlEndToEnd, ControlHeldUntilSigintThenReleased) {
  Jausctl control({"control", "1.1.35.1", "--authority", "9", "--to", to()});
  ASSERT_TRUE(control.wait_for_output("granted"));
  // Held past the controller timeout and the check after it (which drops a
  // silent controller): the liveness checks are answered.
  std::this_thread::sleep_for(kControllerTimeout + 1s);
  EXPECT_TRUE(on_target([&] { return target->communicator().control().controller().has_value(); }));
  control.signal(SIGINT);
  const auto r = control.finish();
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("control of 1.1.35.1 released after "), std::string::npos) << r.out;
  EXPECT_TRUE(eventually([&] { return !target->communicator().control().controller().has_value(); }));
}

// What an operator sees: streaming a command, the driver set in Emergency by
// someone else: jausctl stops sending, says why, releases control, exits 3.
TEST_F(JausctlEndToEnd, ControlSendStopsForGoodWhenTheDriverEntersEmergency) {
  Jausctl control({"control", "1.1.33.1", "--authority", "9", "--rate", "20", "--to", to(), "--send",
                   R"({"name":"Set Wrench Effort","fields":{"propulsive_linear_effort_x_percent":60}})"});
  ASSERT_TRUE(control.wait_for_output("1.1.33.1: state Ready\n"));
  ASSERT_TRUE(eventually([&] { return target->driver().driver_counters().efforts_applied >= 3; }));
  const auto emergency = run({"emergency", "1.1.33.1", "set", "--as", "254.2.40.1", "--to", to(), "--timeout", "5"});
  EXPECT_EQ(emergency.exit_code, 0) << emergency.err;
  const auto r = control.finish();
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_EQ(r.err,
            "jausctl control: 1.1.33.1 entered Emergency: stopped sending Set Wrench Effort; not resuming "
            "(see --resume-when-ready)\n");
  EXPECT_TRUE(eventually([&] { return !target->driver().control().controller().has_value(); }));
}

}  // namespace
}  // namespace jausctl::test
