// The per-message-type checks of the core messages: round trip and vector comparison.
#include "round_trip.hpp"
#include "vector_compare_impl.hpp"

namespace jaus::test {
INSTANTIATE_TYPED_TEST_SUITE_P(Core, RoundTrip, AsGtestTypes<msg::CoreMessages>::type);
template struct VectorComparison<msg::CoreMessages>;
}  // namespace jaus::test
