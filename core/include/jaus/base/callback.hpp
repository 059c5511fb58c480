// What the scheduler runs: a move-only `void()` callable that keeps small
// callables in place. A timer or a posted task usually captures `this`, a
// key and perhaps a weak_ptr; std::function stores only trivially copyable
// callables of up to 16 bytes in place and allocates for everything else,
// which is an allocation per report period and per burst of datagrams on a
// node's hot path. Up to kInlineSize bytes live here; larger callables go to
// the heap, as they would in std::function.
#pragma once

#include <cstddef>
#include <functional>
#include <memory>
#include <new>
#include <type_traits>
#include <utility>

namespace jaus::rt {

class Callback {
 public:
  static constexpr std::size_t kInlineSize = 48;

  Callback() noexcept = default;
  Callback(std::nullptr_t) noexcept {}  // NOLINT(google-explicit-constructor): as std::function

  template <class F, class Stored = std::decay_t<F>>
    requires(!std::is_same_v<Stored, Callback> && std::is_invocable_r_v<void, Stored&>)
  Callback(F&& f) {  // NOLINT(google-explicit-constructor): lambdas convert, as to std::function
    if constexpr (requires { f == nullptr; }) {
      if (f == nullptr) return;  // an empty std::function or a null function pointer stays empty
    }
    if constexpr (stored_in_place<Stored>) {
      ::new (static_cast<void*>(storage_)) Stored(std::forward<F>(f));
      ops_ = &kInPlace<Stored>;
    } else {
      ::new (static_cast<void*>(storage_)) Stored*(new Stored(std::forward<F>(f)));
      ops_ = &kOnHeap<Stored>;
    }
  }

  Callback(Callback&& other) noexcept { take(other); }
  Callback& operator=(Callback&& other) noexcept {
    if (this != &other) {
      reset();
      take(other);
    }
    return *this;
  }
  Callback(const Callback&) = delete;
  Callback& operator=(const Callback&) = delete;
  ~Callback() { reset(); }

  explicit operator bool() const noexcept { return ops_ != nullptr; }

  // Calling an empty Callback is a programming error, as for std::function.
  void operator()() {
    if (ops_ == nullptr) throw std::bad_function_call();
    ops_->invoke(storage_);
  }

  // Whether a callable of type F is kept without allocating.
  template <class F>
  static constexpr bool stored_in_place =
      sizeof(F) <= kInlineSize && alignof(F) <= alignof(std::max_align_t) && std::is_nothrow_move_constructible_v<F>;

 private:
  struct Ops {
    void (*invoke)(void* storage);
    void (*move)(void* from, void* to) noexcept;  // constructs at `to`, destroys `from`
    void (*destroy)(void* storage) noexcept;
  };

  template <class F>
  static constexpr Ops kInPlace{
      [](void* s) { (*std::launder(static_cast<F*>(s)))(); },
      [](void* from, void* to) noexcept {
        F* source = std::launder(static_cast<F*>(from));
        ::new (to) F(std::move(*source));
        source->~F();
      },
      [](void* s) noexcept { std::launder(static_cast<F*>(s))->~F(); },
  };
  template <class F>
  static constexpr Ops kOnHeap{
      [](void* s) { (**std::launder(static_cast<F**>(s)))(); },
      [](void* from, void* to) noexcept { ::new (to) F*(*std::launder(static_cast<F**>(from))); },
      [](void* s) noexcept { delete *std::launder(static_cast<F**>(s)); },
  };

  void take(Callback& other) noexcept {
    if (other.ops_ == nullptr) return;
    other.ops_->move(other.storage_, storage_);
    ops_ = std::exchange(other.ops_, nullptr);
  }
  void reset() noexcept {
    if (ops_ == nullptr) return;
    std::exchange(ops_, nullptr)->destroy(storage_);
  }

  alignas(std::max_align_t) unsigned char storage_[kInlineSize];
  const Ops* ops_ = nullptr;
};

}  // namespace jaus::rt
