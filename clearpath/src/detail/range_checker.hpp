// Visitor that finds the first field outside its documented range.
#pragma once

#include <optional>
#include <string>

#include "detail/field_path.hpp"
#include "detail/wire_number.hpp"
#include "jaus/clearpath/fields.hpp"
#include "jaus/clearpath/packed_date_time.hpp"
#include "jaus/base/expected.hpp"

namespace jaus::clearpath::detail {

class RangeChecker {
 public:
  std::optional<Error> error;

  template <class W, class T>
  void operator()(const fields::Number<W, T>& f) {
    if (!error && !within(f.value, f.scale, f.min, f.max)) fail(f.name, f.min, f.max, static_cast<double>(f.value));
  }
  // The document's part ranges (a received value out of them still decodes).
  template <class T>
  void operator()(const fields::PackedDateTime<T>& f) {
    if (!error && !unpack_date_time(f.value))
      error = Error{ErrorCode::out_of_range, 0, path_.at(f.name),
                    std::to_string(f.value) +
                        " is not a packed date-time (minute 0-59, hour 0-23, day 1-31, "
                        "month 1-12, year 2000-2127, bits 28-31 zero)"};
  }
  template <class S, class B>
  void operator()(const fields::LengthPrefixedText<S, B>& f) {
    if (!error && f.value.size() > f.max_length)
      error = Error{ErrorCode::string_too_long, 0, path_.at(f.name),
                    "at most " + std::to_string(f.max_length) + " characters"};
  }
  template <class B>
  void operator()(const fields::Flag<B>&) {}
  template <class W, class V>
  void operator()(const fields::NumberList<W, V>& f) {
    for (std::size_t i = 0; i < f.values.size() && !error; ++i)
      if (!within(f.values[i], f.scale, f.min, f.max))
        fail(std::string(f.name) + "[" + std::to_string(i) + "]", f.min, f.max, static_cast<double>(f.values[i]));
  }
  template <class V>
  void operator()(const fields::RecordList<V>& f) {
    for (std::size_t i = 0; i < f.records.size() && !error; ++i) {
      const auto saved = path_.enter(f.name, i);
      std::remove_cvref_t<decltype(f.records[i])>::describe(f.records[i], *this);
      path_.leave(saved);
    }
  }
  template <class R>
  void operator()(const fields::Group<R>& f) {
    const auto saved = path_.enter(f.name);
    std::remove_cvref_t<R>::describe(f.record, *this);
    path_.leave(saved);
  }

 private:
  void fail(std::string_view field, double min, double max, double value) {
    error = Error{ErrorCode::out_of_range, 0, path_.at(field),
                  std::to_string(value) + " not in [" + std::to_string(min) + ", " + std::to_string(max) + "]"};
  }
  FieldPath path_;
};

}  // namespace jaus::clearpath::detail
