// Heap allocations per message in a benchmark: replaces the global operator
// new/delete with counting ones. Include it in exactly one file of a
// benchmark program (it defines the replacements, which are one per program).
#pragma once

#include <benchmark/benchmark.h>

#include <cstddef>
#include <cstdlib>
#include <new>

namespace jaus::bench {
// Heap allocations made since the program started.
inline std::size_t g_allocations = 0;

// The allocations made since `allocations_before`, per iteration, as the counter allocs_per_msg.
inline void count_allocations_per_item(benchmark::State& state, std::size_t allocations_before) {
  state.counters["allocs_per_msg"] = benchmark::Counter(
      static_cast<double>(g_allocations - allocations_before) / static_cast<double>(state.iterations()));
}
}  // namespace jaus::bench

void* operator new(std::size_t size) {
  ++jaus::bench::g_allocations;
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
// These replace the global allocation functions as a pair, so free() matches
// the malloc() above; GCC cannot see that and warns.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpragmas"
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
#pragma GCC diagnostic pop
