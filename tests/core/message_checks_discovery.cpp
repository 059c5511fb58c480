// The per-message-type checks of the discovery messages: round trip and vector comparison.
#include "round_trip.hpp"
#include "vector_compare_impl.hpp"

namespace jaus::test {
INSTANTIATE_TYPED_TEST_SUITE_P(Discovery, RoundTrip, AsGtestTypes<msg::DiscoveryMessages>::type);
template struct VectorComparison<msg::DiscoveryMessages>;
}  // namespace jaus::test
