// Visitors between a described message and its JSON "fields" object.
#pragma once

#include <optional>
#include <string>
#include <type_traits>
#include <utility>

#include <nlohmann/json.hpp>

#include "detail/field_path.hpp"
#include "detail/wire_number.hpp"
#include "jaus/clearpath/fields.hpp"
#include "jaus/clearpath/packed_date_time.hpp"
#include "jaus/base/expected.hpp"

namespace jaus::clearpath::detail {

class JsonWriter {
 public:
  explicit JsonWriter(nlohmann::json& out) : out_(out) { out_ = nlohmann::json::object(); }

  template <class W, class T>
  void operator()(const fields::Number<W, T>& f) {
    if constexpr (std::is_integral_v<std::remove_const_t<T>>) {
      for (const auto& n : f.names)
        if (std::cmp_equal(n.value, f.value)) {
          out_[std::string(f.name)] = std::string(n.name);
          return;
        }
    }
    out_[std::string(f.name)] = f.value;
  }
  template <class T>
  void operator()(const fields::PackedDateTime<T>& f) {
    if (const auto parts = unpack_date_time(f.value))
      out_[std::string(f.name)] = format_date_time(*parts);
    else
      out_[std::string(f.name)] = f.value;
  }
  template <class S, class B>
  void operator()(const fields::LengthPrefixedText<S, B>& f) {
    out_[std::string(f.name)] = f.value;
    if (f.nul_terminated != nullptr) out_[std::string(f.name) + "_nul_terminated"] = *f.nul_terminated;
  }
  template <class B>
  void operator()(const fields::Flag<B>& f) { out_[std::string(f.name)] = f.value; }
  template <class W, class V>
  void operator()(const fields::NumberList<W, V>& f) {
    auto array = nlohmann::json::array();
    for (const auto& v : f.values) array.push_back(v);
    out_[std::string(f.name)] = std::move(array);
  }
  template <class V>
  void operator()(const fields::RecordList<V>& f) {
    auto array = nlohmann::json::array();
    for (const auto& record : f.records) {
      nlohmann::json element;
      JsonWriter nested(element);
      std::remove_cvref_t<decltype(record)>::describe(record, nested);
      array.push_back(std::move(element));
    }
    out_[std::string(f.name)] = std::move(array);
  }
  template <class R>
  void operator()(const fields::Group<R>& f) {
    nlohmann::json element;
    JsonWriter nested(element);
    std::remove_cvref_t<R>::describe(f.record, nested);
    out_[std::string(f.name)] = std::move(element);
  }

 private:
  nlohmann::json& out_;
};

// Every wire field must be present and of the right JSON type; integers must
// fit their wire field. Flags and NUL markers are optional (default false).
class JsonReader {
 public:
  JsonReader(const nlohmann::json& in, FieldPath& path) : in_(in), path_(path) {}

  std::optional<Error> error;

  template <class W, class T>
  void operator()(const fields::Number<W, T>& f) {
    const auto* j = require(f.name);
    if (j == nullptr) return;
    if (j->is_string() && !f.names.empty()) {
      const auto name = j->template get<std::string>();
      for (const auto& n : f.names)
        if (n.name == name) {
          f.value = static_cast<T>(n.value);
          return;
        }
      return fail(path_.at(f.name),
                  "unknown name '" + name + "' (expected one of: " + names_of(f.names) + ", or a number)");
    }
    read_number<W>(*j, f.value, f.scale, path_.at(f.name));
  }
  // "YYYY-MM-DDTHH:MM" or the raw number.
  template <class T>
  void operator()(const fields::PackedDateTime<T>& f) {
    const auto* j = require(f.name);
    if (j == nullptr) return;
    if (j->is_string()) {
      const auto text = j->template get<std::string>();
      const auto parts = parse_date_time(text);
      if (!parts)
        return fail(path_.at(f.name), "'" + text + "' is not a date-time \"YYYY-MM-DDTHH:MM\" (year 2000-2127)");
      f.value = *pack_date_time(*parts);
      return;
    }
    read_number<std::uint32_t>(*j, f.value, 1.0, path_.at(f.name));
  }
  template <class S, class B>
  void operator()(const fields::LengthPrefixedText<S, B>& f) {
    const auto* j = require(f.name);
    if (j == nullptr) return;
    if (!j->is_string()) return fail(path_.at(f.name), "expected a string");
    f.value = j->template get<std::string>();
    if (f.nul_terminated != nullptr) {
      *f.nul_terminated = false;
      const auto it = in_.find(std::string(f.name) + "_nul_terminated");
      if (it != in_.end()) {
        if (!it->is_boolean()) return fail(path_.at(f.name) + "_nul_terminated", "expected true or false");
        *f.nul_terminated = it->template get<bool>();
      }
    }
  }
  template <class B>
  void operator()(const fields::Flag<B>& f) {
    if (error) return;
    f.value = false;
    const auto it = in_.find(std::string(f.name));
    if (it == in_.end()) return;
    if (!it->is_boolean()) return fail(path_.at(f.name), "expected true or false");
    f.value = it->template get<bool>();
  }
  template <class W, class V>
  void operator()(const fields::NumberList<W, V>& f) {
    const auto* j = require(f.name);
    if (j == nullptr) return;
    if (!j->is_array()) return fail(path_.at(f.name), "expected an array");
    f.values.resize(j->size());
    for (std::size_t i = 0; i < j->size() && !error; ++i)
      read_number<W>((*j)[i], f.values[i], f.scale, path_.at(f.name) + "[" + std::to_string(i) + "]");
  }
  template <class V>
  void operator()(const fields::RecordList<V>& f) {
    const auto* j = require(f.name);
    if (j == nullptr) return;
    if (!j->is_array()) return fail(path_.at(f.name), "expected an array of objects");
    f.records.resize(j->size());
    for (std::size_t i = 0; i < j->size() && !error; ++i) {
      const auto saved = path_.enter(f.name, i);
      read_record((*j)[i], f.records[i]);
      path_.leave(saved);
    }
  }
  template <class R>
  void operator()(const fields::Group<R>& f) {
    const auto* j = require(f.name);
    if (j == nullptr) return;
    const auto saved = path_.enter(f.name);
    read_record(*j, f.record);
    path_.leave(saved);
  }

 private:
  template <class Record>
  void read_record(const nlohmann::json& j, Record& record) {
    if (!j.is_object()) return fail(path_.at(""), "expected an object");
    JsonReader nested(j, path_);
    Record::describe(record, nested);
    if (nested.error) error = nested.error;
  }
  const nlohmann::json* require(std::string_view name) {
    if (error) return nullptr;
    const auto it = in_.find(std::string(name));
    if (it == in_.end()) {
      fail(path_.at(name), "missing field");
      return nullptr;
    }
    return &*it;
  }
  template <class W, class T>
  void read_number(const nlohmann::json& j, T& value, double scale, const std::string& where) {
    if (error) return;
    if constexpr (std::is_floating_point_v<T>) {
      if (!j.is_number()) return fail(where, "expected a number");
      value = j.template get<double>();
      if (!to_wire<W>(value, scale))
        error = Error{ErrorCode::bad_value, 0, where, "value does not fit the wire field"};
    } else {
      if (!j.is_number_integer()) return fail(where, "expected an integer");
      const bool fits = j.is_number_unsigned() ? std::in_range<W>(j.template get<std::uint64_t>())
                                               : std::in_range<W>(j.template get<std::int64_t>());
      if (!fits) {
        error = Error{ErrorCode::bad_value, 0, where, "integer does not fit the wire field"};
        return;
      }
      value = static_cast<T>(j.template get<std::int64_t>());
    }
  }
  static std::string names_of(std::span<const fields::NamedValue> names) {
    std::string out;
    for (const auto& n : names) out += (out.empty() ? "" : ", ") + std::string(n.name);
    return out;
  }
  void fail(std::string where, std::string detail) {
    if (!error) error = Error{ErrorCode::json, 0, std::move(where), std::move(detail)};
  }

  const nlohmann::json& in_;
  FieldPath& path_;
};

}  // namespace jaus::clearpath::detail
