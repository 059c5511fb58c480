// A minimal value-or-error type (C++20 has no std::expected). Nothing in the
// libraries throws: every fallible operation returns one of these, with the
// project's one Error type unless a caller needs a richer one.
#pragma once

#include <cassert>
#include <optional>
#include <utility>
#include <variant>

#include "jaus/base/error.hpp"

namespace jaus {

template <class E>
struct Unexpected {
  E error;
};

template <class E>
Unexpected<E> unexpected(E e) {
  return Unexpected<E>{std::move(e)};
}

template <class T, class E = Error>
class Expected {
 public:
  Expected(T value) : state_(std::in_place_index<0>, std::move(value)) {}  // NOLINT: implicit by design
  Expected(Unexpected<E> u) : state_(std::in_place_index<1>, std::move(u.error)) {}  // NOLINT

  bool has_value() const { return state_.index() == 0; }
  explicit operator bool() const { return has_value(); }

  T& value() & { assert(has_value()); return std::get<0>(state_); }
  const T& value() const& { assert(has_value()); return std::get<0>(state_); }
  T&& value() && { assert(has_value()); return std::get<0>(std::move(state_)); }
  const E& error() const { assert(!has_value()); return std::get<1>(state_); }

  T& operator*() & { return value(); }
  const T& operator*() const& { return value(); }
  T* operator->() { return &value(); }
  const T* operator->() const { return &value(); }

 private:
  std::variant<T, E> state_;
};

// Where nothing is returned: success, or the error. `return {};` succeeds;
// `if (!result) ... result.error()`. The one style for every fallible
// operation without a value (no optional<Error>, no bool and out-string).
// Success constructs and destroys no E: the error lives in an optional that
// stays empty. (An Error member built on every success, its two strings set up
// and torn down, made wire::decode_payload_into 52 instructions a message
// slower, issue 50.)
template <class E>
class Expected<void, E> {
 public:
  // User-provided, not `= default`: `return {};` value-initialises, and with a
  // defaulted constructor that first zero-fills the whole object, the unused
  // error storage included (88 bytes, a `rep stos` on every success; issue 50).
  Expected() noexcept {}  // NOLINT(modernize-use-equals-default): see above
  Expected(Unexpected<E> u) : error_(std::in_place, std::move(u.error)) {}  // NOLINT: implicit by design

  bool has_value() const { return !error_.has_value(); }
  explicit operator bool() const { return has_value(); }
  void value() const { assert(has_value()); }
  const E& error() const { assert(!has_value()); return *error_; }

 private:
  std::optional<E> error_;
};

}  // namespace jaus
