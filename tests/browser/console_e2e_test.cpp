// jaus-console end to end through headless Chromium (issue 31): a default
// jausd on 127.0.0.120, jaus-console on it, and the operator's page in
// Chromium driven over the DevTools protocol as an operator would (clicks and
// key presses). What the vehicle does is read back with `jausctl query` /
// `jausctl status` against the jausd, never from the console itself.
// A screenshot of each step goes to SCREENSHOT_DIR (the console-screenshots
// target copies some to docs/images/console/). Waits poll with deadlines.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <string>

#include "console_session.hpp"
#include "require_chromium.hpp"

namespace jaus::test::browser {
namespace {

constexpr const char* kNode = "127.0.0.120";
constexpr const char* kConsoleJaus = "127.0.0.121:3794";
constexpr const char* kConsoleHttp = "127.0.0.121:8080";
constexpr const char* kQueryBind = "127.0.0.122:0";
constexpr const char* kDriver = "12.1.33.1";
constexpr const char* kVelocitySensor = "12.1.42.1";
constexpr const char* kVisualSensor = "12.1.37.1";

class ConsoleInChromium : public ::testing::Test {
 protected:
  void SetUp() override {
    JAUS_REQUIRE_CHROMIUM();
    jausd = std::make_unique<DefaultJausd>("console-e2e", 12, kNode);
    ASSERT_TRUE(jausd->started());
    console = start_console(*jausd, kNode, kConsoleJaus, kConsoleHttp);
    ASSERT_TRUE(console->started());
    auto launched = Chromium::launch();
    ASSERT_TRUE(launched) << launched.error().message();
    chromium = std::move(*launched);
    auto connected = CdpClient::connect(*chromium);
    ASSERT_TRUE(connected) << connected.error().message();
    cdp = std::move(*connected);
  }
  void TearDown() override {
    cdp.reset();
    chromium.reset();
    console.reset();
    jausd.reset();
  }

  std::string page_url() const { return std::string("http://") + kConsoleHttp + "/"; }
  std::string diagnostics() const {
    return "\n--- jaus-console ---\n" + (console ? console->output() : "") + "\n--- jausd (tail) ---\n" +
           (jausd ? tail(jausd->output()) : "");
  }
  static std::string tail(const std::string& text) { return text.size() > 4000 ? text.substr(text.size() - 4000) : text; }

  void screenshot(Tab& tab, const std::string& name) {
    auto saved = tab.screenshot(std::filesystem::path(SCREENSHOT_DIR) / (name + ".png"));
    EXPECT_TRUE(saved) << saved.error().message();
  }
  // True once `expression` is true in the page within `deadline`.
  bool page_shows(Tab& tab, const std::string& expression, std::chrono::milliseconds deadline) {
    auto result = tab.wait_until(expression, deadline);
    return result && result->is_boolean() && result->get<bool>();
  }

  // Report Velocity State's forward speed, by `jausctl query` against the jausd (nothing if no answer).
  std::optional<double> forward_speed() {
    auto child = jausd->jausctl_own_id("query", {"query", kVelocitySensor, "0x2404", "--pv", "0x1FF", "--timeout", "2"},
                                       kQueryBind);
    auto report = json_line_of(*child);
    if (!report || !report->contains("fields") || !(*report)["fields"].contains("velocity_x_mps")) return std::nullopt;
    return (*report)["fields"]["velocity_x_mps"].get<double>();
  }
  // Polls the speed until `good` holds for it; the last one heard either way (-1: none).
  double speed_once(const std::function<bool(double)>& good, std::chrono::milliseconds deadline) {
    const auto until = Clock::now() + deadline;
    double last = -1;
    while (true) {
      if (auto v = forward_speed()) {
        last = *v;
        if (good(last)) return last;
      }
      if (Clock::now() >= until) return last;
      std::this_thread::sleep_for(50ms);
    }
  }
  // The driver's state by `jausctl status` ("ready", "emergency", ...), until `wanted` or the deadline.
  std::string driver_status_once(const std::string& wanted, std::chrono::milliseconds deadline) {
    const auto until = Clock::now() + deadline;
    std::string last;
    while (true) {
      auto child = jausd->jausctl_own_id("status", {"status", kDriver, "--timeout", "2"}, kQueryBind);
      if (auto status = json_line_of(*child); status && (*status)["primary_status"].is_string())
        last = (*status)["primary_status"].get<std::string>();
      if (last == wanted || Clock::now() >= until) return last;
      std::this_thread::sleep_for(100ms);
    }
  }

  // Takes control of the driver from the page and makes it Ready (Resume when it is not), asking
  // again while the console's view of the driver lags (its tree is polled every second).
  void take_control(Tab& tab) {
    const std::string held = "window.jausConsole.state.control.get('" + std::string(kDriver) + "')?.state === 'held'";
    const auto until = Clock::now() + 30s;
    while (Clock::now() < until) {
      ASSERT_TRUE(tab.click("#control-request"));
      if (!page_shows(tab, console_controls(kDriver), 5s)) continue;
      if (value_of(tab.evaluate(component_state(kDriver)), Json()) != "ready") {
        ASSERT_TRUE(tab.click("#state-resume"));
      }
      if (page_shows(tab, component_state(kDriver) + " === 'ready' && " + held, 5s)) return;
    }
    FAIL() << "no control of " << kDriver << " from the page" << diagnostics();
  }

  std::unique_ptr<DefaultJausd> jausd;
  std::unique_ptr<ChildProcess> console;
  std::unique_ptr<Chromium> chromium;
  std::unique_ptr<CdpClient> cdp;
};

TEST_F(ConsoleInChromium, TheOperatorDrivesWatchesStopsAndClosesTheTab) {
  auto opened = open_console_page(*cdp, page_url(), 30s);
  ASSERT_TRUE(opened) << opened.error().message() << diagnostics();
  Tab& tab = *opened;

  // 1. The page lists the components of the default jausd.
  ASSERT_TRUE(page_shows(tab, tree_lists(kDriver) + " && " + tree_lists(kVelocitySensor) + " && " +
                                  tree_lists(kVisualSensor), 30s))
      << diagnostics();
  EXPECT_GE(value_of(tab.evaluate("document.querySelectorAll('#tree .component').length"), Json(0)).get<int>(), 10);
  screenshot(tab, "01-tree");

  // 2. Control of the primitive driver, taken from the page.
  take_control(tab);
  if (HasFatalFailure()) return;
  screenshot(tab, "02-control");

  // 3. Holding the forward key drives: Report Velocity State says forward, and the map moves.
  const double start_x = value_of(tab.evaluate("Number(document.getElementById('map').dataset.x || 0)"), Json(0)).get<double>();
  ASSERT_TRUE(tab.key_down("ArrowUp"));
  EXPECT_GT(speed_once([](double v) { return v > 0.2; }, 20s), 0.2) << diagnostics();
  EXPECT_TRUE(page_shows(tab, "Number(document.getElementById('map').dataset.x) > " + std::to_string(start_x + 0.3), 20s))
      << value_of(tab.evaluate("document.getElementById('map').dataset.x"), Json()).dump() << diagnostics();
  EXPECT_TRUE(page_shows(tab, "document.getElementById('driving-status').dataset.sending === 'true'", 5s));
  // Forward and right together: the heading turns clockwise (the map shows the curve).
  ASSERT_TRUE(tab.key_down("ArrowRight"));
  EXPECT_TRUE(page_shows(tab, "window.jausConsole.state.drive.angular > 0 && [...window.jausConsole.state.pose.values()]"
                              ".some((p) => p.yaw_rad > 0.8) && [...window.jausConsole.state.velocity.values()]"
                              ".some((v) => v.yaw_rate_rps > 0.2)", 20s))
      << diagnostics();
  screenshot(tab, "03-driving");
  ASSERT_TRUE(tab.key_up("ArrowRight"));

  // 4. Letting go stops it within the driver's command timeout (0.5 s) and its braking, with a
  //    margin for jausctl's own start on a loaded machine.
  ASSERT_TRUE(tab.key_up("ArrowUp"));
  const auto released = Clock::now();
  EXPECT_EQ(speed_once([](double v) { return v == 0.0; }, 10s), 0.0) << diagnostics();
  const auto stop_ms = std::chrono::duration_cast<std::chrono::milliseconds>(Clock::now() - released).count();
  std::printf("speed zero seen %lld ms after the key went up (jausctl query included)\n", static_cast<long long>(stop_ms));
  EXPECT_LT(stop_ms, 3000) << diagnostics();
  EXPECT_EQ(speed_once([](double v) { return v == 0.0; }, 2s), 0.0);  // and it stays stopped
  EXPECT_TRUE(page_shows(tab, "document.getElementById('deadman').textContent.startsWith('released')", 2s));
  screenshot(tab, "04-released");

  // The on-screen stick (pointer events): pressed and pushed up drives forward, let go stops sending.
  {
    auto stick = tab.center_of("#stick");
    ASSERT_TRUE(stick) << stick.error().message();
    const double x = (*stick)["x"].get<double>(), y = (*stick)["y"].get<double>();
    ASSERT_TRUE(tab.mouse("mousePressed", x, y));
    ASSERT_TRUE(tab.mouse("mouseMoved", x, y - 60));
    EXPECT_TRUE(page_shows(tab, "window.jausConsole.state.drive.held && window.jausConsole.state.drive.linear > 30 && "
                                "document.getElementById('driving-status').dataset.sending === 'true'", 5s))
        << value_of(tab.evaluate("JSON.stringify(window.jausConsole.state.drive)"), Json()).dump() << diagnostics();
    ASSERT_TRUE(tab.mouse("mouseReleased", x, y - 60));
    EXPECT_TRUE(page_shows(tab, "!window.jausConsole.state.drive.held && "
                                "document.getElementById('driving-status').dataset.sending === 'false'", 5s));
    EXPECT_EQ(speed_once([](double v) { return v == 0.0; }, 10s), 0.0) << diagnostics();
  }

  // 5. The camera panel shows the live images: at least two different frames, and a pan moves the picture.
  ASSERT_TRUE(tab.click("#camera-watch"));
  ASSERT_TRUE(page_shows(tab, "!!document.getElementById('camera-image').dataset.frame", 20s)) << diagnostics();
  const Json first = value_of(tab.evaluate("document.getElementById('camera-image').src"), Json());
  ASSERT_TRUE(first.is_string());
  ASSERT_TRUE(tab.evaluate("(() => { const p = document.getElementById('camera-pan'); p.value = 60;"
                           " p.dispatchEvent(new Event('input')); return true; })()"));
  EXPECT_TRUE(page_shows(tab, "document.getElementById('camera-image').src !== " + first.dump(), 20s))
      << "the camera showed one frame only" << diagnostics();
  EXPECT_TRUE(page_shows(tab, "document.getElementById('camera-image').complete && "
                              "document.getElementById('camera-image').naturalWidth > 0", 5s));
  screenshot(tab, "05-camera");

  // 6. The emergency button puts the driver in Emergency; the page shows who holds it; Clear lets go.
  ASSERT_TRUE(tab.click("#emergency"));
  EXPECT_EQ(driver_status_once("emergency", 15s), "emergency") << diagnostics();
  EXPECT_TRUE(page_shows(tab, "document.getElementById('emergency').dataset.active === 'true'", 10s)) << diagnostics();
  screenshot(tab, "06-emergency");
  ASSERT_TRUE(tab.click("#emergency-clear"));
  EXPECT_NE(driver_status_once("standby", 15s), "emergency") << diagnostics();
  EXPECT_TRUE(page_shows(tab, "document.getElementById('emergency').dataset.active === 'false'", 10s)) << diagnostics();
  screenshot(tab, "07-emergency-cleared");

  // 7. After the emergency, a second tab takes control again and drives; closing it while it drives stops
  //    the vehicle (the page's pagehide and the server's socket deadman).
  {
    auto second = open_console_page(*cdp, page_url(), 20s);
    ASSERT_TRUE(second) << second.error().message();
    ASSERT_TRUE(page_shows(*second, tree_lists(kDriver), 20s)) << diagnostics();
    take_control(*second);
    if (HasFatalFailure()) return;
    ASSERT_TRUE(second->key_down("ArrowUp"));
    EXPECT_GT(speed_once([](double v) { return v > 0.2; }, 20s), 0.2) << diagnostics();
    screenshot(*second, "08-driving-before-close");
    ASSERT_TRUE(second->close());
    const auto closed = Clock::now();
    EXPECT_EQ(speed_once([](double v) { return v == 0.0; }, 10s), 0.0) << diagnostics();
    std::printf("speed zero seen %lld ms after the driving tab closed\n",
                static_cast<long long>(std::chrono::duration_cast<std::chrono::milliseconds>(Clock::now() - closed).count()));
    EXPECT_EQ(speed_once([](double v) { return v == 0.0; }, 2s), 0.0);
  }
}

// The arm panel: one slider per joint within its limits; moving one (with
// control of the manipulator) moves the joint, and the position read back
// follows.
TEST_F(ConsoleInChromium, TheArmFollowsItsSlider) {
  constexpr const char* kArm = "12.1.49.1";
  auto opened = open_console_page(*cdp, page_url(), 30s);
  ASSERT_TRUE(opened) << opened.error().message() << diagnostics();
  Tab& tab = *opened;
  ASSERT_TRUE(page_shows(tab, tree_lists(kArm) + " && !!document.getElementById('arm-joint-0')", 30s)) << diagnostics();
  // The emergency button stops the vehicle: its target is the primitive driver unless the operator chose another.
  EXPECT_TRUE(page_shows(tab, "document.getElementById('emergency-target').value === '" + std::string(kDriver) + "'", 5s));
  // base_yaw's limits in config/jausd.yaml (carried in radians, scaled: within a tenth of a degree).
  const Json limits = value_of(tab.evaluate("[Number(document.getElementById('arm-joint-0').min),"
                                            " Number(document.getElementById('arm-joint-0').max)]"),
                               Json{0, 0});
  EXPECT_NEAR(limits[0].get<double>(), -170, 0.1) << limits.dump();
  EXPECT_NEAR(limits[1].get<double>(), 170, 0.1) << limits.dump();

  ASSERT_TRUE(tab.evaluate("(() => { const t = document.getElementById('control-target'); t.value = '" + std::string(kArm) +
                           "'; t.dispatchEvent(new Event('change')); return true; })()"));
  const auto until = Clock::now() + 30s;
  bool ready = false;
  while (!ready && Clock::now() < until) {
    ASSERT_TRUE(tab.click("#control-request"));
    if (!page_shows(tab, console_controls(kArm), 5s)) continue;
    if (value_of(tab.evaluate(component_state(kArm)), Json()) != "ready") {
      ASSERT_TRUE(tab.click("#state-resume"));
    }
    ready = page_shows(tab, component_state(kArm) + " === 'ready'", 5s);
  }
  ASSERT_TRUE(ready) << diagnostics();

  ASSERT_TRUE(tab.evaluate("(() => { const j = document.getElementById('arm-joint-0'); j.value = 30;"
                           " j.dispatchEvent(new Event('input')); return true; })()"));
  EXPECT_TRUE(page_shows(tab, "window.jausConsole.state.arm.get('" + std::string(kArm) + "')[0].position > 25", 20s))
      << value_of(tab.evaluate("JSON.stringify(window.jausConsole.state.arm.get('" + std::string(kArm) + "'))"), Json())
             .dump()
      << diagnostics();
  screenshot(tab, "09-arm");
}

// A console with a token: the page opened with ?token= passes it on to its
// WebSocket and connects; opened without it, the console refuses the socket
// and the page keeps saying it is not connected.
TEST_F(ConsoleInChromium, ThePagePassesTheConsolesTokenOn) {
  console.reset();
  console = std::make_unique<ChildProcess>(
      std::vector<std::string>{JAUS_CONSOLE_PATH, "--to", kNode, "--bind", kConsoleJaus, "--listen", kConsoleHttp,
                               "--token", "field-laptop-7"},
      (jausd->dir() / "jaus-console-token.log").string());
  auto with_token = open_console_page(*cdp, page_url() + "?token=field-laptop-7", 30s);
  ASSERT_TRUE(with_token) << with_token.error().message() << diagnostics();
  EXPECT_TRUE(page_shows(*with_token, tree_lists(kDriver), 30s)) << diagnostics();

  auto without = Tab::open(*cdp, page_url());
  ASSERT_TRUE(without) << without.error().message();
  // Several refused attempts (the page backs off from 0.5 s), never connected.
  EXPECT_TRUE(page_shows(*without, "document.getElementById('link-status').textContent.startsWith('reconnecting')", 10s));
  EXPECT_FALSE(page_shows(*without, "document.getElementById('link-status').classList.contains('ok')", 2s));
  EXPECT_EQ(value_of(without->evaluate("window.jausConsole.state.self"), Json("?")), Json());
}

}  // namespace
}  // namespace jaus::test::browser
