#include "round_trip.hpp"

namespace jaus::test {
INSTANTIATE_TYPED_TEST_SUITE_P(Events, RoundTrip, AsGtestTypes<msg::EventMessages>::type);
}  // namespace jaus::test
