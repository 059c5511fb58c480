// Clearpath protocol benchmarks: parser throughput (bytes/s, shown as MB/s) and
// the delay from a setpoint call to its bytes being written on a UDP link.
#include <benchmark/benchmark.h>

#include <random>

#include "jaus/clearpath/codec.hpp"
#include "jaus/clearpath/frame_parser.hpp"
#include "jaus/clearpath/link.hpp"
#include "jaus/transport/asio_runtime.hpp"

namespace cp = jaus::clearpath;

namespace {

std::vector<std::uint8_t> typical_stream() {
  std::vector<std::uint8_t> stream;
  std::mt19937 rng(1);
  for (std::uint32_t i = 0; stream.size() < (1u << 20); ++i) {
    cp::EncoderData encoders;
    encoders.encoders = {{12.5, 0.5}, {-3.25, -0.125}};
    cp::SystemStatus status;
    status.voltages = {24.5, 12.0, 5.0};
    status.currents = {1.5};
    status.temperatures = {35.0, 31.0};
    (void)cp::append_encoded(stream, cp::Envelope{{0, i, 0, 0}, cp::AnyMessage{encoders}});
    (void)cp::append_encoded(stream, cp::Envelope{{0, i, 0, 0}, cp::AnyMessage{status}});
    if (i % 16 == 0) stream.push_back(static_cast<std::uint8_t>(rng()));  // a little noise
  }
  return stream;
}

void BM_ParserThroughput(benchmark::State& state) {
  const auto stream = typical_stream();
  const auto chunk = static_cast<std::size_t>(state.range(0));
  std::size_t frames = 0;
  for (auto _ : state) {
    cp::FrameParser parser;
    for (std::size_t at = 0; at < stream.size(); at += chunk) {
      parser.feed(std::span(stream).subspan(at, std::min(chunk, stream.size() - at)));
      while (auto event = parser.poll()) frames += std::holds_alternative<cp::Frame>(*event);
    }
  }
  benchmark::DoNotOptimize(frames);
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations() * stream.size()));
}
BENCHMARK(BM_ParserThroughput)->Arg(16)->Arg(256)->Arg(4096);

void BM_ParseAndDecode(benchmark::State& state) {
  const auto stream = typical_stream();
  for (auto _ : state) {
    cp::FrameParser parser;
    parser.feed(stream);
    while (auto event = parser.poll())
      if (const auto* f = std::get_if<cp::Frame>(&*event)) benchmark::DoNotOptimize(cp::decode(*f, cp::Direction::from_platform));
  }
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations() * stream.size()));
}
BENCHMARK(BM_ParseAndDecode);

// Setpoint call -> its frame handed to the UDP socket (loopback, no platform).
void BM_SetpointToWrite(benchmark::State& state) {
  boost::asio::io_context io;
  jaus::transport::AsioRuntime runtime(io);
  boost::asio::ip::udp::socket sink(io, {boost::asio::ip::make_address("127.0.0.1"), 0});
  cp::PlatformEndpoint target;
  target.kind = cp::PlatformEndpoint::Kind::udp;
  target.port = sink.local_endpoint().port();
  cp::ClientConfig config;
  config.setpoint_period = std::chrono::hours(1);  // only fresh setpoints go out
  cp::ClearpathLink link(io, runtime, runtime, target, config);
  std::size_t written = 0;
  link.on_written([&](std::span<const std::uint8_t>) { ++written; });
  link.start();
  // Let the connect-time cancels drain.
  for (int i = 0; i < 100; ++i) io.run_for(std::chrono::milliseconds(2));
  cp::SetVelocity v;
  double speed = 0;
  for (auto _ : state) {
    const std::size_t before = written;
    v.translational = (speed += 0.01) > 1 ? (speed = 0) : speed;
    const auto start = std::chrono::steady_clock::now();
    link.set_setpoint(v);
    while (written == before) io.run_one();
    state.SetIterationTime(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  link.stop();
  io.poll();
}
BENCHMARK(BM_SetpointToWrite)->UseManualTime()->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
