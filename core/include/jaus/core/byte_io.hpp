// Bounds-checked little-endian reader and writer over caller-owned buffers.
// Both keep the first error (sticky): after a failure every further call is a
// no-op, so codecs can run straight-line and check once at the end.
#pragma once

#include <bit>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <optional>
#include <span>
#include <string_view>

#include "jaus/core/error.hpp"

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
      : bytes_(bytes), base_offset_(base_offset) {}

  template <WireScalar T>
  bool read(T& out) {
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

  // Which field is being read, for error messages (static storage).
  void set_field(std::string_view field) { field_ = field; }
  std::string_view field() const { return field_; }

  void fail(ErrorCode code, std::string detail = {}) {
    if (error_) return;
    error_ = Error{code, offset(), field_, std::move(detail)};
  }
  // Fails naming an earlier absolute offset (e.g. the start of a field already read).
  void fail_at(ErrorCode code, std::size_t absolute_offset, std::string detail = {}) {
    if (error_) return;
    error_ = Error{code, absolute_offset, field_, std::move(detail)};
  }
  bool failed() const { return error_.has_value(); }
  const std::optional<Error>& error() const { return error_; }

 private:
  bool has_room(std::size_t n) const { return !error_ && bytes_.size() - pos_ >= n; }
  // Kept out of line: the hot path is the bounds check above.
  [[gnu::noinline]] bool fail_truncated(std::size_t n) {
    if (!failed())
      fail(ErrorCode::truncated,
           "needs " + std::to_string(n) + " bytes, " + std::to_string(bytes_.size() - pos_) + " left");
    return false;
  }

  std::span<const std::uint8_t> bytes_;
  std::size_t base_offset_ = 0;
  std::size_t pos_ = 0;
  std::string_view field_;
  std::optional<Error> error_;
};

class ByteWriter {
 public:
  explicit ByteWriter(std::span<std::uint8_t> out) : out_(out) {}

  template <WireScalar T>
  bool write(T value) {
    if (!has_room(sizeof(T))) [[unlikely]]
      return fail_full();
    detail::to_little_endian<T>(value, out_.data() + pos_);
    pos_ += sizeof(T);
    return true;
  }

  bool write_bytes(std::span<const std::uint8_t> bytes) {
    if (!require(bytes.size())) return false;
    if (!bytes.empty()) std::memcpy(out_.data() + pos_, bytes.data(), bytes.size());
    pos_ += bytes.size();
    return true;
  }

  bool write_zeros(std::size_t n) {
    if (!require(n)) return false;
    std::memset(out_.data() + pos_, 0, n);
    pos_ += n;
    return true;
  }

  // Overwrite already-written bytes (e.g. a count or size known only later).
  template <WireScalar T>
  void patch(std::size_t at, T value) {
    if (!failed() && at + sizeof(T) <= pos_) detail::to_little_endian<T>(value, out_.data() + at);
  }

  std::size_t size() const { return pos_; }
  std::span<std::uint8_t> written() const { return out_.first(pos_); }

  void set_field(std::string_view field) { field_ = field; }
  std::string_view field() const { return field_; }
  void fail(ErrorCode code, std::string detail = {}) {
    if (error_) return;
    error_ = Error{code, pos_, field_, std::move(detail)};
  }
  bool failed() const { return error_.has_value(); }
  const std::optional<Error>& error() const { return error_; }

 private:
  bool has_room(std::size_t n) const { return !error_ && out_.size() - pos_ >= n; }
  [[gnu::noinline]] bool fail_full() {
    fail(ErrorCode::output_too_small);
    return false;
  }
  bool require(std::size_t n) { return has_room(n) || fail_full(); }

  std::span<std::uint8_t> out_;
  std::size_t pos_ = 0;
  std::string_view field_;
  std::optional<Error> error_;
};

}  // namespace jaus
