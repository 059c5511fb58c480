#include "round_trip.hpp"

namespace jaus::test {
INSTANTIATE_TYPED_TEST_SUITE_P(Environment, RoundTrip, AsGtestTypes<msg::EnvironmentMessages>::type);
}  // namespace jaus::test
