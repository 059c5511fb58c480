// Test helper: fills any described message with random in-range values
// (a fixed seed makes every run identical).
#pragma once

#include <random>

#include "jaus/clearpath/messages.hpp"

namespace jaus::clearpath::testing {

// Every field of the message drawn on its wire grid within its documented
// range. Defined once (random_message.cpp): it instantiates every message type.
void randomize(AnyMessage& message, std::mt19937& rng);

}  // namespace jaus::clearpath::testing
