// The RA's safety rules, proved by a model (issue 42, item 7).
//
// Random sequences drive a whole node under virtual time (node manager,
// primitive driver, local vector driver; the bridge and the in-process
// simulated Clearpath platform, whose e-stop shares jausd's emergency bit;
// the JSS face; the emergency holds file): two RA operators (A, B) and a JSS
// client (J) on the primitive driver, an RA operator (C) driving through the
// vector driver, each requesting and releasing control at various
// authorities, sending and streaming Set Wrench Effort, Set/Clear Emergency
// (to the primitive or the vector driver), Standby, Resume, Reset, Set
// Component Authority (JSS: Set Authority) and Shutdown, losing its link and
// getting it back; the platform's e-stop and pause (held, or a 20 ms
// pulse); time passing (100 ms to 5 s); jausd
// restarting from its holds file; the local clear (SIGUSR1). After every
// step, and every 100 ms while time passes, the node is checked against
// reference_model.hpp, which knows the rules and nothing of the code:
//
//   1. Zero when a stop says so: whenever a Set Emergency is held, the
//      primitive driver is in Standby or shut down, the platform's e-stop
//      or pause is on, nobody controls it (released, taken over, silent
//      beyond controller_timeout_s) or its controller's last command is
//      older than command_timeout_s, the last motion command jausd wrote to
//      the platform is zero: within 50 ms of a stop jausd makes, within
//      300 ms of one the platform makes (jausd hears it at 50 Hz, so a
//      pulse of one period, 20 ms, is heard too: the regression below).
//   2. Only the controller moves it: a non-zero drive is the current
//      controller's last Set Wrench Effort in effect (A's, B's or J's,
//      values drawn at random, 5..80 % either way), or the vector driver's
//      while it holds the primitive driver for C's Set Local Vector; an
//      effort from anyone else never changes it.
//   3. Nothing resumes without its controller: after any stop the drive
//      stays zero until the controller sends a new command in Ready (the
//      vector driver: until C sends a new Set Local Vector).
//   4. Every holder's hold is kept: the vehicle's latch holds exactly the
//      parties that sent Set Emergency and have not cleared it, across
//      restarts (the holds file), until each clears its own or the local
//      clear; its holders never change otherwise.
//   5. Control follows the RA's arbitration (uncontrolled: at or above the
//      component's own authority; taken over only by a higher authority;
//      dropped after controller_timeout_s of silence), and an idle vector
//      driver gives the primitive driver back (the vector driver itself
//      asks at its own authority, 1, and is refused or takes over by the
//      same rule).
//   6. The primitive driver's state follows the RA's lifecycle (Emergency
//      while held; Standby only from Ready, Resume only by the controller;
//      an Emergency returns to what it interrupted).
// Where a rule leaves the timing open (within 60 ms of a timeout, an
// Emergency's end before the platform confirms it, a platform stop jausd has
// not heard of yet, the vector driver taking or giving back control), either
// outcome is allowed and the model follows the one the node shows.
//
// Hooks left for rules being added (ReferenceModel's hooks, each a property
// to turn on, with where it goes): RA datagrams from the JSS alias subsystem refused;
// holds persisted with the holder's host; a driver's authority capped
// (max_authority) so operators always win; a stop counter in status; a
// one-way platform link detected.
//
// JAUS_MODEL_SEED (first seed), JAUS_MODEL_RUNS (sequences), JAUS_MODEL_STEPS
// (steps each) choose the runs; a failure prints its seed, the shrunk
// sequence as C++ for a regression test below, and the node's last log lines.
// The soak: tests/benchmarks/bench_model_soak.
#include <gtest/gtest.h>

#include <cstdlib>
#include <iostream>
#include <sstream>

#include "model_runner.hpp"

namespace jaus::model {
namespace {

// CI: the sanitizer tree (clang Debug, ASan) runs these in about a minute of
// CPU per slice; more sequences are the soak's (bench_model_soak).
constexpr std::uint64_t kDefaultSeed = 20261206;
constexpr std::uint64_t kDefaultRuns = 400;
constexpr std::uint64_t kDefaultSteps = 40;
constexpr int kSlices = 4;  // tests, so that the shards share the runs

std::string report(std::uint64_t seed, const Sequence& shrunk, const Failure& f) {
  std::ostringstream o;
  o << "seed " << seed << " breaks a rule (again: JAUS_MODEL_SEED=" << seed
    << " JAUS_MODEL_RUNS=1 model_tests --gtest_filter='ModelBased*')\n"
    << "after step " << f.step << " of the shrunk sequence: " << f.what << "\n"
    << f.trace << "the shrunk sequence, for a regression test:\n"
    << to_cpp(shrunk);
  return o.str();
}

class ModelBased : public ::testing::TestWithParam<int> {};

TEST_P(ModelBased, RandomSequencesKeepTheRules) {
  const std::uint64_t first = env_number("JAUS_MODEL_SEED", kDefaultSeed);
  const std::uint64_t runs = env_number("JAUS_MODEL_RUNS", kDefaultRuns);
  const std::size_t steps = env_number("JAUS_MODEL_STEPS", kDefaultSteps);
  if (GetParam() == 0)
    std::cout << "[ model    ] seeds " << first << ".." << first + runs - 1 << ", " << steps
              << " steps each (JAUS_MODEL_SEED, JAUS_MODEL_RUNS, JAUS_MODEL_STEPS)\n";
  RunStats stats;
  std::size_t ran = 0;
  for (std::uint64_t i = static_cast<std::uint64_t>(GetParam()); i < runs; i += kSlices) {
    const std::uint64_t seed = first + i;
    const Sequence sequence = generate(seed, steps);
    ++ran;
    const auto failure = run_sequence(sequence, fresh_directory("ci"), &stats);
    if (!failure) continue;
    const Sequence shrunk =
        shrink(sequence, [](const Sequence& s) { return run_sequence(s, fresh_directory("shrink")).has_value(); });
    const auto again = run_sequence(shrunk, fresh_directory("shrunk"));
    ADD_FAILURE() << report(seed, shrunk, again.value_or(*failure));
    return;
  }
  if (ran == 0) return;
  std::cout << "[ model    ] " << ran << " sequences, " << stats.steps << " steps, " << stats.checks << " checks: "
            << stats.moving << " moving, " << stats.stopped << " with a stop due, " << stats.held << " held\n";
  if (ran < 10) return;  // one seed again: it passed
  // Not vacuous: the sequences drove the vehicle and stopped it.
  EXPECT_GT(stats.moving, 0u);
  EXPECT_GT(stats.stopped, 0u);
  EXPECT_GT(stats.held, 0u);
}

INSTANTIATE_TEST_SUITE_P(Slices, ModelBased, ::testing::Range(0, kSlices));

// ---- shrunk counterexamples and hand-written sequences, kept -----------------

RunStats expect_rules_kept(const Sequence& s) {
  RunStats stats;
  const auto failure = run_sequence(s, fresh_directory("regression"), &stats);
  if (failure) ADD_FAILURE() << "after step " << failure->step << ": " << failure->what << "\n" << failure->trace;
  return stats;
}

// The model's own sanity: an operator drives, each kind of stop stops it, and
// nothing moves again until its new command.
TEST(ModelRegression, EachStopStopsAndNothingResumesWithoutTheController) {
  const RunStats stats = expect_rules_kept({
      {Kind::request_control, Party::a, 5},
      {Kind::stick, Party::a, 60},
      {Kind::advance, Party::a, 500},
      {Kind::set_emergency, Party::b, 0},
      {Kind::advance, Party::a, 500},
      {Kind::clear_emergency, Party::b, 0},
      {Kind::advance, Party::a, 1000},
      {Kind::standby, Party::j, 0},
      {Kind::advance, Party::a, 300},
      {Kind::resume, Party::a, 0},
      {Kind::advance, Party::a, 300},
      {Kind::estop, Party::a, 1},
      {Kind::advance, Party::a, 500},
      {Kind::estop, Party::a, 0},
      {Kind::advance, Party::a, 1000},
      {Kind::link, Party::a, 0},
      {Kind::advance, Party::a, 4000},
      {Kind::link, Party::a, 1},
      {Kind::advance, Party::a, 1000},
  });
  EXPECT_GT(stats.moving, 5u);  // it did drive between the stops
}

// Holds survive a restart, each holder clears its own, the local clear the rest.
TEST(ModelRegression, HoldsSurviveARestartUntilEachHolderOrTheLocalClear) {
  expect_rules_kept({
      {Kind::set_emergency, Party::a, 0},
      {Kind::set_emergency, Party::c, 0, Target::vector_driver},
      {Kind::set_emergency, Party::j, 0},
      {Kind::restart, Party::a, 0},
      {Kind::advance, Party::a, 500},
      {Kind::clear_emergency, Party::a, 0},
      {Kind::advance, Party::a, 300},
      {Kind::local_clear, Party::a, 0},
      {Kind::advance, Party::a, 1000},
  });
}

// A JSS client's hold is persisted under its alias; after a restart the
// client (given an alias afresh) clears its own hold, and takes control again.
TEST(ModelRegression, AJssClientClearsItsOwnHoldAfterARestart) {
  const RunStats stats = expect_rules_kept({
      {Kind::request_control, Party::j, 5},
      {Kind::stick, Party::j, 40},
      {Kind::advance, Party::a, 500},
      {Kind::set_emergency, Party::j, 0},
      {Kind::set_emergency, Party::b, 0},
      {Kind::restart, Party::a, 0},
      {Kind::advance, Party::a, 500},
      {Kind::clear_emergency, Party::j, 0},
      {Kind::clear_emergency, Party::b, 0},
      {Kind::advance, Party::a, 1000},
      {Kind::request_control, Party::j, 5},
      {Kind::advance, Party::a, 1000},
  });
  EXPECT_GT(stats.moving, 10u);  // J drove before and after
}

// The Husky's e-stop shares jausd's emergency bit: a hold restored at a
// restart while the e-stop is pressed, then cleared by its holder, leaves the
// e-stop holding the vehicle; released, nothing moves until a new command.
TEST(ModelRegression, AnEstopOnJausdsBitOutlastsARestoredHoldAndItsClear) {
  const RunStats stats = expect_rules_kept({
      {Kind::request_control, Party::a, 5},
      {Kind::stick, Party::a, 50},
      {Kind::advance, Party::a, 500},
      {Kind::set_emergency, Party::b, 0},
      {Kind::estop, Party::a, 1},
      {Kind::restart, Party::a, 0},
      {Kind::advance, Party::a, 500},
      {Kind::clear_emergency, Party::b, 0},
      {Kind::advance, Party::a, 1000},
      {Kind::estop, Party::a, 0},
      {Kind::advance, Party::a, 1000},
      {Kind::request_control, Party::a, 5},
      {Kind::advance, Party::a, 1000},
      {Kind::pause, Party::a, 1},
      {Kind::advance, Party::a, 400},
      {Kind::pause, Party::a, 0},
      {Kind::advance, Party::a, 1000},
  });
  EXPECT_GT(stats.moving, 10u);
}

// Standby survives an Emergency and a platform stop; only the controller's
// Resume ends it, and nothing moves until its next command.
TEST(ModelRegression, StandbySurvivesAnEmergencyAndOnlyTheControllerResumes) {
  const RunStats stats = expect_rules_kept({
      {Kind::request_control, Party::j, 2},
      {Kind::stick, Party::j, 30},
      {Kind::advance, Party::a, 500},
      {Kind::standby, Party::a, 0},
      {Kind::set_emergency, Party::c, 0, Target::vector_driver},
      {Kind::estop, Party::a, 1},
      {Kind::advance, Party::a, 500},
      {Kind::clear_emergency, Party::c, 0, Target::vector_driver},
      {Kind::estop, Party::a, 0},
      {Kind::advance, Party::a, 800},
      {Kind::resume, Party::b, 0},
      {Kind::advance, Party::a, 500},
      {Kind::resume, Party::j, 0},
      {Kind::advance, Party::a, 1000},
  });
  EXPECT_GT(stats.moving, 10u);
}

// Found by this model: a pause (or e-stop) pulse shorter than the platform's
// safety status period went unheard by jausd while it sampled at 10 Hz. The
// platform dropped its setpoint for the pulse, but the bridge's periodic
// setpoint sent the last Set Wrench Effort again and the platform drove on
// at 60 % after the pulse, with no new command from the controller: jausd
// undid a stop it did not make. jausd now samples the safety status at 50 Hz,
// so a pulse of one period (20 ms) is always seen and ends the command.
TEST(ModelRegression, APausePulseOfOneStatusPeriodEndsTheCommand) {
  ModelTiming strict;
  strict.every_platform_stop_ends_the_command = true;
  strict.platform_deadline = 150;  // the status period and a margin
  const auto failure = run_sequence(
      {
          {Kind::request_control, Party::a, 5},
          {Kind::effort, Party::a, 60},
          {Kind::pause, Party::a, 2},
          {Kind::advance, Party::a, 300},
      },
      fresh_directory("regression"), nullptr, strict);
  if (failure) ADD_FAILURE() << "after step " << failure->step << ": " << failure->what << "\n" << failure->trace;
}

// The vector driver drives for C, an operator takes over, and nothing restarts it.
TEST(ModelRegression, TheVectorDriverStopsForAnOperatorAndStaysStopped) {
  const RunStats stats = expect_rules_kept({
      {Kind::take_vector, Party::c, 0},
      {Kind::keep_vector, Party::c, 1},
      {Kind::advance, Party::a, 1500},
      {Kind::drive_vector, Party::c, 50},
      {Kind::advance, Party::a, 1000},
      {Kind::request_control, Party::b, 2},
      {Kind::advance, Party::a, 1000},
      {Kind::release_control, Party::b, 0},
      {Kind::advance, Party::a, 1000},
  });
  EXPECT_GT(stats.moving, 5u);  // the vector driver drove for C
}

}  // namespace
}  // namespace jaus::model
