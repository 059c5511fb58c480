// The model-based safety test's soak (issue 42, item 7): the same harness as
// tests/model/model_test.cpp (a whole node under virtual time against the
// reference model of the RA's safety rules), many more sequences, longer
// ones, from a seed of its own each run unless given. Prints how many ran,
// how fast, what they covered; on a violation, the seed, the shrunk
// sequence as C++ (paste it into model_test.cpp's regression tests) and the
// node's last log lines, and exits 1.
//
//   bench_model_soak [--runs 5000] [--steps 80] [--seed N] [--keep-going]
//
// JAUS_MODEL_SEED, JAUS_MODEL_RUNS and JAUS_MODEL_STEPS are read too (the
// options win).
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "model_runner.hpp"

namespace {

using namespace jaus::model;

struct Options {
  std::uint64_t runs = env_number("JAUS_MODEL_RUNS", 5000);
  std::uint64_t steps = env_number("JAUS_MODEL_STEPS", 80);
  std::uint64_t seed = env_number(
      "JAUS_MODEL_SEED", static_cast<std::uint64_t>(std::chrono::system_clock::now().time_since_epoch().count()));
  bool keep_going = false;
};

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const auto value = [&]() -> std::uint64_t {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "bench_model_soak: %s needs a value\n", arg.c_str());
        std::exit(2);
      }
      return std::strtoull(argv[++i], nullptr, 0);
    };
    if (arg == "--runs") o.runs = value();
    else if (arg == "--steps") o.steps = value();
    else if (arg == "--seed") o.seed = value();
    else if (arg == "--keep-going") o.keep_going = true;
    else {
      std::fprintf(stderr, "usage: bench_model_soak [--runs N] [--steps N] [--seed N] [--keep-going]\n");
      std::exit(2);
    }
  }
  return o;
}

}  // namespace

int main(int argc, char** argv) {
  std::setvbuf(stdout, nullptr, _IOLBF, 0);  // a violation shows as soon as it is found
  const Options o = parse(argc, argv);
  std::printf("bench_model_soak: %llu sequences of %llu steps from seed %llu (JAUS_MODEL_SEED=%llu)\n",
              static_cast<unsigned long long>(o.runs), static_cast<unsigned long long>(o.steps),
              static_cast<unsigned long long>(o.seed), static_cast<unsigned long long>(o.seed));
  RunStats stats;
  std::uint64_t failures = 0;
  const auto start = std::chrono::steady_clock::now();
  for (std::uint64_t i = 0; i < o.runs; ++i) {
    const std::uint64_t seed = o.seed + i;
    const Sequence sequence = generate(seed, o.steps);
    const auto failure = run_sequence(sequence, fresh_directory("soak"), &stats);
    if (!failure) continue;
    ++failures;
    const Sequence shrunk =
        shrink(sequence, [](const Sequence& s) { return run_sequence(s, fresh_directory("shrink")).has_value(); });
    const auto again = run_sequence(shrunk, fresh_directory("shrunk")).value_or(*failure);
    std::printf("\nseed %llu breaks a rule (again: JAUS_MODEL_SEED=%llu JAUS_MODEL_RUNS=1)\nafter step %zu of the "
                "shrunk sequence: %s\n%sthe shrunk sequence:\n%s\n",
                static_cast<unsigned long long>(seed), static_cast<unsigned long long>(seed), again.step,
                again.what.c_str(), again.trace.c_str(), to_cpp(shrunk).c_str());
    if (!o.keep_going) break;
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("%zu steps, %zu checks in %.1f s (%.0f steps/s): %.1f %% of checks moving, %.1f %% with a stop due, "
              "%.1f %% held; %llu violation(s)\n",
              stats.steps, stats.checks, seconds, static_cast<double>(stats.steps) / seconds,
              100.0 * static_cast<double>(stats.moving) / static_cast<double>(std::max<std::size_t>(stats.checks, 1)),
              100.0 * static_cast<double>(stats.stopped) / static_cast<double>(std::max<std::size_t>(stats.checks, 1)),
              100.0 * static_cast<double>(stats.held) / static_cast<double>(std::max<std::size_t>(stats.checks, 1)),
              static_cast<unsigned long long>(failures));
  return failures == 0 ? 0 : 1;
}
