#include "round_trip.hpp"

namespace jaus::test {
INSTANTIATE_TYPED_TEST_SUITE_P(Manipulator, RoundTrip, AsGtestTypes<msg::ManipulatorMessages>::type);
}  // namespace jaus::test
