#include "round_trip.hpp"

namespace jaus::test {
INSTANTIATE_TYPED_TEST_SUITE_P(Core, RoundTrip, AsGtestTypes<msg::CoreMessages>::type);
}  // namespace jaus::test
