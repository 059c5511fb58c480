// Runs the example's wheel odometer on a node of its own (1.1) and asks it,
// from an operator component on a second node (1.2), for its velocity state,
// both nodes on one virtual clock joined by the installed jaus::testing
// memory network. Exit 0 when the report carries what the odometer measured;
// 1 otherwise, saying why.
#include <cmath>
#include <iostream>
#include <memory>
#include <optional>
#include <vector>

#include "jaus/base/version.hpp"
#include "jaus/base/virtual_time.hpp"
#include "jaus/node/node.hpp"
#include "jaus/testing/memory_link.hpp"
#include "jaus/testing/virtual_time.hpp"
#include "wheel_odometer.hpp"

namespace {

// The operator's side: sends the query and keeps the report.
class Operator final : public jaus::rt::Component {
 public:
  Operator(jaus::rt::ComponentConfig config, jaus::rt::Environment env) : Component(std::move(config), std::move(env)) {
    handle<jaus::msg::ReportVelocityState>(
        Access::anyone, false, [this](const jaus::Header&, const jaus::msg::ReportVelocityState& r) { report = r; });
  }
  void ask(const jaus::Address& odometer) { send(odometer, jaus::msg::QueryVelocityState{{0x0041}}); }
  std::optional<jaus::msg::ReportVelocityState> report;
};

}  // namespace

int main() {
  jaus::rt::VirtualTime time;
  jaus::testing::MemoryNetwork network(time, time);
  auto& robot_link = network.attach(1, 1);
  auto& operator_link = network.attach(1, 2);
  jaus::node::NodeConfig robot_config, station_config;
  robot_config.node = 1;
  station_config.node = 2;
  jaus::node::Node robot(robot_config, time, time, robot_link);
  jaus::node::Node station(station_config, time, time, operator_link);
  robot_link.deliver_to(robot);
  operator_link.deliver_to(station);

  const jaus::Address odometer_address{1, 1, 42, 1};
  jaus::rt::ComponentConfig odometer_config, operator_config;
  odometer_config.name = "wheel odometer";
  odometer_config.address = odometer_address;
  operator_config.name = "operator";
  operator_config.address = {1, 2, 40, 1};
  auto& odometer = robot.add_as(std::make_unique<example::WheelOdometer>(odometer_config, robot.environment()));
  auto& op = station.add_as(std::make_unique<Operator>(operator_config, station.environment()));

  odometer.measured(1.5, 0.25);
  op.ask(odometer_address);
  jaus::testing::run_until(time, [&] { return op.report.has_value(); }, std::chrono::seconds(1));

  if (!op.report) {
    std::cerr << "example_component: no Report Velocity State from " << odometer_address.to_string() << "\n";
    return 1;
  }
  const auto& r = *op.report;
  // Velocity is a scaled integer on the wire: equal to within its resolution.
  if (!r.velocity_x_mps || std::abs(*r.velocity_x_mps - 1.5) > 0.01 || !r.yaw_rate_rps ||
      std::abs(*r.yaw_rate_rps - 0.25) > 0.01 || r.velocity_y_mps) {
    std::cerr << "example_component: unexpected report: velocity_x " << r.velocity_x_mps.value_or(-1) << ", yaw rate "
              << r.yaw_rate_rps.value_or(-1) << "\n";
    return 1;
  }
  std::cout << "example_component (jaus-node " << jaus::kVersion << "): " << odometer_address.to_string() << " reports "
            << *r.velocity_x_mps << " m/s, " << *r.yaw_rate_rps << " rad/s\n";
  return 0;
}
