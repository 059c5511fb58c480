// The per-message-type checks of the platform messages: round trip and vector comparison.
#include "round_trip.hpp"
#include "vector_compare_impl.hpp"

namespace jaus::test {
INSTANTIATE_TYPED_TEST_SUITE_P(Platform, RoundTrip, AsGtestTypes<msg::PlatformMessages>::type);
template struct VectorComparison<msg::PlatformMessages>;
}  // namespace jaus::test
