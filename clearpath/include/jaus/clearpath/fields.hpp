// The vocabulary a Clearpath message uses to describe its payload once.
//
// Every message struct has
//   template <class Self, class Visitor> static void describe(Self& self, Visitor& v);
// which calls v(...) with one descriptor per wire field, in wire order. The
// encoder, decoder, JSON conversion, range check and test generators are all
// visitors over that one description, so no message has hand-written codecs.
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <numbers>
#include <span>
#include <string_view>
#include <type_traits>

namespace jaus::clearpath::fields {

// A value of an enumerated integer field and its name (JSON shows the name).
// Signed: the gear is a signed byte with -1 = park.
struct NamedValue {
  std::int32_t value;
  std::string_view name;
};

// A number on the wire as the integer Wire; in memory as T (double for scaled
// quantities in engineering units, an integer type otherwise). raw = value * scale.
// An integer field may name some of its values (`names`, from enumerated()):
// only its JSON changes (the name when the value has one, else the number;
// either is read back); the binary visitors ignore the names.
template <class Wire, class T>
struct Number {
  std::string_view name;
  T& value;
  double scale;
  double min;  // documented range, engineering units
  double max;
  std::string_view unit;
  std::span<const NamedValue> names{};
};

// A date and time to the minute packed in a u32 (0x8003's firmware write
// time): minute bits 0-5, hour 6-10, day 11-16, month 17-20, year - 2000
// 21-27 (packed_date_time.hpp). In memory the raw u32; JSON "YYYY-MM-DDTHH:MM"
// when the parts are valid, else the number.
template <class T>
struct PackedDateTime {
  std::string_view name;
  T& value;  // std::uint32_t (const when encoding)
};

// A length-prefixed ASCII string (one length byte, no terminator). Some
// clients append and count a NUL; *nul_terminated records that so the frame
// can be reproduced byte for byte (null if the field does not allow it).
template <class S, class B>
struct LengthPrefixedText {
  std::string_view name;
  S& value;
  std::size_t max_length;
  B* nul_terminated;
};

// A value that is not on the wire but shapes the layout (JSON only).
template <class B>
struct Flag {
  std::string_view name;
  B& value;
};

// A one-byte count followed by that many numbers.
template <class Wire, class V>
struct NumberList {
  std::string_view name;
  V& values;  // std::vector<double or integer>
  double scale;
  double min;
  double max;
  std::string_view unit;
};

enum class Count {
  prefixed,  // a one-byte element count precedes the elements
  implied,   // no count: the elements fill the rest of the payload
};
enum class Layout {
  rows,     // record after record
  columns,  // first field of every record, then the second field of every record...
};

// A list of records, each record itself described with describe().
template <class V>
struct RecordList {
  std::string_view name;
  V& records;  // std::vector<Record>
  Count count;
  Layout layout;
};

// A record embedded in place (JSON: a nested object).
template <class R>
struct Group {
  std::string_view name;
  R& record;
};

// ---- helpers that deduce the descriptor types ------------------------------

template <class Wire, class T>
constexpr Number<Wire, T> scaled(std::string_view name, T& value, double scale, double min, double max,
                                 std::string_view unit) {
  return {name, value, scale, min, max, unit};
}

template <class Wire, class T>
constexpr Number<Wire, T> integer(std::string_view name, T& value,
                                  double min = static_cast<double>(std::numeric_limits<Wire>::min()),
                                  double max = static_cast<double>(std::numeric_limits<Wire>::max())) {
  return {name, value, 1.0, min, max, ""};
}

// An integer whose listed values have names: enumerated<std::int8_t>("gear", s.gear, kGearNames).
template <class Wire, class T>
constexpr Number<Wire, T> enumerated(std::string_view name, T& value, std::span<const NamedValue> names) {
  return {name,
          value,
          1.0,
          static_cast<double>(std::numeric_limits<Wire>::min()),
          static_cast<double>(std::numeric_limits<Wire>::max()),
          "",
          names};
}

template <class T>
constexpr PackedDateTime<T> packed_date_time(std::string_view name, T& value) {
  static_assert(std::is_same_v<std::remove_const_t<T>, std::uint32_t>, "a packed date-time is a u32");
  return {name, value};
}

template <class S>
constexpr LengthPrefixedText<S, std::conditional_t<std::is_const_v<S>, const bool, bool>> text(std::string_view name, S& value,
                                                                                  std::size_t max_length) {
  return {name, value, max_length, nullptr};
}

template <class S, class B>
constexpr LengthPrefixedText<S, B> text(std::string_view name, S& value, std::size_t max_length, B& nul_terminated) {
  return {name, value, max_length, &nul_terminated};
}

template <class B>
constexpr Flag<B> flag(std::string_view name, B& value) {
  return {name, value};
}

template <class Wire, class V>
constexpr NumberList<Wire, V> scaled_list(std::string_view name, V& values, double scale, double min, double max,
                                          std::string_view unit) {
  return {name, values, scale, min, max, unit};
}

template <class Wire, class V>
constexpr NumberList<Wire, V> integer_list(std::string_view name, V& values,
                                           double min = static_cast<double>(std::numeric_limits<Wire>::min()),
                                           double max = static_cast<double>(std::numeric_limits<Wire>::max())) {
  return {name, values, 1.0, min, max, ""};
}

template <class V>
constexpr RecordList<V> records(std::string_view name, V& values, Count count, Layout layout) {
  return {name, values, count, layout};
}

template <class R>
constexpr Group<R> group(std::string_view name, R& record) {
  return {name, record};
}

// The gear of 0x0212 Change Gear and 0x8212 Gear Setpoint Data: 0 neutral,
// -1 park; forward (> 0) and reverse (< -1) gears are numbers.
inline constexpr NamedValue kGearNames[] = {{-1, "park"}, {0, "neutral"}};

// Ranges the document writes with pi.
inline constexpr double kPi = std::numbers::pi;

}  // namespace jaus::clearpath::fields
