#include "round_trip.hpp"

namespace jaus::test {
INSTANTIATE_TYPED_TEST_SUITE_P(Platform, RoundTrip, AsGtestTypes<msg::PlatformMessages>::type);
}  // namespace jaus::test
