// The per-message-type checks of the manipulator messages: round trip and vector comparison.
#include "round_trip.hpp"
#include "vector_compare_impl.hpp"

namespace jaus::test {
INSTANTIATE_TYPED_TEST_SUITE_P(Manipulator, RoundTrip, AsGtestTypes<msg::ManipulatorMessages>::type);
template struct VectorComparison<msg::ManipulatorMessages>;
}  // namespace jaus::test
