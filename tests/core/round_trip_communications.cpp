#include "round_trip.hpp"

namespace jaus::test {
INSTANTIATE_TYPED_TEST_SUITE_P(Communications, RoundTrip, AsGtestTypes<msg::CommunicationsMessages>::type);
}  // namespace jaus::test
