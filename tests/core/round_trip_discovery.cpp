#include "round_trip.hpp"

namespace jaus::test {
INSTANTIATE_TYPED_TEST_SUITE_P(Discovery, RoundTrip, AsGtestTypes<msg::DiscoveryMessages>::type);
}  // namespace jaus::test
