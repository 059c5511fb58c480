// A described JAUS message body as a Lua table for the dissector
// (wireshark_plugin.hpp): one entry per field, in wire order, with what the
// dissector's fixed part (lua/jaus.lua) needs to read it (kind, size,
// signedness, limits, presence bit, dialect, counts, nested records, value
// and bit names).
//
// Walks the same descriptions (jaus/wire/describe.hpp) the codec is built
// from, at compile time: a codec kind this file does not know fails to
// compile, so the dissector cannot fall behind the codec silently.
#pragma once

#include <cstdint>
#include <cstdio>
#include <span>
#include <string>
#include <string_view>
#include <tuple>
#include <type_traits>

#include "jaus/jss/codecs.hpp"
#include "jaus/wire/describe.hpp"
#include "lua_text.hpp"

namespace jaus::wireshark::jaus_table {

namespace detail {

template <class T>
inline constexpr bool kAlwaysFalse = false;

template <class C>
struct IsInt : std::false_type {};
template <std::integral T>
struct IsInt<wire::Int<T>> : std::true_type {};
template <class C>
struct IsReal : std::false_type {};
template <std::floating_point T>
struct IsReal<wire::Real<T>> : std::true_type {};
template <class C>
struct IsScaled : std::false_type {};
template <std::integral T>
struct IsScaled<wire::Scaled<T>> : std::true_type {};
template <class C>
struct IsLinear : std::false_type {};
template <std::integral T>
struct IsLinear<wire::Linear<T>> : std::true_type {};
template <class C>
struct IsText : std::false_type {};
template <std::size_t N, bool S>
struct IsText<wire::Text<N, S>> : std::true_type {
  static constexpr std::size_t length = N;
  static constexpr bool shorter = S;
};
template <class C>
struct IsBytes : std::false_type {};
template <class S>
struct IsBytes<wire::Bytes<S>> : std::true_type {
  static constexpr std::size_t size_bytes =
      std::is_void_v<S> ? 0 : sizeof(std::conditional_t<std::is_void_v<S>, char, S>);
};
template <class C>
struct IsDimension : std::false_type {};
template <std::size_t K, std::unsigned_integral T>
struct IsDimension<wire::Dimension<K, T>> : std::true_type {
  static constexpr std::size_t index = K;
  using type = T;
};
template <class C>
struct IsArray : std::false_type {};
template <class Count, class Elem>
struct IsArray<wire::Array<Count, Elem>> : std::true_type {};
template <class C>
struct IsRecords : std::false_type {};
template <class Count, class Record>
struct IsRecords<wire::Records<Count, Record>> : std::true_type {
  using record = Record;
};
template <class C>
struct IsPerDialect : std::false_type {};
template <class Ra, class Jss>
struct IsPerDialect<wire::PerDialect<Ra, Jss>> : std::true_type {};
template <class C>
struct IsEmbedded : std::false_type {};
template <class S>
struct IsEmbedded<jss::codec::Embedded<S>> : std::true_type {
  static constexpr std::size_t size_bytes = sizeof(S);
};
template <class C>
struct IsTagged : std::false_type {};
template <std::size_t N>
struct IsTagged<jss::codec::Tagged<N>> : std::true_type {};
template <class C>
struct IsFromDim : std::false_type {};
template <std::size_t K, std::uint32_t Less>
struct IsFromDim<wire::FromDim<K, Less>> : std::true_type {
  static constexpr std::size_t index = K;
  static constexpr std::uint32_t less = Less;
};

template <class T>
std::string int_params(std::string_view kind) {
  return "k=\"" + std::string(kind) + "\",s=" + std::to_string(sizeof(T)) + (std::is_signed_v<T> ? ",signed=true" : "");
}

// The integer an enumeration or bit-field codec carries on the wire.
template <class Codec>
auto wire_integer_of() {
  if constexpr (requires { typename Codec::wire_type; }) {
    return typename Codec::wire_type{};
  } else if constexpr (std::is_enum_v<typename Codec::value_type>) {
    return std::underlying_type_t<typename Codec::value_type>{};
  } else {
    return typename Codec::value_type{};
  }
}

inline std::string value_names(auto names) {
  std::string out = "{";
  for (const auto& n : names) out += "[" + std::to_string(n.value) + "]=" + lua_string(n.name) + ",";
  return out + "}";
}

template <class Count>
std::string count_lua(const Count& count) {
  if constexpr (requires { typename Count::wire_type; }) {
    using T = typename Count::wire_type;
    return "{s=" + std::to_string(sizeof(T)) + ",min=" + std::to_string(count.min) +
           ",max=" + std::to_string(count.max) + "}";
  } else if constexpr (IsFromDim<Count>::value) {
    return "{dim=" + std::to_string(IsFromDim<Count>::index) + ",less=" + std::to_string(IsFromDim<Count>::less) + "}";
  } else {
    static_assert(kAlwaysFalse<Count>, "jaus_table.hpp: a count kind the dissector does not know");
    return {};
  }
}

}  // namespace detail

template <class Body>
std::string body_lua(wire::Dialect dialect = wire::Dialect::ra);

// One codec's parameters as Lua table entries (no braces, no name), as
// `dialect` puts it on the wire (a scaled field is unsigned in JSS).
template <class Codec>
std::string codec_lua(const Codec& codec, wire::Dialect dialect = wire::Dialect::ra) {
  using namespace detail;
  // Named values and bits first: they are integers on the wire too.
  if constexpr (requires { codec.enum_names(); }) {
    using T = decltype(wire_integer_of<Codec>());
    return int_params<T>("int") + ",vs=" + value_names(codec.enum_names());
  } else if constexpr (requires { codec.flag_fields(); }) {
    using T = decltype(wire_integer_of<Codec>());
    std::string out = int_params<T>("flags") + ",bits={";
    for (const auto& b : codec.flag_fields()) {
      out += "{first=" + std::to_string(b.first_bit) + ",width=" + std::to_string(b.width) + ",n=" + lua_string(b.name);
      if constexpr (requires { b.values; }) {
        if (!b.values.empty()) out += ",vs=" + value_names(b.values);
      }
      out += "},";
    }
    return out + "}";
  } else if constexpr (IsInt<Codec>::value) {
    return int_params<typename Codec::value_type>("int");
  } else if constexpr (IsReal<Codec>::value) {
    return "k=\"real\",s=" + std::to_string(sizeof(typename Codec::value_type));
  } else if constexpr (IsScaled<Codec>::value) {
    if (dialect == wire::Dialect::jss)
      return int_params<typename Codec::jss_wire_type>("scaled") + ",lo=" + lua_number(codec.jss_lo()) +
             ",hi=" + lua_number(codec.jss_hi());
    return int_params<typename Codec::wire_type>("scaled") + ",lo=" + lua_number(codec.lower) +
           ",hi=" + lua_number(codec.upper) + (codec.quirk == wire::Quirk::openjaus_unsigned_bias ? ",quirk=true" : "");
  } else if constexpr (IsLinear<Codec>::value) {
    return int_params<typename Codec::wire_type>("linear") + ",factor=" + lua_number(codec.factor);
  } else if constexpr (IsText<Codec>::value) {
    return "k=\"text\",len=" + std::to_string(IsText<Codec>::length) + (IsText<Codec>::shorter ? ",shorter=true" : "");
  } else if constexpr (std::is_same_v<Codec, wire::Time>) {
    return "k=\"time\",s=4";
  } else if constexpr (std::is_same_v<Codec, wire::Date>) {
    return "k=\"date\",s=2";
  } else if constexpr (IsBytes<Codec>::value) {
    return "k=\"bytes\",size=" + std::to_string(IsBytes<Codec>::size_bytes);
  } else if constexpr (std::is_same_v<Codec, wire::AddressCodec>) {
    return "k=\"address\",s=4";
  } else if constexpr (std::is_same_v<Codec, wire::EventLimitCodec>) {
    return "k=\"limit\"";
  } else if constexpr (std::is_same_v<Codec, jss::codec::Str8>) {
    return "k=\"str8\"";
  } else if constexpr (std::is_same_v<Codec, jss::codec::IdCodec>) {
    return "k=\"jssid\",s=4";
  } else if constexpr (IsPerDialect<Codec>::value) {
    return dialect == wire::Dialect::jss ? codec_lua(codec.jss, dialect) : codec_lua(codec.ra, dialect);
  } else if constexpr (IsEmbedded<Codec>::value) {
    return "k=\"embedded\",size=" + std::to_string(IsEmbedded<Codec>::size_bytes) + ",min=" +
           std::to_string(codec.min_size);
  } else if constexpr (IsTagged<Codec>::value) {
    std::string out = "k=\"tagged\",alts={";
    for (const auto& a : codec.tag_alternatives())
      out += "[" + std::to_string(a.tag) + "]={n=" + lua_string(a.name) + ",s=" + std::to_string(a.size) + "},";
    return out + "}";
  } else if constexpr (IsDimension<Codec>::value) {
    using T = typename IsDimension<Codec>::type;
    return int_params<T>("dim") + ",dim=" + std::to_string(IsDimension<Codec>::index) +
           ",min=" + std::to_string(codec.min);
  } else if constexpr (IsArray<Codec>::value) {
    return "k=\"array\",count=" + count_lua(codec.count) + ",elem={" + codec_lua(codec.elem, dialect) + "}";
  } else if constexpr (IsRecords<Codec>::value) {
    return "k=\"records\",count=" + count_lua(codec.count) +
           ",body=" + body_lua<typename IsRecords<Codec>::record>(dialect);
  } else {
    static_assert(kAlwaysFalse<Codec>,
                  "jaus_table.hpp: a codec kind the dissector does not know; add its case here and in "
                  "lua/jaus.lua");
    return {};
  }
}

// The body's fields in wire order: {{n="latitude_deg",bit=0,k="scaled",...}, ...}.
template <class Body>
std::string body_lua(wire::Dialect dialect) {
  std::string out = "{";
  std::apply(
      [&](const auto&... f) {
        (([&] {
           using F = std::decay_t<decltype(f)>;
           // The fields and bits this dialect sends (an openjaus extension in RA's table, marked).
           const std::optional<wire::Dialect> shown = wire::shown_in(f, dialect);
           if (!shown) return;
           if constexpr (wire::is_presence_vector<F>::value) {
             out += "{k=\"pv\",s=" + std::to_string(sizeof(typename F::wire_type)) + "},";
           } else {
             out += "{n=" + lua_string(f.name);
             if (f.presence_in(*shown) == wire::Presence::by_bit) out += ",bit=" + std::to_string(f.bit);
             if (*shown != dialect) out += ",only=" + lua_string(wire::to_string(*shown));
             out += "," + codec_lua(f.codec, dialect) + "},";
           }
         }()),
         ...);
      },
      Body::describe());
  return out + "}";
}

// A message's entry of the dissector's table: [0x4402]={name="Report Global Pose",body={...}}.
template <class M>
std::string message_lua(wire::Dialect dialect = wire::Dialect::ra) {
  char code[8];
  std::snprintf(code, sizeof code, "0x%04X", static_cast<unsigned>(M::code));
  return std::string("[") + code + "]={name=" + lua_string(M::name) +
         ",body=" + body_lua<typename M::body_type>(dialect) + "},\n";
}

}  // namespace jaus::wireshark::jaus_table
