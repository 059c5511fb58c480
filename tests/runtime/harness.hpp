// A component under test: virtual time, an outbox that records what the
// component sends (decoded on demand), and a driving component that records
// every command it executes and every stop it is told to make.
#pragma once

#include <gtest/gtest.h>

#include <optional>
#include <string>
#include <vector>

#include "jaus/messages/all.hpp"
#include "jaus/runtime/component.hpp"
#include "jaus/base/virtual_time.hpp"

namespace jaus::test {

// Whether one of the logged `lines` contains `text`.
inline bool any_line_contains(const std::vector<std::string>& lines, const std::string& text) {
  for (const auto& line : lines)
    if (line.find(text) != std::string::npos) return true;
  return false;
}

struct Sent {
  Header header;
  std::vector<std::uint8_t> payload;
  rt::TimePoint at{};
};

class RecordingOutbox : public rt::Outbox {
 public:
  void send(const Header& header, std::span<const std::uint8_t> payload) override {
    sent.push_back({header, {payload.begin(), payload.end()}, clock ? clock->now() : rt::TimePoint{}});
  }
  const rt::Clock* clock = nullptr;  // when set, each message records when it was sent
  // Messages of type M sent to `to` since the last clear(), decoded.
  template <class M>
  std::vector<M> to(const Address& destination) const {
    std::vector<M> out;
    for (const auto& s : sent)
      if (s.header.command_code == M::code && s.header.destination == destination) {
        auto decoded = wire::decode_payload<M>(s.payload);
        EXPECT_TRUE(decoded) << M::name;
        if (decoded) out.push_back(*decoded);
      }
    return out;
  }
  template <class M>
  std::size_t count() const {
    std::size_t n = 0;
    for (const auto& s : sent) n += s.header.command_code == M::code;
    return n;
  }
  void clear() { sent.clear(); }
  std::vector<Sent> sent;
};

// Stands in for a primitive driver: Set Wrench Effort moves the "platform".
class TestDriver : public rt::Component {
 public:
  TestDriver(rt::ComponentConfig config, rt::Environment env, bool init_ok = true)
      : Component(std::move(config), std::move(env)), init_ok_(init_ok) {
    // A pose report with every field but the attitude RMS (bit 7).
    provide<msg::ReportGlobalPose>(0x017F, [] {
      msg::ReportGlobalPose pose;
      pose.latitude_deg = 45.5;
      pose.longitude_deg = -73.6;
      pose.elevation_m = 30;
      pose.position_rms_m = 1;
      pose.roll_rad = 0.01;
      pose.pitch_rad = 0.02;
      pose.yaw_rad = 1.5;
      pose.time_stamp = TimeStamp{};
      return pose;
    });
    handle<msg::SetWrenchEffort>(Access::controller, /*ready_only=*/true,
                                 [this](const Header&, const msg::SetWrenchEffort& m) {
                                   executed.push_back(m.propulsive_linear_effort_x_percent.value_or(0));
                                   moving = executed.back() != 0;
                                 });
  }
  std::vector<double> executed;   // every Set Wrench Effort that ran
  std::vector<std::string> stops;  // every command_stop, with why
  bool moving = false;
  bool init_ok_;

 protected:
  bool initialize() override { return init_ok_; }
  void command_stop(std::string_view why) override {
    stops.emplace_back(why);
    moving = false;
  }
};

inline const Address kDriver{1, 1, 33, 1};
inline const Address kOcuA{2, 1, 40, 1};
inline const Address kOcuB{3, 1, 40, 1};
inline const Address kOcuC{4, 1, 40, 1};

class ComponentTest : public ::testing::Test {
 protected:
  ComponentTest() {
    outbox.clock = &time;
    make();
  }

  void make(std::uint8_t authority = 5, rt::Duration timeout = std::chrono::seconds(3), bool reject = false,
            bool init_ok = true, std::optional<std::uint8_t> max_authority = std::nullopt) {
    driver.reset();
    rt::ComponentConfig config;
    config.name = "driver";
    config.address = kDriver;
    config.authority = authority;
    config.controller_timeout = timeout;
    config.reject_refused_requests = reject;
    config.max_authority = max_authority;
    driver = std::make_unique<TestDriver>(
        config, rt::Environment{time, time, outbox, [this](rt::LogLevel, const std::string& line) { logs.push_back(line); }},
        init_ok);
    driver->start();
  }

  template <class M>
  void deliver(const Address& from, const M& message, std::uint8_t priority = priority::kDefault) {
    deliver_as(rt::SenderStanding::trusted, from, message, priority);
  }
  // The same from a sender of the given standing (an observer, or one the node could not record).
  template <class M>
  void deliver_as(rt::SenderStanding standing, const Address& from, const M& message,
                  std::uint8_t priority = priority::kDefault) {
    std::vector<std::uint8_t> payload(kMaxPayloadSize);
    auto size = wire::encode_payload(message, payload);
    ASSERT_TRUE(size);
    Header h;
    h.priority = priority;
    h.command_code = M::code;
    h.source = from;
    h.destination = kDriver;
    h.data_size = static_cast<std::uint16_t>(*size);
    driver->receive(h, std::span(payload).first(*size), wire::Dialect::ra, standing);
    time.run_ready();
  }

  void drive(const Address& from, double effort) {
    msg::SetWrenchEffort m;
    m.propulsive_linear_effort_x_percent = effort;
    deliver(from, m);
  }

  std::optional<std::uint8_t> request_control(const Address& from, std::uint8_t authority,
                                              rt::SenderStanding standing = rt::SenderStanding::trusted) {
    outbox.clear();
    deliver_as(standing, from, msg::RequestComponentControl{{authority}});
    const auto confirms = outbox.to<msg::ConfirmComponentControl>(from);
    if (confirms.empty()) return std::nullopt;
    return confirms.back().response_code;
  }

  bool logged(const std::string& text) const { return any_line_contains(logs, text); }

  rt::VirtualTime time;
  RecordingOutbox outbox;
  std::vector<std::string> logs;
  std::unique_ptr<TestDriver> driver;
};

}  // namespace jaus::test

namespace jaus::test {

// Delivers `message` from `from` to `component` as its node would (header
// filled, payload encoded in the RA dialect), then runs whatever became due.
template <class M>
void deliver_to(rt::Component& component, rt::VirtualTime& time, const Address& from, const M& message,
                rt::SenderStanding standing = rt::SenderStanding::trusted) {
  std::vector<std::uint8_t> payload(kMaxPayloadSize);
  const auto size = wire::encode_payload(message, payload);
  ASSERT_TRUE(size) << M::name;
  Header h;
  h.command_code = M::code;
  h.source = from;
  h.destination = component.address();
  h.data_size = static_cast<std::uint16_t>(*size);
  component.receive(h, std::span(payload).first(*size), wire::Dialect::ra, standing);
  time.run_ready();
}

}  // namespace jaus::test
