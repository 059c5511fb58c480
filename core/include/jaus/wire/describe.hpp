// Describing a message once. A body type lists its fields in wire order:
//
//   struct GlobalPose {
//     std::optional<double> latitude_deg;
//     ...
//     static constexpr auto describe() {
//       return std::make_tuple(
//           presence_vector<std::uint16_t>(),
//           optional(0, "latitude_deg", &GlobalPose::latitude_deg, Scaled<std::int32_t>{-90, 90}),
//           ...);
//     }
//   };
//
// From that list this header derives the binary encoder and decoder, the JSON
// form, and the presence vector (computed from which optional members are set,
// never stored twice).
#pragma once

#include <cassert>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

#include "jaus/wire/codecs.hpp"

namespace jaus::wire {

template <class T>
struct is_optional : std::false_type {};
template <class T>
struct is_optional<std::optional<T>> : std::true_type {};

// Dialects as a set, a bit per wire::Dialect: where a field or a presence
// vector is sent. Most are sent in every dialect; a body JSS shares with RA
// names the few that one side alone defines.
struct DialectSet {
  std::uint8_t bits = 0;
  static constexpr DialectSet every() { return {0xFF}; }
  static constexpr DialectSet of(Dialect d) { return {static_cast<std::uint8_t>(1u << static_cast<unsigned>(d))}; }
  constexpr bool has(Dialect d) const { return ((bits >> static_cast<unsigned>(d)) & 1u) != 0; }
  constexpr bool is_every() const { return bits == 0xFF; }
  constexpr bool is_empty() const { return bits == 0; }
  constexpr DialectSet with(Dialect d) const { return {static_cast<std::uint8_t>(bits | of(d).bits)}; }
  constexpr DialectSet without(Dialect d) const { return {static_cast<std::uint8_t>(bits & ~of(d).bits)}; }
};

// How a field is sent in one dialect: not at all, always (a required field, an
// optional one with no presence bit there), or when its presence bit is set.
enum class Presence : std::uint8_t { absent, always, by_bit };

template <class Owner, class Member, class Codec>
struct Field {
  std::string_view name;
  Member Owner::*member;
  Codec codec;
  int bit = -1;  // presence-vector bit of an optional field
  DialectSet dialects = DialectSet::every();  // where the field is sent
  // Where an optional field with a presence bit is sent always, without its
  // bit (the dialect has no presence vector, or defines the field required).
  DialectSet always = {};
  using codec_type = Codec;
  static constexpr bool is_optional = wire::is_optional<Member>::value;

  constexpr Field only_in(Dialect d) const { return with_dialects(DialectSet::of(d)); }
  constexpr Field not_in(Dialect d) const { return with_dialects(dialects.without(d)); }
  constexpr Field always_in(Dialect d) const {
    Field out = *this;
    out.always = always.with(d);
    return out;
  }
  constexpr Presence presence_in(Dialect d) const {
    if (!dialects.has(d)) return Presence::absent;
    if (!is_optional || bit < 0 || always.has(d)) return Presence::always;
    return Presence::by_bit;
  }

 private:
  constexpr Field with_dialects(DialectSet set) const {
    Field out = *this;
    out.dialects = set;
    return out;
  }
};

// The presence vector itself: its value is derived from the optional members.
template <std::unsigned_integral T>
struct PresenceVector {
  using wire_type = T;
  DialectSet dialects = DialectSet::every();  // where it is sent
  constexpr PresenceVector only_in(Dialect d) const { return {DialectSet::of(d)}; }
  constexpr PresenceVector not_in(Dialect d) const { return {dialects.without(d)}; }
};

// Whether field or presence vector `f` is sent alike in every dialect.
template <class F>
constexpr bool same_in_every_dialect(const F& f) {
  if constexpr (requires { f.always; })
    return f.dialects.is_every() && f.always.is_empty();
  else
    return f.dialects.is_every();
}

template <std::unsigned_integral T>
constexpr PresenceVector<T> presence_vector() {
  return {};
}

template <class Owner, class M, class C>
constexpr Field<Owner, M, C> field(std::string_view name, M Owner::*member, C codec) {
  static_assert(std::is_same_v<M, typename C::value_type>, "member type must match the codec");
  return {name, member, codec, -1};
}

template <class Owner, class M, class C>
constexpr Field<Owner, std::optional<M>, C> optional(int bit, std::string_view name, std::optional<M> Owner::*member,
                                                     C codec) {
  static_assert(std::is_same_v<M, typename C::value_type>, "member type must match the codec");
  return {name, member, codec, bit};
}

// A field one peer sends that Part 3 does not define (see docs/messages.md):
// present exactly when encoding/decoding in that dialect.
template <class Owner, class M, class C>
constexpr Field<Owner, std::optional<M>, C> dialect_field(Dialect dialect, std::string_view name,
                                                          std::optional<M> Owner::*member, C codec) {
  static_assert(std::is_same_v<M, typename C::value_type>, "member type must match the codec");
  return Field<Owner, std::optional<M>, C>{name, member, codec, -1}.only_in(dialect);
}

template <class T>
struct is_presence_vector : std::false_type {};
template <class T>
struct is_presence_vector<PresenceVector<T>> : std::true_type {};

// The description as a constant. The walkers below reach each field as
// std::get<I>(kFields<Body>) with I a template argument, so its name, bit,
// dialect and codec limits are compile-time values in the generated code
// whether or not the compiler inlines the walk (passed as function arguments,
// a long description was left to run-time loads, divisions included).
template <class Body>
inline constexpr auto kFields = Body::describe();

template <class Body, class F>
JAUS_ALWAYS_INLINE void for_each_field_index(F&& f) {
  [&]<std::size_t... I>(std::index_sequence<I...>) JAUS_ALWAYS_INLINE_LAMBDA {
    (f(std::integral_constant<std::size_t, I>{}), ...);
  }(std::make_index_sequence<std::tuple_size_v<decltype(kFields<Body>)>>{});
}

// Whether every field (and the presence vector) is sent alike in every
// dialect: the walks then take no dialect into account.
template <class Body>
constexpr bool same_in_every_dialect() {
  return std::apply([](const auto&... f) { return (same_in_every_dialect(f) && ...); }, Body::describe());
}

// Bits the body defines in `dialect`; any other bit of a received presence
// vector is reserved.
template <class Body>
constexpr std::uint32_t optional_mask(Dialect dialect = Dialect::ra) {
  std::uint32_t mask = 0;
  std::apply(
      [&](const auto&... f) {
        (([&] {
           if constexpr (!is_presence_vector<std::decay_t<decltype(f)>>::value)
             if (f.presence_in(dialect) == Presence::by_bit) mask |= 1u << f.bit;
         }()),
         ...);
      },
      Body::describe());
  return mask;
}

// optional_mask() of the dialect a message is read in, a constant per dialect.
template <class Body>
JAUS_ALWAYS_INLINE std::uint32_t defined_bits(Dialect dialect) {
  if constexpr (same_in_every_dialect<Body>()) {
    constexpr std::uint32_t mask = optional_mask<Body>();
    return mask;
  } else {
    constexpr std::uint32_t ra = optional_mask<Body>(Dialect::ra);
    constexpr std::uint32_t openjaus = optional_mask<Body>(Dialect::openjaus);
    constexpr std::uint32_t jss = optional_mask<Body>(Dialect::jss);
    return dialect == Dialect::jss ? jss : dialect == Dialect::openjaus ? openjaus : ra;
  }
}

// Whether the body has a presence vector in some dialect.
template <class Body>
constexpr bool has_presence_vector() {
  return std::apply([](const auto&... f) { return (is_presence_vector<std::decay_t<decltype(f)>>::value || ...); },
                    Body::describe());
}

// Whether a body with a presence vector (which is its first field) sends it in `dialect`.
template <class Body>
JAUS_ALWAYS_INLINE bool presence_vector_sent_in(Dialect dialect) {
  constexpr const auto& pv = std::get<0>(kFields<Body>);
  if constexpr (pv.dialects.is_every())
    return true;
  else
    return pv.dialects.has(dialect);
}

// The presence vector `body` is sent with in `dialect`.
template <class Body>
JAUS_ALWAYS_INLINE std::uint32_t presence_of(const Body& body, Dialect dialect = Dialect::ra) {
  std::uint32_t pv = 0;
  for_each_field_index<Body>([&](auto index) JAUS_ALWAYS_INLINE_LAMBDA {
    constexpr const auto& f = std::get<decltype(index)::value>(kFields<Body>);
    using F = std::decay_t<decltype(f)>;
    if constexpr (!is_presence_vector<F>::value) {
      if constexpr (F::is_optional && f.bit >= 0) {
        const auto present = static_cast<std::uint32_t>((body.*f.member).has_value());
        if constexpr (same_in_every_dialect(f))
          pv |= present << f.bit;
        else if (f.presence_in(dialect) == Presence::by_bit)
          pv |= present << f.bit;
      }
    }
  });
  return pv;
}

// Keeps only the optional fields whose presence bit is in `mask` (a query's
// or service connection's request ANDed with what the responder has).
template <class Body>
void mask_presence(Body& body, std::uint32_t mask) {
  std::apply(
      [&](const auto&... f) {
        (([&] {
           using F = std::decay_t<decltype(f)>;
           if constexpr (!is_presence_vector<F>::value) {
             if constexpr (F::is_optional)
               if (f.bit >= 0 && !((mask >> f.bit) & 1u)) (body.*f.member).reset();
           }
         }()),
         ...);
      },
      Body::describe());
}

// ---- binary ----------------------------------------------------------------

namespace detail {
[[gnu::noinline, gnu::cold]] inline void fail_reserved_bits(ByteReader& r, std::size_t at, std::uint32_t defined,
                                                             std::uint32_t pv) {
  r.fail_at(ErrorCode::reserved_presence_bits, at, "defined bits are 0x" + hex_u32(defined) + ", got 0x" + hex_u32(pv));
}
}  // namespace detail

template <class Body>
void encode_fields(const Body& body, ByteWriter& w, auto& ctx);
template <class Body>
void decode_fields(ByteReader& r, Body& body, auto& ctx);

template <class Codec>
constexpr std::size_t min_wire_size() {
  if constexpr (requires { typename Codec::wire_type; })
    return sizeof(typename Codec::wire_type);
  else
    return 1;
}

// A variable-length list of values of one codec.
template <class Count>
std::string count_doc(const Count&) {
  if constexpr (requires { typename Count::wire_type; })
    return detail::wire_name<typename Count::wire_type>() + " count, then ";
  else
    return "count given earlier, ";
}

// A codec's words in `dialect`: a codec whose wire form differs by dialect
// (wire::Scaled, and the lists that hold one) takes it, the others read alike.
template <class Codec>
std::string codec_doc(const Codec& codec, Dialect dialect) {
  if constexpr (requires { codec.doc(dialect); })
    return codec.doc(dialect);
  else
    return codec.doc();
}

// A codec's JSON form in `dialect`: a codec whose value reads differently by
// dialect (wire::PerDialect) takes it, the others read alike.
template <class Json, class Codec>
Json codec_to_json(const Codec& codec, const typename Codec::value_type& v, Dialect dialect) {
  if constexpr (requires { codec.template to_json<Json>(v, dialect); })
    return codec.template to_json<Json>(v, dialect);
  else
    return codec.template to_json<Json>(v);
}
template <class Json, class Codec>
Expected<void> codec_from_json(const Codec& codec, const Json& j, typename Codec::value_type& v, Dialect dialect) {
  if constexpr (requires { codec.template from_json<Json>(j, v, dialect); })
    return codec.template from_json<Json>(j, v, dialect);
  else
    return codec.template from_json<Json>(j, v);
}

// A field whose wire form differs by dialect beyond scaling: one codec in RA
// (and openjaus), another in JSS, over the same value type. Event's report is
// the one: RA's payload bytes, JSS's whole embedded message, ID first.
template <class RaCodec, class JssCodec>
struct PerDialect {
  static_assert(std::is_same_v<typename RaCodec::value_type, typename JssCodec::value_type>,
                "both dialects' codecs hold the same value type");
  using value_type = typename RaCodec::value_type;
  RaCodec ra{};
  JssCodec jss{};
  std::string doc(Dialect dialect = Dialect::ra) const {
    return dialect == Dialect::jss ? codec_doc(jss, dialect) : codec_doc(ra, dialect);
  }
  void encode(const value_type& v, auto& w, auto& ctx) const {
    if (ctx.dialect == Dialect::jss)
      jss.encode(v, w, ctx);
    else
      ra.encode(v, w, ctx);
  }
  void decode(auto& r, value_type& v, auto& ctx) const {
    if (ctx.dialect == Dialect::jss)
      jss.decode(r, v, ctx);
    else
      ra.decode(r, v, ctx);
  }
  template <class Json>
  Json to_json(const value_type& v, Dialect dialect) const {
    return dialect == Dialect::jss ? codec_to_json<Json>(jss, v, dialect) : codec_to_json<Json>(ra, v, dialect);
  }
  template <class Json>
  Expected<void> from_json(const Json& j, value_type& v, Dialect dialect) const {
    return dialect == Dialect::jss ? codec_from_json(jss, j, v, dialect) : codec_from_json(ra, j, v, dialect);
  }
};

template <class Count, class Elem>
struct Array {
  using value_type = std::vector<typename Elem::value_type>;
  Count count;
  Elem elem;
  std::string doc(Dialect dialect = Dialect::ra) const {
    return count_doc(count) + "each " + codec_doc(elem, dialect);
  }

  void encode(const value_type& v, ByteWriter& w, auto& ctx) const {
    if (!detail::encode_count(count, v.size(), w, ctx)) return;
    for (const auto& e : v) elem.encode(e, w, ctx);
  }
  void decode(ByteReader& r, value_type& v, auto& ctx) const {
    std::size_t n = 0;
    if (!detail::decode_count(count, min_wire_size<Elem>(), r, ctx, n)) return;
    v.resize(n);
    for (auto& e : v) {
      if (r.failed()) return;
      elem.decode(r, e, ctx);
    }
  }
  template <class Json>
  Json to_json(const value_type& v) const {
    Json out = Json::array();
    for (const auto& e : v) out.push_back(elem.template to_json<Json>(e));
    return out;
  }
  template <class Json>
  Expected<void> from_json(const Json& j, value_type& v) const {
    if (!j.is_array()) return detail::json_error("expected an array");
    v.resize(j.size());
    for (std::size_t i = 0; i < j.size(); ++i) {
      if (auto element = elem.template from_json<Json>(j[i], v[i]); !element)
        return detail::json_error_in("[" + std::to_string(i) + "]", element.error());
    }
    return {};
  }
};

// A variable-length list of records, each described like a message body.
template <class Body>
std::string fields_doc(Dialect dialect = Dialect::ra);

template <class Count, class Record>
struct Records {
  using value_type = std::vector<Record>;
  Count count;
  std::string doc(Dialect dialect = Dialect::ra) const {
    return count_doc(count) + "records of: " + fields_doc<Record>(dialect);
  }

  void encode(const value_type& v, ByteWriter& w, auto& ctx) const {
    if (!detail::encode_count(count, v.size(), w, ctx)) return;
    for (const auto& e : v) encode_fields(e, w, ctx);
  }
  void decode(ByteReader& r, value_type& v, auto& ctx) const {
    std::size_t n = 0;
    if (!detail::decode_count(count, 1, r, ctx, n)) return;
    v.resize(n);
    for (auto& e : v) {
      if (r.failed()) return;
      decode_fields(r, e, ctx);
    }
  }
  template <class Json>
  Json to_json(const value_type& v) const;
  template <class Json>
  Expected<void> from_json(const Json& j, value_type& v) const;
};

// A body has a fixed layout when every field's codec has a fixed size: its
// size then follows from the presence vector (and dialect) alone, so it is
// checked once and the fields go through an UncheckedReader/UncheckedWriter.
// Anything else (arrays, records, bytes, counts) walks with the checked
// ByteReader/ByteWriter, which name the field of any error.
template <class Codec>
constexpr std::size_t fixed_size_of() {
  if constexpr (requires { Codec::fixed_size; })
    return Codec::fixed_size;
  else
    return 0;
}

// Bytes a field of type F takes whatever its value (0: variable, or the
// presence vector, which is counted apart). A named helper, not a lambda
// inside a fold expression: clang 14 crashes on that pattern.
template <class F>
constexpr std::size_t fixed_field_size() {
  if constexpr (is_presence_vector<F>::value)
    return 0;
  else
    return fixed_size_of<typename F::codec_type>();
}

template <class Body>
constexpr bool has_fixed_layout() {
  return std::apply(
      [](const auto&... f) {
        return ((is_presence_vector<std::decay_t<decltype(f)>>::value ||
                 fixed_field_size<std::decay_t<decltype(f)>>() > 0) &&
                ...);
      },
      Body::describe());
}

// The size of the fields after the presence vector `pv` of a fixed-layout body.
template <class Body>
JAUS_ALWAYS_INLINE std::size_t fixed_layout_size(std::uint32_t pv, const auto& ctx) {
  std::size_t size = 0;
  for_each_field_index<Body>([&](auto index) JAUS_ALWAYS_INLINE_LAMBDA {
    constexpr const auto& f = std::get<decltype(index)::value>(kFields<Body>);
    using F = std::decay_t<decltype(f)>;
    if constexpr (!is_presence_vector<F>::value) {
      constexpr std::size_t n = fixed_size_of<typename F::codec_type>();
      if constexpr (same_in_every_dialect(f) && !F::is_optional) {
        size += n;
      } else if constexpr (same_in_every_dialect(f)) {
        size += ((pv >> f.bit) & 1u) * n;
      } else {
        constexpr unsigned bit = f.bit < 0 ? 0 : f.bit;  // by_bit only where there is one
        switch (f.presence_in(ctx.dialect)) {
          case Presence::absent: break;
          case Presence::always: size += n; break;
          case Presence::by_bit: size += ((pv >> bit) & 1u) * n; break;
        }
      }
    }
  });
  return size;
}

// Every field present (and every dialect's fields, an upper bound).
template <class Body>
inline constexpr std::size_t kMaxFixedLayoutSize = [] {
  return std::apply([](const auto&... f) { return (std::size_t{0} + ... + fixed_field_size<std::decay_t<decltype(f)>>()); },
                    Body::describe());
}();

// The presence vector, when there is one, is the first field: it is read
// before the others, to know their size.
template <class Body>
constexpr bool presence_vector_first() {
  using Fields = decltype(Body::describe());
  return []<std::size_t... I>(std::index_sequence<I...>) {
    return ((I == 0 || !is_presence_vector<std::tuple_element_t<I, Fields>>::value) && ...);
  }(std::make_index_sequence<std::tuple_size_v<Fields>>{});
}

// The RA dialect as a compile-time value. A fixed-layout body's unchecked walk
// (below) is compiled once more for it: every dialect branch of its fields
// (the quirks, the openjaus-only fields) folds away, and the dialect is not
// reloaded after each byte written (a store through uint8_t* may alias the
// context). Only that walk is doubled; the checked walks, which report errors,
// keep the run-time dialect (issue 50).
struct RaCodecContext {
  static constexpr Dialect dialect = Dialect::ra;
};
inline constexpr RaCodecContext kRaContext{};

// The JSS dialect as a compile-time value, for the bodies JSS shares with RA
// (a body says so: `static constexpr bool kSharedWithJss = true;`). Only
// those get a JSS walk of their own: the JSS round trip of a shared body
// stays as fast as when it was a JSS copy, and no other RA body compiles a
// walk JSS never takes.
struct JssCodecContext {
  static constexpr Dialect dialect = Dialect::jss;
};
inline constexpr JssCodecContext kJssContext{};

template <class Body>
constexpr bool shared_with_jss() {
  if constexpr (requires { Body::kSharedWithJss; })
    return Body::kSharedWithJss;
  else
    return false;
}

// Whether JSS reads the body's bytes as RA does: no signed scaled field, no
// scaled field with limits of its own in JSS, no field or presence vector of
// one dialect only (JSS's own bodies: their RA walk is their JSS walk).
template <class Body>
constexpr bool jss_reads_as_ra() {
  return std::apply(
      [](const auto&... f) {
        return ([&] {
          using F = std::decay_t<decltype(f)>;
          if (!same_in_every_dialect(f)) return false;
          if constexpr (is_presence_vector<F>::value) {
            return true;
          } else {
            if constexpr (requires { f.codec.jss_range(); })
              return std::is_unsigned_v<typename F::codec_type::wire_type> && f.codec.jss_lo() == f.codec.lower &&
                     f.codec.jss_hi() == f.codec.upper;
            else
              return true;
          }
        }() && ...);
      },
      Body::describe());
}

// Runs `walk` with the dialect as a constant where the walk is compiled so
// (RA; JSS for the bodies above), else with the run-time context.
template <class Body, class Walk>
JAUS_ALWAYS_INLINE void walk_in_dialect(auto& ctx, Walk&& walk) {
  if (ctx.dialect == Dialect::ra) [[likely]]
    return walk(kRaContext);
  if constexpr (jss_reads_as_ra<Body>()) {
    if (ctx.dialect == Dialect::jss) return walk(kRaContext);
  } else if constexpr (shared_with_jss<Body>()) {
    if (ctx.dialect == Dialect::jss) return walk(kJssContext);
  }
  walk(ctx);
}

// Writes every field after the presence vector. W is a ByteWriter, or an
// UncheckedWriter with room for fixed_layout_size() bytes.
template <class Body, class W>
JAUS_ALWAYS_INLINE void write_fields(const Body& body, W& w, auto& ctx) {
  for_each_field_index<Body>([&](auto index) JAUS_ALWAYS_INLINE_LAMBDA {
    constexpr const auto& f = std::get<decltype(index)::value>(kFields<Body>);
    using F = std::decay_t<decltype(f)>;
    if constexpr (is_presence_vector<F>::value) {
      // written by encode_fields
    } else if constexpr (same_in_every_dialect(f)) {
      w.set_field(f.name);
      if constexpr (F::is_optional) {
        if ((body.*f.member).has_value()) f.codec.encode(*(body.*f.member), w, ctx);
      } else {
        f.codec.encode(body.*f.member, w, ctx);
      }
    } else {
      const Presence presence = f.presence_in(ctx.dialect);
      if (presence == Presence::absent) return;
      w.set_field(f.name);
      if constexpr (F::is_optional) {
        // Sent always in this dialect: an unset member goes as its zero value.
        if (presence == Presence::always)
          f.codec.encode((body.*f.member).value_or(typename F::codec_type::value_type{}), w, ctx);
        else if ((body.*f.member).has_value())
          f.codec.encode(*(body.*f.member), w, ctx);
      } else {
        f.codec.encode(body.*f.member, w, ctx);
      }
    }
  });
}

// Reads every field after the presence vector `pv`. R is a ByteReader, or an
// UncheckedReader over fixed_layout_size() bytes.
template <class Body, class R>
JAUS_ALWAYS_INLINE void read_fields(R& r, Body& body, std::uint32_t pv, auto& ctx) {
  for_each_field_index<Body>([&](auto index) JAUS_ALWAYS_INLINE_LAMBDA {
    constexpr const auto& f = std::get<decltype(index)::value>(kFields<Body>);
    using F = std::decay_t<decltype(f)>;
    if constexpr (is_presence_vector<F>::value) {
      // read by decode_fields
    } else if constexpr (F::is_optional) {
      auto& member = body.*f.member;
      bool present;
      if constexpr (same_in_every_dialect(f)) {
        present = ((pv >> f.bit) & 1u) != 0;
      } else {
        constexpr unsigned bit = f.bit < 0 ? 0 : f.bit;  // by_bit only where there is one
        const Presence presence = f.presence_in(ctx.dialect);
        present = presence == Presence::always || (presence == Presence::by_bit && ((pv >> bit) & 1u) != 0);
      }
      if (present) {
        r.set_field(f.name);
        if (!member) member.emplace();
        f.codec.decode(r, *member, ctx);
      } else {
        member.reset();
      }
    } else if constexpr (same_in_every_dialect(f)) {
      r.set_field(f.name);
      f.codec.decode(r, body.*f.member, ctx);
    } else if (f.presence_in(ctx.dialect) == Presence::absent) {
      body.*f.member = typename F::codec_type::value_type{};  // not sent in this dialect: its zero value
    } else {
      r.set_field(f.name);
      f.codec.decode(r, body.*f.member, ctx);
    }
  });
}

// Out of line: the checked walk is the fast path's fallback, taken only to
// report an error.
template <class Body>
[[gnu::noinline]] void write_fields_checked(const Body& body, ByteWriter& w, auto& ctx) {
  write_fields(body, w, ctx);
}
template <class Body>
[[gnu::noinline]] void read_fields_checked(ByteReader& r, Body& body, std::uint32_t pv, auto& ctx) {
  read_fields(r, body, pv, ctx);
}

template <class Body>
void encode_fields(const Body& body, ByteWriter& w, auto& ctx) {
  // The presence vector first, from the optional members alone: computed
  // inside the field branches it cost more than the fields themselves.
  static_assert(presence_vector_first<Body>());
  const std::uint32_t pv = presence_of(body, ctx.dialect);
  if constexpr (has_presence_vector<Body>()) {
    using Pv = typename std::decay_t<decltype(std::get<0>(kFields<Body>))>::wire_type;
    if (presence_vector_sent_in<Body>(ctx.dialect)) {
      w.set_field("presence_vector");
      w.write(static_cast<Pv>(pv));
    }
  }
  if constexpr (has_fixed_layout<Body>()) {
    const std::size_t room = w.room();
    // Room for every field (the usual case) spares working out the exact size.
    if (room >= kMaxFixedLayoutSize<Body> || room >= fixed_layout_size<Body>(pv, ctx)) [[likely]] {
      UncheckedWriter fast(w.cursor());
      walk_in_dialect<Body>(ctx, [&](auto& dialect) JAUS_ALWAYS_INLINE_LAMBDA { write_fields(body, fast, dialect); });
      if (!fast.failed()) [[likely]] {
        assert(fast.size() == fixed_layout_size<Body>(pv, ctx));
        w.commit(fast.size());
        return;
      }
    }
    // Too little room, or a codec refused a value (a time stamp part out of
    // range, text too long): the checked walk reports where and in which field.
    write_fields_checked(body, w, ctx);
  } else {
    write_fields(body, w, ctx);
  }
}

template <class Body>
void decode_fields(ByteReader& r, Body& body, auto& ctx) {
  static_assert(presence_vector_first<Body>());
  std::uint32_t pv = 0;
  if constexpr (has_presence_vector<Body>()) {
    using Pv = typename std::decay_t<decltype(std::get<0>(kFields<Body>))>::wire_type;
    if (presence_vector_sent_in<Body>(ctx.dialect)) {
      r.set_field("presence_vector");
      Pv raw{};
      // On failure pv stays 0 and the fields below fail in turn (sticky error).
      if (r.read(raw)) {
        pv = raw;
        const std::uint32_t defined = defined_bits<Body>(ctx.dialect);
        if ((pv & ~defined) != 0) [[unlikely]]
          detail::fail_reserved_bits(r, r.offset() - sizeof(raw), defined, pv);
      }
    }
  }
  if constexpr (has_fixed_layout<Body>()) {
    const std::size_t left = r.remaining();
    if (left >= kMaxFixedLayoutSize<Body> || left >= fixed_layout_size<Body>(pv, ctx)) [[likely]] {
      UncheckedReader fast(r.cursor());
      walk_in_dialect<Body>(ctx, [&](auto& dialect) JAUS_ALWAYS_INLINE_LAMBDA { read_fields(fast, body, pv, dialect); });
      assert(fast.size() == fixed_layout_size<Body>(pv, ctx));
      r.skip(fast.size());
      return;
    }
    // Too few bytes: the checked walk names the field that is cut short.
    read_fields_checked(r, body, pv, ctx);
  } else {
    read_fields(r, body, pv, ctx);
  }
}

// The dialect whose reading of field `f` a document or JSON form in `dialect`
// shows. RA's shows the fields of the openjaus peers' extensions too (said so
// in the document), JSS's only its own; nullopt: the field is not shown.
template <class F>
constexpr std::optional<Dialect> shown_in(const F& f, Dialect dialect) {
  if (f.dialects.has(dialect)) return dialect;
  if (dialect == Dialect::ra && f.dialects.has(Dialect::openjaus)) return Dialect::openjaus;
  return std::nullopt;
}

// One line per message: "name: type; name (bit 0): type; ..." for
// docs/messages.md (RA) and docs/jss-messages.md (JSS), each in its dialect's
// wire types and with the fields and presence bits that dialect sends.
template <class Body>
std::string fields_doc(Dialect dialect) {
  std::string out;
  std::apply(
      [&](const auto&... f) {
        (([&] {
           using F = std::decay_t<decltype(f)>;
           const std::optional<Dialect> shown = shown_in(f, dialect);
           if (!shown) return;
           if (!out.empty()) out += "; ";
           if constexpr (is_presence_vector<F>::value) {
             out += "presence vector (" + detail::wire_name<typename F::wire_type>() + ")";
           } else {
             out += "`" + std::string(f.name) + "`";
             if (f.presence_in(*shown) == Presence::by_bit) out += " (bit " + std::to_string(f.bit) + ")";
             if (*shown != dialect) out += " (" + std::string(to_string(*shown)) + " dialect only)";
             out += ": " + codec_doc(f.codec, dialect);
           }
         }()),
         ...);
      },
      Body::describe());
  return out.empty() ? "(no fields)" : "{" + out + "}";
}

// ---- JSON ------------------------------------------------------------------
// Keys are the field names; an optional field is present in JSON exactly when
// it is present on the wire. The presence vector is not a key: it is derived.
// The form is a dialect's (RA's by default): a field that dialect does not
// send is no key of it (see shown_in).

template <class Json, class Body>
Json fields_to_json(const Body& body, Dialect dialect = Dialect::ra) {
  Json out = Json::object();
  std::apply(
      [&](const auto&... f) {
        (([&] {
           using F = std::decay_t<decltype(f)>;
           if constexpr (!is_presence_vector<F>::value) {
             if (!shown_in(f, dialect)) return;
             if constexpr (F::is_optional) {
               if ((body.*f.member).has_value())
                 out[std::string(f.name)] = codec_to_json<Json>(f.codec, *(body.*f.member), dialect);
             } else {
               out[std::string(f.name)] = codec_to_json<Json>(f.codec, body.*f.member, dialect);
             }
           }
         }()),
         ...);
      },
      Body::describe());
  return out;
}

// Fills `body` from a JSON object in `dialect`'s form. Unknown keys and
// missing required fields are errors (ErrorCode::json); the detail names the
// field.
template <class Json, class Body>
Expected<void> fields_from_json(const Json& j, Body& body, Dialect dialect = Dialect::ra) {
  if (!j.is_object()) return detail::json_error("expected a JSON object");
  std::size_t known = 0;
  Expected<void> result;
  std::apply(
      [&](const auto&... f) {
        (([&] {
           using F = std::decay_t<decltype(f)>;
           if constexpr (!is_presence_vector<F>::value) {
             if (!result) return;
             const std::optional<Dialect> shown = shown_in(f, dialect);
             if (!shown) {  // not a key of this form: left at its zero value, and refused below if given
               if constexpr (F::is_optional)
                 (body.*f.member).reset();
               else
                 body.*f.member = typename F::codec_type::value_type{};
               return;
             }
             const std::string key(f.name);
             const auto it = j.find(key);
             if (it == j.end()) {
               // Required: a required field, and an optional one this dialect
               // always sends (a peer's extension field, with no bit, aside).
               const bool required = !F::is_optional || (f.bit >= 0 && f.presence_in(*shown) == Presence::always);
               if (required) {
                 result = detail::json_error("'" + key + "' is missing");
               } else if constexpr (F::is_optional) {
                 (body.*f.member).reset();
               }
               return;
             }
             ++known;
             Expected<void> field;
             if constexpr (F::is_optional) {
               auto& member = body.*f.member;
               member.emplace();
               field = codec_from_json(f.codec, *it, *member, dialect);
             } else {
               field = codec_from_json(f.codec, *it, body.*f.member, dialect);
             }
             if (!field) result = detail::json_error_in("'" + key + "'", field.error());
           }
         }()),
         ...);
      },
      Body::describe());
  if (result && known != j.size()) {
    for (const auto& item : j.items()) {
      bool is_known = false;
      std::apply([&](const auto&... f) {
        ((is_known = is_known || [&] {
            if constexpr (is_presence_vector<std::decay_t<decltype(f)>>::value) return false;
            else return f.name == item.key() && shown_in(f, dialect).has_value();
          }()), ...);
      }, Body::describe());
      if (!is_known) return detail::json_error("unknown field '" + item.key() + "'");
    }
  }
  return result;
}

template <class Count, class Record>
template <class Json>
Json Records<Count, Record>::to_json(const value_type& v) const {
  Json out = Json::array();
  for (const auto& e : v) out.push_back(fields_to_json<Json>(e));
  return out;
}

template <class Count, class Record>
template <class Json>
Expected<void> Records<Count, Record>::from_json(const Json& j, value_type& v) const {
  if (!j.is_array()) return detail::json_error("expected an array of objects");
  v.resize(j.size());
  for (std::size_t i = 0; i < j.size(); ++i) {
    if (auto record = fields_from_json<Json>(j[i], v[i]); !record)
      return detail::json_error_in("[" + std::to_string(i) + "]", record.error());
  }
  return {};
}

}  // namespace jaus::wire
