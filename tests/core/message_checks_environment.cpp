// The per-message-type checks of the environment sensor messages: round trip and vector comparison.
#include "round_trip.hpp"
#include "vector_compare_impl.hpp"

namespace jaus::test {
INSTANTIATE_TYPED_TEST_SUITE_P(Environment, RoundTrip, AsGtestTypes<msg::EnvironmentMessages>::type);
template struct VectorComparison<msg::EnvironmentMessages>;
}  // namespace jaus::test
