// Encode + decode of full messages (every presence bit set), the per-message
// cost of the codec. Steady state allocates nothing: the buffer and the decoded
// object are reused. Reference: the common open RA 3.3 codec takes about
// 115-130 ns per encode+decode of these messages on this machine class.
// BM_*_HandWritten time the same round trip written by hand for these two
// messages (codec_reference.hpp), the floor codec_speed_guard compares with.
#include <benchmark/benchmark.h>

#include <array>
#include <cstdlib>
#include <new>

#include "allocation_count.hpp"
#include "codec_reference.hpp"
#include "jaus/messages/all.hpp"

namespace {

using namespace jaus;

using bench::full_global_pose;
using bench::full_wrench_effort;

template <class M>
void encode_decode(benchmark::State& state, const M& message) {
  std::array<std::uint8_t, kHeaderSize + kMaxPayloadSize> buffer{};
  Header header;
  header.destination = {1, 1, 33, 1};
  header.source = {2, 1, 40, 1};
  M decoded{};
  const std::size_t allocations_before = bench::g_allocations;
  for (auto _ : state) {
    benchmark::DoNotOptimize(message);
    auto size = wire::encode_message(header, message, buffer);
    auto packet = decode_packet(std::span(buffer).first(*size));
    auto error = wire::decode_payload_into(packet->payload, decoded);
    benchmark::DoNotOptimize(error);
    benchmark::DoNotOptimize(decoded);
    benchmark::ClobberMemory();
  }
  bench::count_allocations_per_item(state, allocations_before);
  if (!(decoded == message)) {
    // Values are quantised, so exact equality is not expected; presence must match.
    if (wire::presence_of(decoded) != wire::presence_of(message)) state.SkipWithError("round trip lost fields");
  }
}

template <class M>
void hand_written(benchmark::State& state, const M& message) {
  std::array<std::uint8_t, kHeaderSize + kMaxPayloadSize> buffer{};
  Header header;
  header.destination = {1, 1, 33, 1};
  header.source = {2, 1, 40, 1};
  M decoded{};
  for (auto _ : state) {
    benchmark::DoNotOptimize(message);
    const std::size_t size = bench::reference::encode(header, message, buffer);
    bool ok = bench::reference::decode(std::span<const std::uint8_t>(buffer).first(size), decoded);
    benchmark::DoNotOptimize(ok);
    benchmark::DoNotOptimize(decoded);
    benchmark::ClobberMemory();
  }
}

void BM_ReportGlobalPose_EncodeDecode(benchmark::State& state) { encode_decode(state, full_global_pose()); }
void BM_ReportGlobalPose_HandWritten(benchmark::State& state) { hand_written(state, full_global_pose()); }
void BM_SetWrenchEffort_EncodeDecode(benchmark::State& state) { encode_decode(state, full_wrench_effort()); }
void BM_SetWrenchEffort_HandWritten(benchmark::State& state) { hand_written(state, full_wrench_effort()); }

BENCHMARK(BM_ReportGlobalPose_EncodeDecode);
BENCHMARK(BM_ReportGlobalPose_HandWritten);
BENCHMARK(BM_SetWrenchEffort_EncodeDecode);
BENCHMARK(BM_SetWrenchEffort_HandWritten);

}  // namespace

BENCHMARK_MAIN();
