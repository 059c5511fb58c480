// The per-message-type checks of the event messages: round trip and vector comparison.
#include "round_trip.hpp"
#include "vector_compare_impl.hpp"

namespace jaus::test {
INSTANTIATE_TYPED_TEST_SUITE_P(Events, RoundTrip, AsGtestTypes<msg::EventMessages>::type);
template struct VectorComparison<msg::EventMessages>;
}  // namespace jaus::test
