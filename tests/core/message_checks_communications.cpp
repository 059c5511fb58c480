// The per-message-type checks of the communications messages: round trip and vector comparison.
#include "round_trip.hpp"
#include "vector_compare_impl.hpp"

namespace jaus::test {
INSTANTIATE_TYPED_TEST_SUITE_P(Communications, RoundTrip, AsGtestTypes<msg::CommunicationsMessages>::type);
template struct VectorComparison<msg::CommunicationsMessages>;
}  // namespace jaus::test
