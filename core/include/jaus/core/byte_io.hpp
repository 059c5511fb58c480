// Bounds-checked little-endian reader and writer over caller-owned buffers.
// Both keep the first error (sticky): after a failure every further call is a
// no-op, so codecs can run straight-line and check once at the end.
#pragma once

#include <bit>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <memory>
#include <span>
#include <string>
#include <string_view>

#include "jaus/base/error.hpp"

// Per-field codec steps are a handful of instructions; keeping them inline lets
// a whole message encode or decode as straight-line code. Only where the
// compiler optimizes: at -O0 (the sanitizer tree) forced inlining buys no
// speed and made every message's walk one huge function to compile and
// instrument (about half of the catalogue's compile time there).
#if defined(__OPTIMIZE__)
#define JAUS_ALWAYS_INLINE [[gnu::always_inline]] inline
// The same for a lambda (placed after the parameter list).
#define JAUS_ALWAYS_INLINE_LAMBDA __attribute__((always_inline))
#else
#define JAUS_ALWAYS_INLINE inline
#define JAUS_ALWAYS_INLINE_LAMBDA
#endif

namespace jaus {

template <class T>
concept WireScalar = std::integral<T> || std::floating_point<T>;

namespace detail {
template <WireScalar T>
T from_little_endian(const std::uint8_t* p) {
  T value;
  std::memcpy(&value, p, sizeof(T));
  if constexpr (std::endian::native == std::endian::big && sizeof(T) > 1) {
    auto* b = reinterpret_cast<std::uint8_t*>(&value);
    for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(b[i], b[sizeof(T) - 1 - i]);
  }
  return value;
}
template <WireScalar T>
void to_little_endian(T value, std::uint8_t* p) {
  if constexpr (std::endian::native == std::endian::big && sizeof(T) > 1) {
    auto* b = reinterpret_cast<std::uint8_t*>(&value);
    for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(b[i], b[sizeof(T) - 1 - i]);
  }
  std::memcpy(p, &value, sizeof(T));
}
}  // namespace detail

class ByteReader {
 public:
  explicit ByteReader(std::span<const std::uint8_t> bytes, std::size_t base_offset = 0)
      : bytes_(bytes), base_offset_(base_offset), limit_(bytes.size()) {}

  template <WireScalar T>
  JAUS_ALWAYS_INLINE bool read(T& out) {
    if (!has_room(sizeof(T))) [[unlikely]]
      return fail_truncated(sizeof(T));
    out = detail::from_little_endian<T>(bytes_.data() + pos_);
    pos_ += sizeof(T);
    return true;
  }

  // A view of the next n bytes (valid while the underlying buffer lives).
  bool read_bytes(std::size_t n, std::span<const std::uint8_t>& out) {
    if (!has_room(n)) [[unlikely]]
      return fail_truncated(n);
    out = bytes_.subspan(pos_, n);
    pos_ += n;
    return true;
  }

  std::size_t remaining() const { return failed() ? 0 : bytes_.size() - pos_; }
  std::size_t offset() const { return base_offset_ + pos_; }

  // For a caller that checked remaining() and reads the bytes itself
  // (an UncheckedReader), then skips them (n <= remaining()).
  const std::uint8_t* cursor() const { return bytes_.data() + pos_; }
  void skip(std::size_t n) { pos_ += n; }

  // Which field is being read, for error messages (static storage).
  void set_field(std::string_view field) { field_ = field; }
  std::string_view field() const { return field_; }

  void fail(ErrorCode code, std::string detail = {}) { fail_at(code, offset(), std::move(detail)); }
  // Fails naming an earlier absolute offset (e.g. the start of a field already read).
  void fail_at(ErrorCode code, std::size_t absolute_offset, std::string detail = {}) {
    if (error_) return;
    error_ = std::make_unique<Error>(Error{code, absolute_offset, std::string(field_), std::move(detail)});
    limit_ = pos_;
  }
  bool failed() const { return error_ != nullptr; }
  // The first error; only when failed().
  const Error& error() const { return *error_; }

 private:
  // After a failure the limit drops to the current position, so the check
  // below is the only one on the hot path.
  bool has_room(std::size_t n) const { return limit_ - pos_ >= n; }
  // Kept out of line: the hot path is the bounds check above.
  [[gnu::noinline]] bool fail_truncated(std::size_t n) {
    if (!failed())
      fail(ErrorCode::truncated,
           "needs " + std::to_string(n) + " bytes, " + std::to_string(bytes_.size() - pos_) + " left");
    return false;
  }

  std::span<const std::uint8_t> bytes_;
  std::size_t base_offset_ = 0;
  std::size_t limit_ = 0;
  std::size_t pos_ = 0;
  std::string_view field_;
  // Allocated only on failure, so that a healthy read or write costs nothing.
  std::unique_ptr<Error> error_;
};

class ByteWriter {
 public:
  explicit ByteWriter(std::span<std::uint8_t> out)
      : begin_(out.data()), cur_(out.data()), end_(out.data() + out.size()) {}

  template <WireScalar T>
  JAUS_ALWAYS_INLINE bool write(T value) {
    if (static_cast<std::size_t>(end_ - cur_) < sizeof(T)) [[unlikely]]
      return fail_full();
    detail::to_little_endian<T>(value, cur_);
    cur_ += sizeof(T);
    return true;
  }

  bool write_bytes(std::span<const std::uint8_t> bytes) {
    if (static_cast<std::size_t>(end_ - cur_) < bytes.size()) return fail_full();
    if (!bytes.empty()) std::memcpy(cur_, bytes.data(), bytes.size());
    cur_ += bytes.size();
    return true;
  }

  bool write_zeros(std::size_t n) {
    if (static_cast<std::size_t>(end_ - cur_) < n) return fail_full();
    std::memset(cur_, 0, n);
    cur_ += n;
    return true;
  }

  // Overwrite already-written bytes (e.g. a count or size known only later).
  template <WireScalar T>
  void patch(std::size_t at, T value) {
    if (!failed() && at + sizeof(T) <= size()) detail::to_little_endian<T>(value, begin_ + at);
  }

  std::size_t size() const { return static_cast<std::size_t>(cur_ - begin_); }
  std::span<std::uint8_t> written() const { return {begin_, size()}; }

  // For a caller that checked room() and writes the bytes itself (an
  // UncheckedWriter), then commits them (n <= room()).
  std::size_t room() const { return static_cast<std::size_t>(end_ - cur_); }
  std::uint8_t* cursor() const { return cur_; }
  void commit(std::size_t n) { cur_ += n; }

  void set_field(std::string_view field) { field_ = field; }
  std::string_view field() const { return field_; }
  void fail(ErrorCode code, std::string detail = {}) {
    if (error_) return;
    error_ = std::make_unique<Error>(Error{code, size(), std::string(field_), std::move(detail)});
    end_ = cur_;  // nothing more fits: every later write fails fast
  }
  bool failed() const { return error_ != nullptr; }
  // The first error; only when failed().
  const Error& error() const { return *error_; }

 private:
  [[gnu::noinline]] bool fail_full() {
    fail(ErrorCode::output_too_small);
    return false;
  }

  std::uint8_t* begin_;
  std::uint8_t* cur_;
  std::uint8_t* end_;
  std::string_view field_;
  // Allocated only on failure, so that a healthy write costs nothing.
  std::unique_ptr<Error> error_;
};

// The same interfaces over bytes whose extent the caller has already checked
// (a message of fixed layout checks its whole size once, describe.hpp): no
// bounds check per value and no field names, so that the cursor stays in a
// register. Errors are left to ByteReader/ByteWriter: a reader has no error
// of its own, and a writer only notes that a codec refused a value so that
// the caller can redo the message with a ByteWriter, which reports it.
class UncheckedReader {
 public:
  explicit UncheckedReader(const std::uint8_t* at) : begin_(at), cur_(at) {}

  template <WireScalar T>
  JAUS_ALWAYS_INLINE bool read(T& out) {
    out = detail::from_little_endian<T>(cur_);
    cur_ += sizeof(T);
    return true;
  }
  bool read_bytes(std::size_t n, std::span<const std::uint8_t>& out) {
    out = {cur_, n};
    cur_ += n;
    return true;
  }
  std::size_t size() const { return static_cast<std::size_t>(cur_ - begin_); }  // bytes read
  void set_field(std::string_view) {}

 private:
  const std::uint8_t* begin_;
  const std::uint8_t* cur_;
};

class UncheckedWriter {
 public:
  explicit UncheckedWriter(std::uint8_t* at) : begin_(at), cur_(at) {}

  template <WireScalar T>
  JAUS_ALWAYS_INLINE bool write(T value) {
    detail::to_little_endian<T>(value, cur_);
    cur_ += sizeof(T);
    return true;
  }
  bool write_bytes(std::span<const std::uint8_t> bytes) {
    if (!bytes.empty()) std::memcpy(cur_, bytes.data(), bytes.size());
    cur_ += bytes.size();
    return true;
  }
  bool write_zeros(std::size_t n) {
    std::memset(cur_, 0, n);
    cur_ += n;
    return true;
  }

  std::size_t size() const { return static_cast<std::size_t>(cur_ - begin_); }  // bytes written
  void set_field(std::string_view) {}
  void fail(ErrorCode, const std::string& = {}) { failed_ = true; }
  bool failed() const { return failed_; }

 private:
  std::uint8_t* begin_;
  std::uint8_t* cur_;
  bool failed_ = false;
};

}  // namespace jaus
