// The mission end to end, with real processes: `jausctl control --send` takes
// control of the primitive driver of a jausd running its default components
// and drives it; an observer OCU (this test) sees the global pose and the
// velocity change; `jausctl emergency set` stops the vehicle although the
// controller keeps sending efforts. Only outcomes are asserted, with generous
// deadlines (a loaded machine, sanitizers).
#include <gtest/gtest.h>

#include <boost/asio/io_context.hpp>

#include "default_jausd.hpp"
#include "jaus/host/node_host.hpp"
#include "jaus/messages/all.hpp"

namespace jaus::test {
namespace {

using namespace std::chrono_literals;

const Address kObserver{9, 1, 40, 1};
const Address kManager{5, 1, 1, 1}, kDriver{5, 1, 33, 1}, kPoseSensor{5, 1, 38, 1}, kVelocitySensor{5, 1, 42, 1};
constexpr const char* kNode = "127.0.0.24";

// The observer's component: keeps the reports it receives.
class Observer : public rt::Component {
 public:
  using Component::Component;
  template <class M>
  void ask(const Address& to, const M& m) {
    send(to, m);
  }
  template <class M>
  std::optional<M> last_from(const Address& from) const {
    for (auto it = inbox.rbegin(); it != inbox.rend(); ++it)
      if (it->first.command_code == M::code && it->first.source == from)
        if (auto m = wire::decode_payload<M>(it->second)) return *m;
    return std::nullopt;
  }
  std::vector<std::pair<Header, std::vector<std::uint8_t>>> inbox;

 protected:
  bool unhandled(const Header& h, std::span<const std::uint8_t> payload) override {
    inbox.emplace_back(h, std::vector<std::uint8_t>(payload.begin(), payload.end()));
    return true;
  }
};

class DriveAVehicle : public ::testing::Test {
 protected:
  void SetUp() override {
    jausd = std::make_unique<DefaultJausd>("drive", 5, kNode);
    ASSERT_TRUE(jausd->started());

    host::HostConfig host;
    host.node.subsystem = kObserver.subsystem;
    host.node.node = kObserver.node;
    host.link.bind = *transport::parse_endpoint("127.0.0.25:3794");
    host.link.peers = {{*transport::parse_endpoint(std::string(kNode) + ":3794"), transport::Framing::opc}};
    host.settings.identity.subsystem_type = 20001;
    host.components = {host::ComponentSpec{"node_manager", 1, 1, 0, "observer node manager", {}, 0, {}}};
    auto opened = host::NodeHost::open(host, io);
    ASSERT_TRUE(opened) << opened.error().message();
    node_host = std::move(*opened);
    observer = &node_host->emplace<Observer>(node_host->component_config("observer", kObserver.component));
    // The daemon takes a moment to start (longer under sanitizers).
    ASSERT_TRUE(run_until([&] {
      observer->ask(kManager, msg::QueryIdentification{{msg::identification::kComponent}});
      return run_until([&] { return observer->last_from<msg::ReportIdentification>(kManager).has_value(); }, 200ms);
    }, 20s)) << jausd->output();
  }
  void TearDown() override {
    controller.reset();
    node_host.reset();
    jausd.reset();
  }

  std::unique_ptr<ChildProcess> jausctl(const std::string& name, std::vector<std::string> args,
                                        const std::string& bind) {
    auto child = jausd->jausctl(name, std::move(args), bind);
    EXPECT_TRUE(child->started());
    return child;
  }

  bool run_until(const std::function<bool()>& done, std::chrono::milliseconds deadline) {
    const auto until = std::chrono::steady_clock::now() + deadline;
    while (!done()) {
      if (std::chrono::steady_clock::now() > until) return false;
      io.run_for(10ms);
    }
    return true;
  }
  // Asks `to` with `query` until the answer satisfies `good`, or the deadline.
  template <class Report, class Query>
  std::optional<Report> poll(const Address& to, const Query& query, const std::function<bool(const Report&)>& good,
                             std::chrono::milliseconds deadline) {
    std::optional<Report> last;
    run_until([&] {
      observer->inbox.clear();
      observer->ask(to, query);
      run_until([&] { return observer->last_from<Report>(to).has_value(); }, 200ms);
      last = observer->last_from<Report>(to);
      return last && good(*last);
    }, deadline);
    return last;
  }
  // The forward speed once `good` holds for it (or the last one heard before the deadline; -1: none).
  double speed(const std::function<bool(double)>& good = [](double) { return true; }) {
    const auto v = poll<msg::ReportVelocityState>(
        kVelocitySensor, msg::QueryVelocityState{{0x0001}},
        [&](const auto& r) { return r.velocity_x_mps && good(*r.velocity_x_mps); }, 10s);
    return v && v->velocity_x_mps ? *v->velocity_x_mps : -1;
  }

  std::unique_ptr<DefaultJausd> jausd;
  std::unique_ptr<ChildProcess> controller;
  boost::asio::io_context io;
  std::unique_ptr<host::NodeHost> node_host;
  Observer* observer = nullptr;
};

TEST_F(DriveAVehicle, JausctlDrivesThePoseMovesAndSetEmergencyStopsIt) {
  const auto start = poll<msg::ReportGlobalPose>(kPoseSensor, msg::QueryGlobalPose{{0x0003}},
                                                 [](const auto& p) { return p.latitude_deg.has_value(); }, 5s);
  ASSERT_TRUE(start && start->latitude_deg) << jausd->output();

  // Full ahead, repeated at 10 Hz so that the driver's 0.5 s command timeout never runs out.
  controller = jausctl("control",
                       {"control", kDriver.to_string(), "--authority", "10", "--for", "60", "--rate", "10", "--send",
                        R"({"name":"Set Wrench Effort","fields":{"propulsive_linear_effort_x_percent":100}})"},
                       "127.0.0.26:3794");

  // The vehicle starts heading north: the pose sensor shows it moving (> 1 m).
  constexpr double kMetresPerDegreeOfLatitude = 111'132;
  const auto moved = poll<msg::ReportGlobalPose>(
      kPoseSensor, msg::QueryGlobalPose{{0x0003}},
      [&](const auto& p) {
        return p.latitude_deg && (*p.latitude_deg - *start->latitude_deg) * kMetresPerDegreeOfLatitude > 1.0;
      },
      20s);
  ASSERT_TRUE(moved && moved->latitude_deg) << controller->output() << jausd->output();
  EXPECT_GT((*moved->latitude_deg - *start->latitude_deg) * kMetresPerDegreeOfLatitude, 1.0)
      << controller->output() << jausd->output();
  // (Eventually: a stall of the controller past the driver's command timeout may pause it.)
  EXPECT_GT(speed([](double v) { return v > 0.5; }), 0.5);

  // Set Emergency from another OCU: the drive stops, and the controller stops sending.
  auto emergency = jausctl("emergency", {"emergency", kDriver.to_string(), "set", "--as", "254.2.40.1", "--timeout", "5"},
                           "127.0.0.27:3794");
  EXPECT_EQ(emergency->wait(20s), 0) << emergency->output();
  const auto effort = poll<msg::ReportWrenchEffort>(
      kDriver, msg::QueryWrenchEffort{{0x0001}},
      [](const auto& e) { return e.propulsive_linear_effort_x_percent == 0.0; }, 5s);
  ASSERT_TRUE(effort && effort->propulsive_linear_effort_x_percent) << jausd->output();
  EXPECT_EQ(*effort->propulsive_linear_effort_x_percent, 0.0);
  const auto stopped = poll<msg::ReportVelocityState>(
      kVelocitySensor, msg::QueryVelocityState{{0x0001}},
      [](const auto& v) { return v.velocity_x_mps && *v.velocity_x_mps == 0.0; }, 5s);
  ASSERT_TRUE(stopped && stopped->velocity_x_mps);
  EXPECT_EQ(*stopped->velocity_x_mps, 0.0);
  // ...and stays stopped; the operator tool stopped too, released control and said why (exit 3).
  run_until([] { return false; }, 1500ms);
  EXPECT_EQ(speed(), 0.0) << jausd->output();
  EXPECT_TRUE(jausd->output_shows("drive stopped: entered Emergency")) << jausd->output();
  EXPECT_EQ(controller->wait(10s), 3) << controller->output();
  EXPECT_NE(controller->output().find("entered Emergency: stopped sending Set Wrench Effort"), std::string::npos)
      << controller->output();
}

}  // namespace
}  // namespace jaus::test
