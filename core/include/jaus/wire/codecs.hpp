// Field codecs: how one field of a message travels on the wire. A message is
// described once as a list of fields (see describe.hpp), each naming its
// member, its codec and, when optional, its presence-vector bit; the binary
// codec, the JSON form and the tests are all derived from those descriptions.
//
// Every codec has:
//   value_type                                    the member's type (engineering units)
//   encode(const value_type&, ByteWriter&, Context&)
//   decode(ByteReader&, value_type&, Context&)
//   to_json<Json>(const value_type&) / from_json<Json>(const Json&, value_type&) -> Expected<void>
//     (a failure is ErrorCode::json whose detail says why and, for nested values, where)
// JSON members are templates so that this header does not pull in a JSON library.
//
// A codec whose field always takes the same number of bytes, and whose decode
// cannot fail once those bytes are there, also has
//   static constexpr std::size_t fixed_size
// and takes any reader/writer (auto&): a message made only of such fields is
// checked for size once and then encoded or decoded with an UncheckedWriter or
// UncheckedReader (describe.hpp). UncheckedReader has no fail(), so a decode
// that can fail does not compile there.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <concepts>
#include <cstdint>
#include <iterator>
#include <limits>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "jaus/core/address.hpp"
#include "jaus/core/byte_io.hpp"
#include "jaus/base/expected.hpp"
#include "jaus/base/hex.hpp"
#include "jaus/core/scaled_integer.hpp"
#include "jaus/core/time_stamp.hpp"

namespace jaus::wire {

// Which peer's reading of the wire to use. `ra` is what Part 3 specifies and
// what we send; `openjaus` reproduces the quirks of the common open RA 3.3
// implementation (docs/wire-format.md, "Interoperability") so that its messages
// decode to the values it meant; `jss` is SAE JAUS (docs/jss.md, "Scaled
// values"): a body JSS shares with RA is described once, and its JSS reading
// differs only where the description says so (every scaled integer unsigned,
// some ranges its own).
enum class Dialect : std::uint8_t { ra, openjaus, jss };

constexpr std::string_view to_string(Dialect dialect) {
  switch (dialect) {
    case Dialect::ra: return "ra";
    case Dialect::openjaus: return "openjaus";
    case Dialect::jss: return "jss";
  }
  return "?";
}

// State shared by the fields of one message while it is encoded or decoded.
// The dialect is a run-time value: the quirks it selects are a few branches,
// and one instantiation per body instead of one per body and dialect halves
// the codec's compile time and code size.
struct CodecContext {
  Dialect dialect = Dialect::ra;
  std::array<std::uint32_t, 2> dims{};
};

namespace detail {
template <class T>
std::string wire_name() {
  const char* base = std::is_floating_point_v<T> ? (sizeof(T) == 4 ? "float" : "double")
                                                 : (std::is_signed_v<T> ? "i" : "u");
  return std::is_floating_point_v<T> ? std::string(base) : std::string(base) + std::to_string(8 * sizeof(T));
}
inline std::string number_text(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", v);
  return text;
}

// A JSON value its field cannot take: the detail says why.
inline Unexpected<Error> json_error(std::string why) { return unexpected(Error{ErrorCode::json, 0, {}, std::move(why)}); }
// The same error one level up: `where` ("'poses'", "[2]") is put before its detail.
inline Unexpected<Error> json_error_in(const std::string& where, const Error& inner) {
  return json_error(where + ": " + inner.detail);
}

template <class Json, std::integral T>
Expected<void> integer_from_json(const Json& j, T& out) {
  if (!j.is_number_integer()) return json_error("expected an integer");
  if (j.is_number_unsigned()) {
    const auto v = j.template get<std::uint64_t>();
    if (v > static_cast<std::uint64_t>(std::numeric_limits<T>::max())) return json_error("out of range for its wire type");
    out = static_cast<T>(v);
    return {};
  }
  const auto v = j.template get<std::int64_t>();
  if constexpr (std::is_unsigned_v<T>) {
    if (v < 0 || static_cast<std::uint64_t>(v) > static_cast<std::uint64_t>(std::numeric_limits<T>::max()))
      return json_error("out of range for its wire type");
  } else {
    if (v < static_cast<std::int64_t>(std::numeric_limits<T>::min()) ||
        v > static_cast<std::int64_t>(std::numeric_limits<T>::max()))
      return json_error("out of range for its wire type");
  }
  out = static_cast<T>(v);
  return {};
}

template <class Json>
Expected<void> real_from_json(const Json& j, double& out) {
  if (!j.is_number()) return json_error("expected a number");
  out = j.template get<double>();
  return {};
}

inline constexpr char kHexDigits[] = "0123456789ABCDEF";

inline std::string hex_u32(std::uint32_t v) {
  std::string out;
  bool started = false;
  for (int shift = 28; shift >= 0; shift -= 4) {
    const unsigned digit = (v >> shift) & 0xF;
    if (digit != 0 || started || shift == 0) {
      out += kHexDigits[digit];
      started = true;
    }
  }
  return out;
}
}  // namespace detail

// A plain integer (Byte, Short Integer, Unsigned Integer, ... without limits).
template <std::integral T>
struct Int {
  using value_type = T;
  using wire_type = T;
  static constexpr std::size_t fixed_size = sizeof(T);
  std::string doc() const { return detail::wire_name<T>(); }
  JAUS_ALWAYS_INLINE void encode(const T& v, auto& w, auto&) const { w.write(v); }
  JAUS_ALWAYS_INLINE void decode(auto& r, T& v, auto&) const { r.read(v); }
  template <class Json>
  Json to_json(const T& v) const { return Json(v); }
  template <class Json>
  Expected<void> from_json(const Json& j, T& v) const { return detail::integer_from_json(j, v); }
};

// IEEE 754 Float or Double.
template <std::floating_point T>
struct Real {
  using value_type = T;
  static constexpr std::size_t fixed_size = sizeof(T);
  std::string doc() const { return detail::wire_name<T>(); }
  JAUS_ALWAYS_INLINE void encode(const T& v, auto& w, auto&) const { w.write(v); }
  JAUS_ALWAYS_INLINE void decode(auto& r, T& v, auto&) const { r.read(v); }
  template <class Json>
  Json to_json(const T& v) const { return Json(v); }
  template <class Json>
  Expected<void> from_json(const Json& j, T& v) const {
    double d = 0;
    if (auto read = detail::real_from_json(j, d); !read) return read;
    v = static_cast<T>(d);
    return {};
  }
};

// The openjaus quirk for signed manipulator quantities: sent as unsigned with
// bias = lower limit. Marked on the fields it affects.
enum class Quirk : std::uint8_t { none, openjaus_unsigned_bias };

// A scaled integer with limits (docs/wire-format.md); the value is in the
// engineering unit named by the field.
template <std::integral T>
struct Scaled {
  using value_type = double;
  using wire_type = T;
  static constexpr std::size_t fixed_size = sizeof(T);  // also as the quirk's unsigned
  using jss_wire_type = std::make_unsigned_t<T>;
  double lower;
  double upper;
  Quirk quirk = Quirk::none;
  // The JSS limits when they are not RA's (equal: RA's); see jss().
  double jss_lower = 0;
  double jss_upper = 0;

  // The field as JSS has it: unsigned over these limits (a JSS scaled integer
  // is always unsigned, bias = lower limit). Without it, JSS reads the field
  // as unsigned over the RA limits.
  constexpr Scaled jss(double lo, double hi) const {
    Scaled out = *this;
    out.jss_lower = lo;
    out.jss_upper = hi;
    return out;
  }
  // Always inlined: on the walk's constant description they fold to constants.
  JAUS_ALWAYS_INLINE constexpr double jss_lo() const { return jss_lower != jss_upper ? jss_lower : lower; }
  JAUS_ALWAYS_INLINE constexpr double jss_hi() const { return jss_lower != jss_upper ? jss_upper : upper; }
  JAUS_ALWAYS_INLINE constexpr ScaledRange<jss_wire_type> jss_range() const {
    return ScaledRange<jss_wire_type>{jss_lo(), jss_hi()};
  }

  std::string doc(Dialect dialect = Dialect::ra) const {
    if (dialect == Dialect::jss)
      return detail::wire_name<jss_wire_type>() + " scaled [" + detail::number_text(jss_lo()) + ", " +
             detail::number_text(jss_hi()) + "]";
    return detail::wire_name<T>() + " scaled [" + detail::number_text(lower) + ", " + detail::number_text(upper) + "]";
  }

  // Resolution of the encoding: values round-trip within one step.
  constexpr double step() const { return ScaledRange<T>{lower, upper}.scale(); }
  constexpr double jss_step() const { return jss_range().scale(); }

  // The range as the dialect reads it: the openjaus dialect sends quirk fields
  // as unsigned with bias = lower limit, divides 32-bit unsigned ranges into
  // 2^32 - 2 steps and rounds like that implementation.
  template <class W>
  constexpr ScaledRange<W> range_for(const auto& ctx) const {
    const bool peer = ctx.dialect == Dialect::openjaus;
    return ScaledRange<W>{lower, upper, peer, peer};
  }
  bool uses_quirk(const auto& ctx) const {
    if constexpr (std::is_signed_v<T>) {
      return quirk == Quirk::openjaus_unsigned_bias && ctx.dialect == Dialect::openjaus;
    } else {
      return false;
    }
  }
  // The RA walk's context has its dialect as a constant (describe.hpp,
  // RaCodecContext): there the JSS and quirk branches fold away.
  JAUS_ALWAYS_INLINE void encode(const double& v, auto& w, auto& ctx) const {
    if (ctx.dialect == Dialect::jss)
      w.write(jss_range().encode(v));
    else if (uses_quirk(ctx))
      w.write(range_for<std::make_unsigned_t<T>>(ctx).encode(v));
    else
      w.write(range_for<T>(ctx).encode(v));
  }
  JAUS_ALWAYS_INLINE void decode(auto& r, double& v, auto& ctx) const {
    if (ctx.dialect == Dialect::jss) {
      jss_wire_type raw{};
      if (r.read(raw)) v = jss_range().decode(raw);
    } else if (uses_quirk(ctx)) {
      std::make_unsigned_t<T> raw{};
      if (r.read(raw)) v = range_for<std::make_unsigned_t<T>>(ctx).decode(raw);
    } else {
      T raw{};
      if (r.read(raw)) v = range_for<T>(ctx).decode(raw);
    }
  }
  template <class Json>
  Json to_json(const double& v) const { return Json(v); }
  template <class Json>
  Expected<void> from_json(const Json& j, double& v) const { return detail::real_from_json(j, v); }
};

// An integer with a fixed unit factor and no limits (value = raw * factor),
// e.g. milliradians or millimetres carried as Unsigned Short.
template <std::integral T>
struct Linear {
  using value_type = double;
  using wire_type = T;
  static constexpr std::size_t fixed_size = sizeof(T);
  double factor;
  std::string doc() const { return detail::wire_name<T>() + " x " + detail::number_text(factor); }

  constexpr double step() const { return factor; }
  constexpr double lower() const { return static_cast<double>(std::numeric_limits<T>::min()) * factor; }
  constexpr double upper() const { return static_cast<double>(std::numeric_limits<T>::max()) * factor; }
  void encode(const double& v, auto& w, auto&) const {
    double raw = ScaledRange<T>::round_half_away(std::isfinite(v) ? v / factor : 0.0);
    raw = std::clamp(raw, static_cast<double>(std::numeric_limits<T>::min()),
                     static_cast<double>(std::numeric_limits<T>::max()));
    w.write(static_cast<T>(raw));
  }
  void decode(auto& r, double& v, auto&) const {
    T raw{};
    if (r.read(raw)) v = static_cast<double>(raw) * factor;
  }
  template <class Json>
  Json to_json(const double& v) const { return Json(v); }
  template <class Json>
  Expected<void> from_json(const Json& j, double& v) const { return detail::real_from_json(j, v); }
};

// ASCII text in a fixed-length field, NUL padded. With `accept_shorter`, a
// final field may arrive shorter than its length (Report Identification).
template <std::size_t N, bool AcceptShorter = false>
struct Text {
  using value_type = std::string;
  static constexpr std::size_t length = N;
  static constexpr std::size_t fixed_size = AcceptShorter ? 0 : N;  // 0: not fixed
  std::string doc() const {
    return "text, " + std::to_string(N) + " bytes NUL padded" + (AcceptShorter ? " (shorter accepted)" : "");
  }

  void encode(const std::string& v, auto& w, auto&) const {
    if (v.size() > N) {
      w.fail(ErrorCode::string_too_long, std::to_string(v.size()) + " > " + std::to_string(N) + " characters");
      return;
    }
    w.write_bytes({reinterpret_cast<const std::uint8_t*>(v.data()), v.size()});
    w.write_zeros(N - v.size());
  }
  void decode(auto& r, std::string& v, auto&) const {
    std::span<const std::uint8_t> bytes;
    std::size_t n = N;
    if constexpr (AcceptShorter) n = std::min(N, r.remaining());
    if (!r.read_bytes(n, bytes)) return;
    std::size_t len = 0;
    while (len < bytes.size() && bytes[len] != 0) ++len;
    v.assign(reinterpret_cast<const char*>(bytes.data()), len);
  }
  template <class Json>
  Json to_json(const std::string& v) const { return Json(v); }
  template <class Json>
  Expected<void> from_json(const Json& j, std::string& v) const {
    if (!j.is_string()) return detail::json_error("expected a string");
    v = j.template get<std::string>();
    if (v.size() > N) return detail::json_error("longer than " + std::to_string(N) + " characters");
    return {};
  }
};

// Time stamp (u32) as its parts.
struct Time {
  using value_type = TimeStamp;
  static constexpr std::size_t fixed_size = 4;
  std::string doc() const { return "time stamp (u32)"; }
  void encode(const TimeStamp& v, auto& w, auto&) const {
    const auto raw = v.pack();
    if (!raw) {
      w.fail(ErrorCode::bad_value, "time stamp part out of its bit range");
      return;
    }
    w.write(*raw);
  }
  void decode(auto& r, TimeStamp& v, auto&) const {
    std::uint32_t raw = 0;
    if (r.read(raw)) v = TimeStamp::unpack(raw);
  }
  template <class Json>
  Json to_json(const TimeStamp& v) const {
    return Json{{"day", v.day}, {"hour", v.hour}, {"minute", v.minute}, {"second", v.second},
                {"millisecond", v.millisecond}};
  }
  template <class Json>
  Expected<void> from_json(const Json& j, TimeStamp& v) const {
    if (!j.is_object()) return detail::json_error("expected {day, hour, minute, second, millisecond}");
    for (const auto& [key, value] : j.items()) {
      Expected<void> part;
      if (key == "day") part = detail::integer_from_json(value, v.day);
      else if (key == "hour") part = detail::integer_from_json(value, v.hour);
      else if (key == "minute") part = detail::integer_from_json(value, v.minute);
      else if (key == "second") part = detail::integer_from_json(value, v.second);
      else if (key == "millisecond") part = detail::integer_from_json(value, v.millisecond);
      else return detail::json_error("unknown time stamp part '" + key + "'");
      if (!part) return part;
    }
    if (!v.pack()) return detail::json_error("time stamp part out of range");
    return {};
  }
};

// Date stamp (u16) as its parts. The openjaus dialect writes the calendar year
// masked to 7 bits and a 0-based month; it is mapped back here.
struct Date {
  using value_type = DateStamp;
  static constexpr std::size_t fixed_size = 2;
  std::string doc() const { return "date stamp (u16)"; }
  void encode(const DateStamp& v, auto& w, auto& ctx) const {
    DateStamp wire = v;
    if (ctx.dialect == Dialect::openjaus) {
      wire.month = static_cast<std::uint8_t>(v.month == 0 ? 0 : v.month - 1);
      wire.year = static_cast<std::uint16_t>(2000 + (v.year & 0x7F));
    }
    const auto raw = wire.pack();
    if (!raw) {
      w.fail(ErrorCode::bad_value, "date stamp part out of its bit range");
      return;
    }
    w.write(*raw);
  }
  void decode(auto& r, DateStamp& v, auto& ctx) const {
    std::uint16_t raw = 0;
    if (!r.read(raw)) return;
    v = DateStamp::unpack(raw);
    if (ctx.dialect == Dialect::openjaus) {
      v.month = static_cast<std::uint8_t>(v.month + 1);
      // The year in 2000-2127 whose low 7 bits were sent.
      const unsigned low = (v.year - 2000) & 0x7F;
      v.year = static_cast<std::uint16_t>(2000 + ((low + 128 - (2000 & 0x7F)) & 0x7F));
    }
  }
  template <class Json>
  Json to_json(const DateStamp& v) const { return Json{{"year", v.year}, {"month", v.month}, {"day", v.day}}; }
  template <class Json>
  Expected<void> from_json(const Json& j, DateStamp& v) const {
    if (!j.is_object()) return detail::json_error("expected {year, month, day}");
    for (const auto& [key, value] : j.items()) {
      Expected<void> part;
      if (key == "year") part = detail::integer_from_json(value, v.year);
      else if (key == "month") part = detail::integer_from_json(value, v.month);
      else if (key == "day") part = detail::integer_from_json(value, v.day);
      else return detail::json_error("unknown date stamp part '" + key + "'");
      if (!part) return part;
    }
    // Bit ranges are checked when encoding, per dialect: the openjaus dialect
    // reads month 16 from its 0-based 15, which the RA form cannot carry.
    if (v.day > 31 || v.month > 16 || v.year < 2000 || v.year > 2127)
      return detail::json_error("date stamp part out of range (year 2000-2127, month 0-16, day 0-31)");
    return {};
  }
};

// Opaque bytes: either the rest of the payload (SizeT = void) or preceded by
// a size of type SizeT. JSON form: upper-case hex string.
template <class SizeT = void>
struct Bytes {
  using value_type = std::vector<std::uint8_t>;
  std::string doc() const {
    if constexpr (std::is_void_v<SizeT>) return "bytes to the end (hex)";
    else return detail::wire_name<SizeT>() + " size + bytes (hex)";
  }
  void encode(const value_type& v, ByteWriter& w, auto&) const {
    if constexpr (!std::is_void_v<SizeT>) {
      if (v.size() > std::numeric_limits<SizeT>::max()) {
        w.fail(ErrorCode::count_out_of_range, "too many bytes for the size field");
        return;
      }
      w.write(static_cast<SizeT>(v.size()));
    }
    w.write_bytes(v);
  }
  void decode(ByteReader& r, value_type& v, auto&) const {
    std::size_t n = r.remaining();
    if constexpr (!std::is_void_v<SizeT>) {
      SizeT size{};
      if (!r.read(size)) return;
      if (size > r.remaining()) {
        r.fail(ErrorCode::count_out_of_range,
               "size " + std::to_string(size) + " but " + std::to_string(r.remaining()) + " bytes left");
        return;
      }
      n = size;
    }
    std::span<const std::uint8_t> bytes;
    if (r.read_bytes(n, bytes)) v.assign(bytes.begin(), bytes.end());
  }
  template <class Json>
  Json to_json(const value_type& v) const {
    return Json(jaus::to_hex(v));
  }
  template <class Json>
  Expected<void> from_json(const Json& j, value_type& v) const;
};

template <class SizeT>
template <class Json>
Expected<void> Bytes<SizeT>::from_json(const Json& j, value_type& v) const {
  if (!j.is_string()) return detail::json_error("expected a hex string");
  auto bytes = jaus::parse_hex(j.template get<std::string>());
  if (!bytes) return detail::json_error(bytes.error().detail);
  v = std::move(*bytes);
  return {};
}

// An address as four bytes in the order subsystem, node, component, instance
// (the order of discovery and control reports; the header uses the reverse).
struct AddressCodec {
  using value_type = Address;
  static constexpr std::size_t fixed_size = 4;
  std::string doc() const { return "address S.N.C.I (4 x u8)"; }
  void encode(const Address& v, auto& w, auto&) const {
    w.write(v.subsystem);
    w.write(v.node);
    w.write(v.component);
    w.write(v.instance);
  }
  void decode(auto& r, Address& v, auto&) const {
    r.read(v.subsystem);
    r.read(v.node);
    r.read(v.component);
    r.read(v.instance);
  }
  template <class Json>
  Json to_json(const Address& v) const { return Json(v.to_string()); }
  template <class Json>
  Expected<void> from_json(const Json& j, Address& v) const {
    const auto parsed = j.is_string() ? Address::parse(j.template get<std::string>()) : std::nullopt;
    if (!parsed) return detail::json_error("expected an address \"S.N.C.I\"");
    v = *parsed;
    return {};
  }
};

// Event limit of Create/Update Event: a type tag then a value of that type.
struct EventLimit {
  enum Type : std::uint8_t {
    byte = 0, short_integer = 1, integer = 2, long_integer = 3, unsigned_short = 4, unsigned_integer = 5,
    unsigned_long = 6, float32 = 7, float64 = 8, rgb = 9
  };
  std::uint8_t type = byte;
  std::uint64_t bits = 0;  // the value's little-endian bytes, zero-extended

  bool operator==(const EventLimit&) const = default;
  static constexpr std::size_t size_of(std::uint8_t type) {
    constexpr std::size_t sizes[] = {1, 2, 4, 8, 2, 4, 8, 4, 8, 3};
    return type < 10 ? sizes[type] : 0;
  }
  // The type's name in JSON, by its number (the Type enumerators).
  static constexpr std::string_view kTypeNames[] = {
      "byte",          "short_integer", "integer", "long_integer", "unsigned_short", "unsigned_integer",
      "unsigned_long", "float32",       "float64", "rgb"};
};

struct EventLimitCodec {
  using value_type = EventLimit;
  std::string doc() const {
    std::string types;
    for (std::size_t i = 0; i < std::size(EventLimit::kTypeNames); ++i)
      types += (i == 0 ? "" : ", ") + std::to_string(i) + " " + std::string(EventLimit::kTypeNames[i]);
    return "event limit: u8 type (" + types + ") + value";
  }
  void encode(const EventLimit& v, ByteWriter& w, auto&) const {
    const std::size_t n = EventLimit::size_of(v.type);
    if (n == 0) {
      w.fail(ErrorCode::bad_value, "event limit type " + std::to_string(v.type));
      return;
    }
    w.write(v.type);
    std::array<std::uint8_t, 8> raw{};
    jaus::detail::to_little_endian<std::uint64_t>(v.bits, raw.data());
    w.write_bytes(std::span<const std::uint8_t>(raw).first(n));
  }
  void decode(ByteReader& r, EventLimit& v, auto&) const {
    if (!r.read(v.type)) return;
    const std::size_t n = EventLimit::size_of(v.type);
    if (n == 0) {
      r.fail(ErrorCode::bad_value, "event limit type " + std::to_string(v.type));
      return;
    }
    std::span<const std::uint8_t> bytes;
    if (!r.read_bytes(n, bytes)) return;
    std::array<std::uint8_t, 8> raw{};
    std::copy(bytes.begin(), bytes.end(), raw.begin());
    v.bits = jaus::detail::from_little_endian<std::uint64_t>(raw.data());
  }
  // The type by name ("unsigned_short"); read back by name or number.
  template <class Json>
  Json to_json(const EventLimit& v) const {
    if (EventLimit::size_of(v.type) == 0) return Json{{"type", v.type}, {"bits", v.bits}};
    return Json{{"type", std::string(EventLimit::kTypeNames[v.type])}, {"bits", v.bits}};
  }
  template <class Json>
  Expected<void> from_json(const Json& j, EventLimit& v) const {
    if (!j.is_object() || !j.contains("type") || !j.contains("bits")) return detail::json_error("expected {type, bits}");
    const auto& type = j.at("type");
    if (type.is_string()) {
      const auto name = type.template get<std::string>();
      const auto* names = std::begin(EventLimit::kTypeNames);
      const auto* found = std::find(names, std::end(EventLimit::kTypeNames), name);
      if (found == std::end(EventLimit::kTypeNames))
        return detail::json_error("unknown event limit type '" + name +
                                  "' (expected one of: byte, short_integer, integer, long_integer, "
                                  "unsigned_short, unsigned_integer, unsigned_long, float32, float64, rgb, or 0-9)");
      v.type = static_cast<std::uint8_t>(found - names);
    } else if (auto read = detail::integer_from_json(type, v.type); !read) {
      return read;
    }
    if (auto read = detail::integer_from_json(j.at("bits"), v.bits); !read) return read;
    if (EventLimit::size_of(v.type) == 0) return detail::json_error("unknown event limit type");
    return {};
  }
};

// ---- counts of variable-length parts --------------------------------------

// The element count travels right before the elements.
template <std::unsigned_integral T>
struct Prefix {
  using wire_type = T;
  std::uint32_t min = 0;  // e.g. 1 where "0 is reserved"
  std::uint32_t max = std::numeric_limits<T>::max();
};

// The count was sent earlier by a Dimension field (dims[K]) minus `less`.
template <std::size_t K, std::uint32_t Less = 0>
struct FromDim {};

// A count sent once and shared by later arrays (FromDim<K>). Its member holds
// the count; encoding checks every such array against it.
template <std::size_t K, std::unsigned_integral T>
struct Dimension {
  static_assert(K < std::tuple_size_v<decltype(CodecContext::dims)>);
  using value_type = T;
  std::uint32_t min = 0;
  std::string doc() const { return detail::wire_name<T>() + " count (shared)"; }
  void encode(const T& v, ByteWriter& w, auto& ctx) const {
    if (v < min) {
      w.fail(ErrorCode::count_out_of_range, std::to_string(v) + " < " + std::to_string(min));
      return;
    }
    ctx.dims[K] = v;
    w.write(v);
  }
  void decode(ByteReader& r, T& v, auto& ctx) const {
    if (!r.read(v)) return;
    if (v < min) r.fail(ErrorCode::count_out_of_range, std::to_string(v) + " < " + std::to_string(min));
    ctx.dims[K] = v;
  }
  template <class Json>
  Json to_json(const T& v) const { return Json(v); }
  template <class Json>
  Expected<void> from_json(const Json& j, T& v) const { return detail::integer_from_json(j, v); }
};

namespace detail {
template <std::size_t K, std::uint32_t Less>
bool encode_dim_count(const FromDim<K, Less>&, std::size_t n, ByteWriter& w, auto& ctx) {
  const std::size_t expected = ctx.dims[K] >= Less ? ctx.dims[K] - Less : 0;
  if (n != expected) {
    w.fail(ErrorCode::count_mismatch, std::to_string(n) + " elements, count says " + std::to_string(expected));
    return false;
  }
  return true;
}

template <std::size_t K, std::uint32_t Less>
std::size_t decode_dim_count(const FromDim<K, Less>&, const auto& ctx) {
  return ctx.dims[K] >= Less ? ctx.dims[K] - Less : 0;
}
// Writes the count (Prefix) or checks it (FromDim). False on failure.
template <class Count>
bool encode_count(const Count& count, std::size_t n, ByteWriter& w, auto& ctx) {
  if constexpr (requires { typename Count::wire_type; }) {
    if (n < count.min || n > count.max) {
      w.fail(ErrorCode::count_out_of_range, std::to_string(n) + " elements, allowed " + std::to_string(count.min) +
                                                "-" + std::to_string(count.max));
      return false;
    }
    return w.write(static_cast<typename Count::wire_type>(n));
  } else {
    return encode_dim_count(count, n, w, ctx);
  }
}
// Reads or looks up the count; checks that the elements can fit in what is left
// (each at least `min_element_size` bytes) before anything is allocated.
template <class Count>
bool decode_count(const Count& count, std::size_t min_element_size, ByteReader& r, auto& ctx,
                  std::size_t& n) {
  if constexpr (requires { typename Count::wire_type; }) {
    typename Count::wire_type raw{};
    if (!r.read(raw)) return false;
    if (raw < count.min || raw > count.max) {
      r.fail(ErrorCode::count_out_of_range,
             std::to_string(raw) + ", allowed " + std::to_string(count.min) + "-" + std::to_string(count.max));
      return false;
    }
    n = raw;
  } else {
    n = decode_dim_count(count, ctx);
  }
  if (min_element_size > 0 && n > r.remaining() / min_element_size) {
    r.fail(ErrorCode::count_out_of_range, std::to_string(n) + " elements cannot fit in " +
                                              std::to_string(r.remaining()) + " bytes");
    return false;
  }
  return true;
}
}  // namespace detail

}  // namespace jaus::wire
