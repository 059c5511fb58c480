// Service connection period jitter on the real clock: a component serves a
// report on an SC at 100 Hz and at 1000 Hz for 10 s each (argument: seconds
// per rate), on the Asio runtime; prints p50, p99 and max of |period error|.
// A program that prints figures, not a test.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "jaus/messages/all.hpp"
#include "jaus/runtime/component.hpp"
#include "jaus/transport/asio_runtime.hpp"

namespace {

using namespace jaus;

class Recorder : public rt::Outbox {
 public:
  void send(const Header& header, std::span<const std::uint8_t>) override {
    if (header.command_code == msg::ReportGlobalPose::code) times.push_back(std::chrono::steady_clock::now());
  }
  std::vector<std::chrono::steady_clock::time_point> times;
};

class PoseSource : public rt::Component {
 public:
  PoseSource(rt::ComponentConfig config, rt::Environment env) : Component(std::move(config), std::move(env)) {
    provide<msg::ReportGlobalPose>(0x01FF, [] {
      msg::ReportGlobalPose pose;
      pose.latitude_deg = 45.5;
      pose.longitude_deg = -73.6;
      pose.yaw_rad = 1.0;
      return pose;
    });
  }
};

void measure(double rate_hz, double seconds) {
  boost::asio::io_context io;
  transport::AsioRuntime runtime(io);
  Recorder recorder;
  rt::ComponentConfig config;
  config.address = Address{1, 1, 38, 1};
  PoseSource source(config, rt::Environment{runtime, runtime, recorder});
  source.start();

  msg::CreateServiceConnection create;
  create.command_code = msg::ReportGlobalPose::code;
  create.periodic_rate_hz = rate_hz;
  create.presence_vector = 0x1FF;
  std::vector<std::uint8_t> payload(16);
  const auto size = wire::encode_payload(create, payload);
  Header h;
  h.command_code = create.code;
  h.source = Address{2, 1, 40, 1};
  h.destination = config.address;
  source.receive(h, std::span(payload).first(*size));

  boost::asio::steady_timer stop(io, std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                         std::chrono::duration<double>(seconds)));
  stop.async_wait([&](const boost::system::error_code&) { io.stop(); });
  io.run();

  // The confirmed rate travels as a scaled integer: use the rate actually served.
  const ScaledRange<std::uint16_t> rate_range{msg::kServiceRate.lower, msg::kServiceRate.upper};
  const double served_rate = rate_range.decode(rate_range.encode(rate_hz));
  const double ideal_us = 1e6 / served_rate;
  std::vector<double> errors_us;
  for (std::size_t i = 1; i < recorder.times.size(); ++i) {
    const double period_us =
        std::chrono::duration<double, std::micro>(recorder.times[i] - recorder.times[i - 1]).count();
    errors_us.push_back(std::abs(period_us - ideal_us));
  }
  std::sort(errors_us.begin(), errors_us.end());
  auto percentile = [&](double p) {
    return errors_us.empty() ? 0.0 : errors_us[std::min(errors_us.size() - 1, static_cast<std::size_t>(p * errors_us.size()))];
  };
  const double drift_us =
      recorder.times.size() < 2
          ? 0
          : std::chrono::duration<double, std::micro>(recorder.times.back() - recorder.times.front()).count() -
                ideal_us * static_cast<double>(recorder.times.size() - 1);
  std::printf("SC %7.1f Hz for %4.1f s: %6zu reports, period error p50 %8.1f us, p99 %8.1f us, max %8.1f us, "
              "end-to-end drift %8.1f us\n",
              served_rate, seconds, recorder.times.size(), percentile(0.50), percentile(0.99),
              errors_us.empty() ? 0.0 : errors_us.back(), drift_us);
}

}  // namespace

int main(int argc, char** argv) {
  const double seconds = argc > 1 ? std::atof(argv[1]) : 10.0;
  measure(100, seconds);
  measure(1000, seconds);
  return 0;
}
