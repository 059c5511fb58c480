// rt::Callback, what the scheduler runs: small captures in place (no
// allocation per timer or post), larger and move-only ones still work, and
// what a callback captures is destroyed exactly once whatever moves it.
#include <gtest/gtest.h>

#include <array>
#include <memory>

#include "jaus/base/callback.hpp"

namespace jaus::rt {
namespace {

struct Owner {
  int calls = 0;
};

TEST(Callback, ATimersUsualCaptureIsKeptInPlace) {
  Owner owner;
  std::shared_ptr<const char> alive = std::make_shared<const char>(0);
  auto timer = [o = &owner, alive = std::weak_ptr<const char>(alive), key = 42u] {
    if (!alive.expired()) o->calls += static_cast<int>(key);
  };
  static_assert(Callback::stored_in_place<decltype(timer)>);
  static_assert(Callback::stored_in_place<std::function<void()>>);  // a std::function handed over as it is
  Callback callback(std::move(timer));
  callback();
  EXPECT_EQ(owner.calls, 42);
}

TEST(Callback, ALargeCaptureGoesToTheHeapAndStillRuns) {
  std::array<int, 64> values{};
  values[63] = 7;
  int seen = 0;
  auto large = [values, &seen] { seen = values[63]; };
  static_assert(!Callback::stored_in_place<decltype(large)>);
  Callback callback(large);
  Callback moved(std::move(callback));
  EXPECT_FALSE(callback);  // NOLINT(bugprone-use-after-move): a moved-from Callback is empty
  moved();
  EXPECT_EQ(seen, 7);
}

TEST(Callback, MoveOnlyCapturesAreAccepted) {
  auto value = std::make_unique<int>(5);
  int seen = 0;
  Callback callback([v = std::move(value), &seen] { seen = *v; });
  callback();
  EXPECT_EQ(seen, 5);
}

// Whatever moves it, in place or on the heap, a capture is destroyed once.
template <std::size_t Padding>
void captured_state_is_destroyed_exactly_once() {
  auto token = std::make_shared<int>(0);
  {
    std::array<char, Padding> padding{};
    Callback first([token, padding] { (void)padding; });
    EXPECT_EQ(token.use_count(), 2);
    Callback second(std::move(first));
    EXPECT_EQ(token.use_count(), 2);
    Callback third;
    third = std::move(second);
    EXPECT_EQ(token.use_count(), 2);
    third = Callback([] {});  // assigning over it destroys what it held
    EXPECT_EQ(token.use_count(), 1);
    Callback fourth([token, padding] { (void)padding; });
    Callback& same = fourth;
    fourth = std::move(same);  // self-move keeps it
    EXPECT_EQ(token.use_count(), 2);
  }
  EXPECT_EQ(token.use_count(), 1);
}

TEST(Callback, CapturedStateIsDestroyedExactlyOnceInPlace) { captured_state_is_destroyed_exactly_once<8>(); }
TEST(Callback, CapturedStateIsDestroyedExactlyOnceOnTheHeap) { captured_state_is_destroyed_exactly_once<128>(); }

TEST(Callback, AnEmptyFunctionStaysEmptyAndCallingItThrows) {
  Callback none;
  EXPECT_FALSE(none);
  EXPECT_THROW(none(), std::bad_function_call);
  Callback from_empty_function(std::function<void()>{});
  EXPECT_FALSE(from_empty_function);
  Callback from_null(nullptr);
  EXPECT_FALSE(from_null);
  Callback some([] {});
  EXPECT_TRUE(some);
}

}  // namespace
}  // namespace jaus::rt
