// Runs a sequence on a whole node (model_node.hpp) and the reference model
// (reference_model.hpp) in lockstep, checking the node against the model
// after every step and every 100 ms of time passing; makes random sequences
// from a seed; shrinks a failing one by deleting steps.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>

#include "action.hpp"
#include "reference_model.hpp"

namespace jaus::model {

struct Failure {
  std::size_t step = 0;  // the step after which (or during which) the check failed
  std::string what;      // the rule, and what the node showed
  std::string trace;     // the steps so far, the model's state, the node's last log lines
};

struct RunStats {
  std::size_t steps = 0;
  std::size_t checks = 0;
  std::size_t moving = 0;    // checks that saw a non-zero drive
  std::size_t stopped = 0;   // checks at which the rules required zero
  std::size_t held = 0;      // checks with at least one holder
};

// Runs `sequence` on a fresh node whose state directory is `directory`
// (made, and removed afterwards). The first failing check, or nullopt.
std::optional<Failure> run_sequence(const Sequence& sequence, const std::filesystem::path& directory,
                                    RunStats* stats = nullptr, ModelTiming timing = {});

// A random sequence of `steps` steps; the same for the same seed on every platform.
Sequence generate(std::uint64_t seed, std::size_t steps);

// Deletes steps (halves, quarters, ... single steps) and shortens time
// advances while `fails` still holds; at most `budget` tries.
Sequence shrink(Sequence failing, const std::function<bool(const Sequence&)>& fails, std::size_t budget = 400);

// A state directory of its own for each run of this process.
std::filesystem::path fresh_directory(const std::string& tag);

// JAUS_MODEL_SEED / JAUS_MODEL_RUNS / JAUS_MODEL_STEPS, or the fallback.
std::uint64_t env_number(const char* name, std::uint64_t fallback);

}  // namespace jaus::model
