#include "jaus/node/sequence_counters.hpp"

#include <gtest/gtest.h>

#include "jaus/jss/jss_id.hpp"

namespace jaus::node {
namespace {

const Address kDriver{1, 1, 33, 1};
const Address kOcu{2, 1, 40, 1};
const Address kOtherOcu{3, 1, 40, 1};

TEST(SequenceCounters, EachStreamCountsFromZero) {
  SequenceCounters counters;
  EXPECT_EQ(counters.take({kDriver, kOcu}), 0);
  EXPECT_EQ(counters.take({kDriver, kOcu}), 1);
  EXPECT_EQ(counters.take({kDriver, kOtherOcu}), 0);
  EXPECT_EQ(counters.take({kOcu, kDriver}), 0);
  EXPECT_EQ(counters.peek({kDriver, kOcu}), 2);
  EXPECT_EQ(counters.size(), 3u);
}

TEST(SequenceCounters, ReservesARunForALargeDataSet) {
  SequenceCounters counters;
  EXPECT_EQ(counters.take({kDriver, kOcu}, 5), 0);
  EXPECT_EQ(counters.take({kDriver, kOcu}), 5);
}

TEST(SequenceCounters, WrapsAfter65535) {
  SequenceCounters counters;
  const SequenceStream stream{kDriver, kOcu};
  counters.take(stream, 65534);
  EXPECT_EQ(counters.take(stream), 65534);
  EXPECT_EQ(counters.take(stream), 65535);
  EXPECT_EQ(counters.take(stream), 0);
  counters.take(stream, 65533);
  EXPECT_EQ(counters.take(stream, 4), 65534);  // a run may straddle the wrap
  EXPECT_EQ(counters.take(stream), 2);
}

TEST(SequenceCounters, ForgetsTheLeastRecentlyUsedStreamWhenFull) {
  SequenceCounters counters(SequenceCounters::Options{.max_streams = 2});
  counters.take({kDriver, kOcu}, 10);
  counters.take({kDriver, kOtherOcu}, 20);
  counters.take({kDriver, kOcu});          // kOcu is now the most recent
  counters.take({kOcu, kDriver});          // evicts kDriver -> kOtherOcu
  EXPECT_EQ(counters.size(), 2u);
  EXPECT_EQ(counters.evicted(), 1u);
  EXPECT_EQ(counters.peek({kDriver, kOcu}), 11);
  EXPECT_EQ(counters.peek({kDriver, kOtherOcu}), 0);
}

// An operator tool under a kept ID starts each run elsewhere, so a repeated
// command of a new run is not numbered like the last run's (a receiver would
// take it for a copy); every stream, new or forgotten, starts there.
TEST(SequenceCounters, NewStreamsStartAtTheConfiguredFirstNumber) {
  SequenceCounters counters(SequenceCounters::Options{.max_streams = 1, .first = 40000});
  EXPECT_EQ(counters.peek({kDriver, kOcu}), 40000);
  EXPECT_EQ(counters.take({kDriver, kOcu}), 40000);
  EXPECT_EQ(counters.take({kDriver, kOcu}), 40001);
  counters.take({kDriver, kOtherOcu});  // evicts kDriver -> kOcu
  EXPECT_EQ(counters.take({kDriver, kOcu}), 40000);
}

// The JSS face numbers per destination JSS ID with the same counters: one
// series per destination, the least recently used forgotten when full.
TEST(SequenceCounters, AJssFaceCountsPerDestinationId) {
  BasicSequenceCounters<jss::JssId> counters({.max_streams = 2});
  const jss::JssId client{200, 1, 1}, other{201, 1, 1}, third{202, 1, 1};
  EXPECT_EQ(counters.take(client, 3), 0);  // a large message's three packets
  EXPECT_EQ(counters.take(client), 3);
  EXPECT_EQ(counters.take(other), 0);
  counters.take(client);  // client is now the most recent
  EXPECT_EQ(counters.take(third), 0);  // forgets other
  EXPECT_EQ(counters.evicted(), 1u);
  EXPECT_EQ(counters.peek(other), 0);
  EXPECT_EQ(counters.peek(client), 5);
}

}  // namespace
}  // namespace jaus::node
