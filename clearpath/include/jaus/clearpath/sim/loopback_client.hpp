// A Clearpath client wired straight to a simulated platform in the same
// process, run by the runtime's Scheduler: the bridge and its tests drive a
// platform under the same (virtual) time as the JAUS components. Every period
// the client ticks, its frames go to the platform, the platform steps and its
// frames come back, each way optionally through a FaultInjector.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <vector>

#include "jaus/base/time.hpp"
#include "jaus/clearpath/client.hpp"
#include "jaus/clearpath/sim/fault_injector.hpp"
#include "jaus/clearpath/sim/sim_platform.hpp"

namespace jaus::clearpath::sim {

struct LoopbackConfig {
  PlatformConfig platform;
  FaultConfig faults;
  ClientConfig client;
  rt::Duration period = std::chrono::milliseconds(1);
};

class LoopbackClient final : public Client {
 public:
  // Starts at once: connected, and ticking on the scheduler until destroyed.
  LoopbackClient(rt::Clock& clock, rt::Scheduler& scheduler, LoopbackConfig config = {});
  ~LoopbackClient() override;
  LoopbackClient(const LoopbackClient&) = delete;
  LoopbackClient& operator=(const LoopbackClient&) = delete;

  void send(AnyMessage message, ClientCore::CommandCallback done = {}) override { core_.send(std::move(message), std::move(done)); }
  void subscribe(AnyMessage request, ClientCore::CommandCallback done = {}) override {
    core_.subscribe(std::move(request), std::move(done));
  }
  void set_setpoint(AnyMessage command) override { core_.set_setpoint(std::move(command), clock_.now()); }
  void clear_setpoint(std::uint16_t type) override { core_.clear_setpoint(type); }
  void stop_setpoint(AnyMessage stop) override { core_.stop_setpoint(std::move(stop), clock_.now()); }
  void on_data(ClientCore::DataCallback callback) override { core_.on_data(std::move(callback)); }
  void on_state(ClientCore::StateCallback callback) override { core_.on_state(std::move(callback)); }
  void on_problem(ClientCore::ProblemCallback callback) override { core_.on_problem(std::move(callback)); }
  ConnectionState state() const override { return core_.state(); }
  const ClientCounters& counters() const override { return core_.counters(); }
  const std::string& down_reason() const override { return core_.down_reason(); }

  // A pulled cable: nothing crosses and reopening fails until it is plugged back.
  void set_plugged(bool plugged) { plugged_ = plugged; }
  // Every frame the client writes, as written (before any injected fault).
  void on_written(std::function<void(std::span<const std::uint8_t>)> callback) { on_written_ = std::move(callback); }

  ClientCore& core() { return core_; }
  const ClientCore& core() const { return core_; }
  const SimPlatform& platform() const { return platform_; }
  SimPlatform& platform() { return platform_; }  // e.g. press its e-stop or pause input

 private:
  void step();
  void deliver_to_client(std::vector<std::uint8_t> bytes, rt::TimePoint now);

  rt::Clock& clock_;
  rt::Scheduler& scheduler_;
  rt::Duration period_;
  SimPlatform platform_;
  ClientCore core_;
  FaultInjector faults_;
  bool plugged_ = true;
  std::function<void(std::span<const std::uint8_t>)> on_written_;
  rt::TimerId timer_ = rt::kNoTimer;
};

}  // namespace jaus::clearpath::sim
