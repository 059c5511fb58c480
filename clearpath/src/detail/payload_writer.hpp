// Visitor that appends a described message's payload to a byte vector.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "detail/field_path.hpp"
#include "detail/record_walk.hpp"
#include "detail/wire_number.hpp"
#include "jaus/clearpath/fields.hpp"
#include "jaus/base/expected.hpp"

namespace jaus::clearpath::detail {

class PayloadWriter {
 public:
  explicit PayloadWriter(std::vector<std::uint8_t>& out) : out_(out), start_(out.size()) {}

  std::optional<Error> error;

  template <class W, class T>
  void operator()(const fields::Number<W, T>& f) {
    if (error) return;
    const auto raw = to_wire<W>(f.value, f.scale);
    if (!raw) return fail(ErrorCode::bad_value, f.name, "value does not fit the wire field");
    put<W>(*raw);
  }

  template <class T>
  void operator()(const fields::PackedDateTime<T>& f) {
    if (!error) put<std::uint32_t>(f.value);
  }

  template <class S, class B>
  void operator()(const fields::LengthPrefixedText<S, B>& f) {
    if (error) return;
    const bool nul = f.nul_terminated != nullptr && *f.nul_terminated;
    const std::size_t length = f.value.size() + (nul ? 1 : 0);
    if (length > 255) return fail(ErrorCode::string_too_long, f.name, "longer than 255 bytes");
    put<std::uint8_t>(static_cast<std::uint8_t>(length));
    out_.insert(out_.end(), f.value.begin(), f.value.end());
    if (nul) out_.push_back(0);
  }

  template <class B>
  void operator()(const fields::Flag<B>&) {}

  template <class W, class V>
  void operator()(const fields::NumberList<W, V>& f) {
    if (error) return;
    if (f.values.size() > 255) return fail(ErrorCode::count_out_of_range, f.name, "more than 255 elements");
    put<std::uint8_t>(static_cast<std::uint8_t>(f.values.size()));
    for (std::size_t i = 0; i < f.values.size() && !error; ++i) {
      const auto raw = to_wire<W>(f.values[i], f.scale);
      if (!raw) return fail(ErrorCode::bad_value, element(f.name, i), "value does not fit the wire field");
      put<W>(*raw);
    }
  }

  template <class V>
  void operator()(const fields::RecordList<V>& f) {
    if (error) return;
    using Record = typename std::remove_cvref_t<V>::value_type;
    if (f.count == fields::Count::prefixed) {
      if (f.records.size() > 255) return fail(ErrorCode::count_out_of_range, f.name, "more than 255 elements");
      put<std::uint8_t>(static_cast<std::uint8_t>(f.records.size()));
    }
    if (f.layout == fields::Layout::rows) {
      for (std::size_t i = 0; i < f.records.size() && !error; ++i) {
        const auto saved = path_.enter(f.name, i);
        Record::describe(f.records[i], *this);
        path_.leave(saved);
      }
      return;
    }
    const std::size_t columns = field_count<Record>();
    for (std::size_t column = 0; column < columns; ++column) {
      for (std::size_t i = 0; i < f.records.size() && !error; ++i) {
        const auto saved = path_.enter(f.name, i);
        ColumnVisitor<PayloadWriter> only{*this, column};
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
  void put(W value) {
    auto bits = static_cast<std::make_unsigned_t<W>>(value);
    for (std::size_t i = 0; i < sizeof(W); ++i) {
      out_.push_back(static_cast<std::uint8_t>(bits & 0xFFu));
      if constexpr (sizeof(W) > 1) bits = static_cast<decltype(bits)>(bits >> 8);
    }
  }
  static std::string element(std::string_view name, std::size_t i) {
    return std::string(name) + "[" + std::to_string(i) + "]";
  }
  void fail(ErrorCode code, std::string_view field, std::string detail) {
    error = Error{code, out_.size() - start_, path_.at(field), std::move(detail)};
  }

  std::vector<std::uint8_t>& out_;
  std::size_t start_;
  FieldPath path_;
};

}  // namespace jaus::clearpath::detail
