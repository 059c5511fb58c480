// Visitor that fills a described message from payload bytes. It checks the
// layout only (sizes, counts); ranges are checked separately.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>

#include "detail/field_path.hpp"
#include "detail/record_walk.hpp"
#include "detail/wire_number.hpp"
#include "jaus/clearpath/fields.hpp"
#include "jaus/base/expected.hpp"

namespace jaus::clearpath::detail {

class PayloadReader {
 public:
  explicit PayloadReader(std::span<const std::uint8_t> payload) : in_(payload) {}

  std::optional<Error> error;
  std::size_t position() const { return pos_; }
  std::size_t remaining() const { return in_.size() - pos_; }

  template <class W, class T>
  void operator()(const fields::Number<W, T>& f) {
    W raw{};
    if (!get(raw, f.name)) return;
    f.value = from_wire<T>(raw, f.scale);
  }

  template <class T>
  void operator()(const fields::PackedDateTime<T>& f) {
    get(f.value, f.name);  // any value decodes; JSON shows an invalid one as its number
  }

  template <class S, class B>
  void operator()(const fields::LengthPrefixedText<S, B>& f) {
    std::uint8_t length = 0;
    if (!get(length, f.name)) return;
    if (remaining() < length) return short_of(f.name, length);
    f.value.assign(reinterpret_cast<const char*>(in_.data() + pos_), length);
    pos_ += length;
    if (f.nul_terminated != nullptr) {
      // One reference client appends a NUL and counts it: strip it, remember it.
      *f.nul_terminated = !f.value.empty() && f.value.back() == '\0';
      if (*f.nul_terminated) f.value.pop_back();
    }
  }

  template <class B>
  void operator()(const fields::Flag<B>&) {}

  template <class W, class V>
  void operator()(const fields::NumberList<W, V>& f) {
    std::uint8_t count = 0;
    if (!get(count, f.name)) return;
    if (remaining() < std::size_t{count} * sizeof(W)) return short_of(f.name, std::size_t{count} * sizeof(W));
    f.values.resize(count);
    for (auto& value : f.values) {
      W raw{};
      get(raw, f.name);
      value = from_wire<typename std::remove_cvref_t<V>::value_type>(raw, f.scale);
    }
  }

  template <class V>
  void operator()(const fields::RecordList<V>& f) {
    if (error) return;
    using Record = typename std::remove_cvref_t<V>::value_type;
    f.records.clear();
    if (f.count == fields::Count::implied) {
      // Elements fill the rest of the payload; a partial last element is an error.
      for (std::size_t i = 0; remaining() > 0 && !error; ++i) {
        const auto saved = path_.enter(f.name, i);
        Record::describe(f.records.emplace_back(), *this);
        path_.leave(saved);
      }
      return;
    }
    std::uint8_t count = 0;
    if (!get(count, f.name)) return;
    f.records.resize(count);
    if (f.layout == fields::Layout::rows) {
      for (std::size_t i = 0; i < f.records.size() && !error; ++i) {
        const auto saved = path_.enter(f.name, i);
        Record::describe(f.records[i], *this);
        path_.leave(saved);
      }
      return;
    }
    const std::size_t columns = field_count<Record>();
    for (std::size_t column = 0; column < columns && !error; ++column) {
      for (std::size_t i = 0; i < f.records.size() && !error; ++i) {
        const auto saved = path_.enter(f.name, i);
        ColumnVisitor<PayloadReader> only{*this, column};
        Record::describe(f.records[i], only);
        path_.leave(saved);
      }
    }
  }

  template <class R>
  void operator()(const fields::Group<R>& f) {
    if (error) return;
    const auto saved = path_.enter(f.name);
    std::remove_cvref_t<R>::describe(f.record, *this);
    path_.leave(saved);
  }

 private:
  template <class W>
  bool get(W& out, std::string_view field) {
    if (error) return false;
    if (remaining() < sizeof(W)) {
      short_of(field, sizeof(W));
      return false;
    }
    std::make_unsigned_t<W> bits = 0;
    for (std::size_t i = 0; i < sizeof(W); ++i)
      bits = static_cast<decltype(bits)>(bits | (static_cast<decltype(bits)>(in_[pos_ + i]) << (8 * i)));
    pos_ += sizeof(W);
    out = static_cast<W>(bits);
    return true;
  }
  void short_of(std::string_view field, std::size_t needed) {
    if (error) return;
    error = Error{ErrorCode::truncated, pos_, path_.at(field),
                  "needs " + std::to_string(needed) + " bytes, " + std::to_string(remaining()) + " left"};
  }

  std::span<const std::uint8_t> in_;
  std::size_t pos_ = 0;
  FieldPath path_;
};

}  // namespace jaus::clearpath::detail
