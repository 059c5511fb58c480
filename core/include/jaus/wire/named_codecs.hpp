// Integers whose values or bits have names (Part 3's enumerations and bit
// fields). On the wire they are exactly Int<T>: the same bytes and the same
// one-line encode/decode; only the JSON form and the documentation use the
// names. In memory they stay the integer T, so components keep comparing
// numbers.
//
//   Enum<T, N>   JSON: the value's name ("ready"), or the number when it has
//                none; from JSON: a name or a number.
//   Flags<T, N>  JSON: {"auto_focus": true, ...} (bool for one-bit fields, a
//                number or enum name for wider ones), plus "other_bits" when
//                bits no field covers are set; from JSON: that object or a
//                plain number.
//
// Tools that walk the descriptions (docs, dissector generators) find the
// names through enum_names() and flag_fields().
#pragma once

#include <array>
#include <concepts>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>

#include "jaus/wire/codecs.hpp"

namespace jaus::wire {

struct NamedValue {
  std::uint32_t value;
  std::string_view name;
};

// A field of `width` bits starting at `first_bit` (bit 0 = least significant)
// of a bit-field integer. A wider field may name its values (`values`).
struct NamedBits {
  std::uint8_t first_bit;
  std::uint8_t width;
  std::string_view name;
  std::span<const NamedValue> values{};
};

namespace detail {

constexpr const NamedValue* find_value(std::span<const NamedValue> names, std::uint32_t v) {
  for (const auto& n : names)
    if (n.value == v) return &n;
  return nullptr;
}
constexpr const NamedValue* find_name(std::span<const NamedValue> names, std::string_view name) {
  for (const auto& n : names)
    if (n.name == name) return &n;
  return nullptr;
}
inline std::string name_list(std::span<const NamedValue> names) {
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "" : ", ") + std::string(n.name);
  return out;
}
inline std::string values_doc(std::span<const NamedValue> names) {
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "" : ", ") + std::to_string(n.value) + " " + std::string(n.name);
  return out;
}
constexpr std::uint64_t bits_mask(const NamedBits& b) { return ((std::uint64_t{1} << b.width) - 1) << b.first_bit; }

// A name or a number of at most `max`; a failure names the valid names.
template <class Json>
Expected<void> named_value_from_json(const Json& j, std::span<const NamedValue> names, std::uint64_t max,
                                     std::uint64_t& out) {
  if (j.is_string()) {
    const auto name = j.template get<std::string>();
    if (const auto* n = find_name(names, name)) {
      out = n->value;
      return {};
    }
    return json_error("unknown name '" + name + "' (expected one of: " + name_list(names) + ", or a number)");
  }
  if (auto number = integer_from_json(j, out); !number) {
    if (!j.is_number()) return json_error("expected a name (" + name_list(names) + ") or a number");
    return number;
  }
  if (out > max) return json_error(std::to_string(out) + " does not fit (at most " + std::to_string(max) + ")");
  return {};
}
}  // namespace detail

// The name of `value` in `names`, empty when it has none (for tools that
// print a typed value the way its message's JSON does).
constexpr std::string_view name_of(std::span<const NamedValue> names, std::uint32_t value) {
  const auto* n = detail::find_value(names, value);
  return n != nullptr ? n->name : std::string_view{};
}

// An enumerated integer: JSON is the name when the value has one, else the number; from JSON accepts either.
template <std::unsigned_integral T, std::size_t N>
struct Enum {
  using value_type = T;
  using wire_type = T;
  static constexpr std::size_t fixed_size = sizeof(T);
  std::array<NamedValue, N> names;
  constexpr std::span<const NamedValue> enum_names() const { return names; }

  std::string doc() const { return detail::wire_name<T>() + " enum: " + detail::values_doc(names); }
  JAUS_ALWAYS_INLINE void encode(const T& v, auto& w, auto&) const { w.write(v); }
  JAUS_ALWAYS_INLINE void decode(auto& r, T& v, auto&) const { r.read(v); }
  template <class Json>
  Json to_json(const T& v) const {
    if (const auto* n = detail::find_value(names, v)) return Json(std::string(n->name));
    return Json(v);
  }
  template <class Json>
  Expected<void> from_json(const Json& j, T& v) const {
    std::uint64_t raw = 0;
    if (auto read = detail::named_value_from_json(j, names, std::numeric_limits<T>::max(), raw); !read) return read;
    v = static_cast<T>(raw);
    return {};
  }
};

// A bit-field integer: JSON is an object {name: bool for width 1, name: number (or enum name) for wider fields},
// bits no name covers that are set appear as "other_bits": number; from JSON accepts the object or a plain number.
template <std::unsigned_integral T, std::size_t N>
struct Flags {
  using value_type = T;
  using wire_type = T;
  static constexpr std::size_t fixed_size = sizeof(T);
  std::array<NamedBits, N> fields;
  constexpr std::span<const NamedBits> flag_fields() const { return fields; }

  static constexpr std::string_view kOtherBits = "other_bits";

  constexpr T covered() const {
    std::uint64_t mask = 0;
    for (const auto& f : fields) mask |= detail::bits_mask(f);
    return static_cast<T>(mask);
  }
  std::string doc() const {
    std::string out;
    for (const auto& f : fields) {
      out += out.empty() ? "" : ", ";
      out += f.width == 1 ? "bit " + std::to_string(f.first_bit)
                          : "bits " + std::to_string(f.first_bit) + "-" + std::to_string(f.first_bit + f.width - 1);
      out += " " + std::string(f.name);
      if (!f.values.empty()) out += " (" + detail::values_doc(f.values) + ")";
    }
    return detail::wire_name<T>() + " bits: " + out;
  }
  JAUS_ALWAYS_INLINE void encode(const T& v, auto& w, auto&) const { w.write(v); }
  JAUS_ALWAYS_INLINE void decode(auto& r, T& v, auto&) const { r.read(v); }

  template <class Json>
  Json to_json(const T& v) const {
    Json out = Json::object();
    for (const auto& f : fields) {
      const auto part = static_cast<std::uint32_t>((std::uint64_t{v} & detail::bits_mask(f)) >> f.first_bit);
      if (f.width == 1)
        out[std::string(f.name)] = part != 0;
      else if (const auto* n = detail::find_value(f.values, part))
        out[std::string(f.name)] = std::string(n->name);
      else
        out[std::string(f.name)] = part;
    }
    if (const T other = static_cast<T>(v & ~covered()); other != 0) out[std::string(kOtherBits)] = other;
    return out;
  }

  template <class Json>
  Expected<void> from_json(const Json& j, T& v) const {
    if (j.is_number()) return detail::integer_from_json(j, v);
    if (!j.is_object()) return detail::json_error("expected an object {" + field_names() + "} or a number");
    std::uint64_t raw = 0;
    for (const auto& [key, value] : j.items()) {
      const std::string where = "'" + key + "'";
      if (key == kOtherBits) {
        T other{};
        if (auto read = detail::integer_from_json(value, other); !read) return detail::json_error_in(where, read.error());
        if ((other & covered()) != 0) return detail::json_error("'other_bits' overlaps the named bits");
        raw |= other;
        continue;
      }
      const NamedBits* field = nullptr;
      for (const auto& f : fields)
        if (f.name == key) field = &f;
      if (field == nullptr)
        return detail::json_error("unknown bit field '" + key + "' (expected: " + field_names() + ")");
      std::uint64_t part = 0;
      if (field->width == 1) {
        if (value.is_boolean()) {
          part = value.template get<bool>() ? 1 : 0;
        } else if (!detail::integer_from_json(value, part) || part > 1) {
          return detail::json_error(where + ": expected true or false");
        }
      } else if (auto read = detail::named_value_from_json(value, field->values,
                                                           (std::uint64_t{1} << field->width) - 1, part);
                 !read) {
        return detail::json_error_in(where, read.error());
      }
      raw |= part << field->first_bit;
    }
    v = static_cast<T>(raw);
    return {};
  }

 private:
  std::string field_names() const {
    std::string out;
    for (const auto& f : fields) out += std::string(f.name) + ", ";
    return out + std::string(kOtherBits);
  }
};

// enum_of<std::uint8_t>({{0, "initialize"}, {1, "ready"}}) or enum_of<std::uint8_t>(kSharedTable).
template <std::unsigned_integral T, std::size_t N>
constexpr Enum<T, N> enum_of(const NamedValue (&names)[N]) {
  Enum<T, N> out{};
  for (std::size_t i = 0; i < N; ++i) out.names[i] = names[i];
  return out;
}
template <std::unsigned_integral T, std::size_t N>
constexpr Enum<T, N> enum_of(const std::array<NamedValue, N>& names) {
  return {names};
}

// flags_of<std::uint16_t>({{0, 1, "auto_focus"}, ...}).
template <std::unsigned_integral T, std::size_t N>
constexpr Flags<T, N> flags_of(const NamedBits (&fields)[N]) {
  Flags<T, N> out{};
  for (std::size_t i = 0; i < N; ++i) out.fields[i] = fields[i];
  return out;
}
// One-bit flags at bits 0, 1, 2, ... in order: bits_of<std::uint8_t>({"parking_brake", "horn"}).
template <std::unsigned_integral T, std::size_t N>
constexpr Flags<T, N> bits_of(const std::string_view (&names)[N]) {
  static_assert(N <= 8 * sizeof(T));
  Flags<T, N> out{};
  for (std::size_t i = 0; i < N; ++i) out.fields[i] = NamedBits{static_cast<std::uint8_t>(i), 1, names[i]};
  return out;
}

}  // namespace jaus::wire
