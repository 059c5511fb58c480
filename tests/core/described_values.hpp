// Test support derived from the message descriptions: random in-range values
// for any described body, and comparison within one scale step. Like the codec
// itself, nothing here is written per message.
#pragma once

#include <gtest/gtest.h>

#include <random>
#include <string>

#include "jaus/messages/all.hpp"

namespace jaus::test {

using Rng = std::mt19937_64;

template <class Body>
void randomize(Body& body, Rng& rng, wire::CodecContext& ctx, bool all_present = false);

inline double uniform(Rng& rng, double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); }
template <class T>
T uniform_int(Rng& rng, T lo, T hi) {
  return static_cast<T>(std::uniform_int_distribution<std::int64_t>(lo, hi)(rng));
}

// ---- random values, one overload per codec kind ---------------------------
template <class T>
void random_value(const wire::Int<T>&, T& v, Rng& rng, wire::CodecContext&) {
  v = uniform_int<T>(rng, std::numeric_limits<T>::min(), std::numeric_limits<T>::max());
}
// Any value of the wire type: named ones, unnamed ones and bits no name covers.
template <class T, std::size_t N>
void random_value(const wire::Enum<T, N>& c, T& v, Rng& rng, wire::CodecContext&) {
  v = (rng() & 1) ? static_cast<T>(c.names[uniform_int<std::size_t>(rng, 0, N - 1)].value)
                  : uniform_int<T>(rng, 0, std::numeric_limits<T>::max());
}
template <class T, std::size_t N>
void random_value(const wire::Flags<T, N>&, T& v, Rng& rng, wire::CodecContext&) {
  v = uniform_int<T>(rng, 0, std::numeric_limits<T>::max());
}
template <class T>
void random_value(const wire::Real<T>&, T& v, Rng& rng, wire::CodecContext&) {
  v = static_cast<T>(uniform(rng, -1e6, 1e6));
}
template <class T>
void random_value(const wire::Scaled<T>& c, double& v, Rng& rng, wire::CodecContext& ctx) {
  v = ctx.dialect == wire::Dialect::jss ? uniform(rng, c.jss_lo(), c.jss_hi()) : uniform(rng, c.lower, c.upper);
}
template <class T>
void random_value(const wire::Linear<T>& c, double& v, Rng& rng, wire::CodecContext&) {
  v = uniform(rng, c.lower(), c.upper());
}
template <std::size_t N, bool S>
void random_value(const wire::Text<N, S>&, std::string& v, Rng& rng, wire::CodecContext&) {
  v.assign(uniform_int<std::size_t>(rng, S ? 1 : 0, N), 'a');
  for (auto& c : v) c = static_cast<char>(uniform_int<int>(rng, 32, 126));
}
inline void random_value(const wire::Time&, TimeStamp& v, Rng& rng, wire::CodecContext&) {
  v = TimeStamp{uniform_int<std::uint16_t>(rng, 0, 999), uniform_int<std::uint8_t>(rng, 0, 59),
                uniform_int<std::uint8_t>(rng, 0, 59), uniform_int<std::uint8_t>(rng, 0, 23),
                uniform_int<std::uint8_t>(rng, 1, 31)};
}
inline void random_value(const wire::Date&, DateStamp& v, Rng& rng, wire::CodecContext&) {
  v = DateStamp{uniform_int<std::uint8_t>(rng, 1, 31), uniform_int<std::uint8_t>(rng, 1, 12),
                uniform_int<std::uint16_t>(rng, 2000, 2127)};
}
template <class S>
void random_value(const wire::Bytes<S>&, std::vector<std::uint8_t>& v, Rng& rng, wire::CodecContext&) {
  v.resize(uniform_int<std::size_t>(rng, 0, 64));
  for (auto& b : v) b = uniform_int<std::uint8_t>(rng, 0, 255);
}
// The codec of the dialect being tested (JSS's, where the JSS tests' values
// for it are visible: tests/jss/codec/jss_values.hpp).
template <class Ra, class Jss>
void random_value(const wire::PerDialect<Ra, Jss>& c, typename Ra::value_type& v, Rng& rng, wire::CodecContext& ctx) {
  if constexpr (requires { random_value(c.jss, v, rng, ctx); }) {
    if (ctx.dialect == wire::Dialect::jss) return random_value(c.jss, v, rng, ctx);
  }
  random_value(c.ra, v, rng, ctx);
}
inline void random_value(const wire::AddressCodec&, Address& v, Rng& rng, wire::CodecContext&) {
  v = Address{uniform_int<std::uint8_t>(rng, 1, 255), uniform_int<std::uint8_t>(rng, 1, 255),
              uniform_int<std::uint8_t>(rng, 1, 255), uniform_int<std::uint8_t>(rng, 1, 255)};
}
inline void random_value(const wire::EventLimitCodec&, wire::EventLimit& v, Rng& rng, wire::CodecContext&) {
  v.type = uniform_int<std::uint8_t>(rng, 0, 9);
  const auto bits = 8 * wire::EventLimit::size_of(v.type);
  v.bits = rng() & (bits == 64 ? ~0ull : ((1ull << bits) - 1));
}
template <std::size_t K, class T>
void random_value(const wire::Dimension<K, T>& c, T& v, Rng& rng, wire::CodecContext& ctx) {
  v = uniform_int<T>(rng, static_cast<T>(std::max<std::uint32_t>(c.min, 1)), 4);
  ctx.dims[K] = v;
}

template <class Count>
std::size_t random_count(const Count& count, Rng& rng, const wire::CodecContext& ctx) {
  if constexpr (requires { typename Count::wire_type; })
    return uniform_int<std::size_t>(rng, count.min, std::min<std::uint32_t>(count.max, 5));
  else
    return wire::detail::decode_dim_count(count, ctx);
}
template <class Count, class Elem>
void random_value(const wire::Array<Count, Elem>& c, typename wire::Array<Count, Elem>::value_type& v, Rng& rng,
                  wire::CodecContext& ctx) {
  v.resize(random_count(c.count, rng, ctx));
  for (auto& e : v) random_value(c.elem, e, rng, ctx);
}
template <class Count, class Record>
void random_value(const wire::Records<Count, Record>& c, std::vector<Record>& v, Rng& rng, wire::CodecContext& ctx) {
  v.resize(random_count(c.count, rng, ctx));
  for (auto& e : v) randomize(e, rng, ctx);
}

template <class Body>
void randomize(Body& body, Rng& rng, wire::CodecContext& ctx, bool all_present) {
  std::apply(
      [&](const auto&... f) {
        (([&] {
           using F = std::decay_t<decltype(f)>;
           if constexpr (!wire::is_presence_vector<F>::value) {
             if constexpr (F::is_optional) {
               auto& member = body.*f.member;
               // A field the dialect always sends is always there, one it does not send never.
               const wire::Presence presence = f.presence_in(ctx.dialect);
               const bool present = presence == wire::Presence::always ||
                                    (presence == wire::Presence::by_bit && (all_present || (rng() & 1)));
               if (present) {
                 member.emplace();
                 random_value(f.codec, *member, rng, ctx);
               } else {
                 member.reset();
               }
             } else if (f.presence_in(ctx.dialect) == wire::Presence::absent) {
               body.*f.member = typename F::codec_type::value_type{};  // what a decode in this dialect gives
             } else {
               random_value(f.codec, body.*f.member, rng, ctx);
             }
           }
         }()),
         ...);
      },
      Body::describe());
}

// ---- comparison within a number of scale steps ----------------------------
// Our own encoding is within half a step; the openjaus dialect's rounding
// (int)(x + 0.5) is up to one step high for negative values, so comparisons
// in that dialect allow 1.5 steps.
inline double& step_tolerance() {
  static double steps = 1.0;
  return steps;
}
struct StepTolerance {
  explicit StepTolerance(double steps) : saved(step_tolerance()) { step_tolerance() = steps; }
  ~StepTolerance() { step_tolerance() = saved; }
  double saved;
};

// `dialect`: whose steps (a scaled field's JSS step is its own).
template <class Codec, class V>
void expect_close(const Codec&, const V& a, const V& b, const std::string& where, wire::Dialect) {
  EXPECT_EQ(a, b) << where;
}
template <class T>
void expect_close(const wire::Scaled<T>& c, const double& a, const double& b, const std::string& where,
                  wire::Dialect dialect) {
  // The openjaus quirk uses the unsigned step, never larger than the signed one.
  const double step = dialect == wire::Dialect::jss ? c.jss_step() : c.step();
  EXPECT_NEAR(a, b, step * step_tolerance() * 1.001) << where;
}
template <class T>
void expect_close(const wire::Linear<T>& c, const double& a, const double& b, const std::string& where,
                  wire::Dialect) {
  EXPECT_NEAR(a, b, c.step() * step_tolerance() * 1.001) << where;
}
template <class T>
void expect_close(const wire::Real<T>&, const T& a, const T& b, const std::string& where, wire::Dialect) {
  EXPECT_EQ(a, b) << where;
}
template <class Body>
void expect_close_body(const Body& a, const Body& b, const std::string& where,
                       wire::Dialect dialect = wire::Dialect::ra);
template <class Count, class Elem>
void expect_close(const wire::Array<Count, Elem>& c, const typename wire::Array<Count, Elem>::value_type& a,
                  const typename wire::Array<Count, Elem>::value_type& b, const std::string& where,
                  wire::Dialect dialect) {
  ASSERT_EQ(a.size(), b.size()) << where;
  for (std::size_t i = 0; i < a.size(); ++i)
    expect_close(c.elem, a[i], b[i], where + "[" + std::to_string(i) + "]", dialect);
}
template <class Count, class Record>
void expect_close(const wire::Records<Count, Record>&, const std::vector<Record>& a, const std::vector<Record>& b,
                  const std::string& where, wire::Dialect dialect) {
  ASSERT_EQ(a.size(), b.size()) << where;
  for (std::size_t i = 0; i < a.size(); ++i)
    expect_close_body(a[i], b[i], where + "[" + std::to_string(i) + "]", dialect);
}

template <class Body>
void expect_close_body(const Body& a, const Body& b, const std::string& where, wire::Dialect dialect) {
  std::apply(
      [&](const auto&... f) {
        (([&] {
           using F = std::decay_t<decltype(f)>;
           if constexpr (!wire::is_presence_vector<F>::value) {
             const std::string name = where + "." + std::string(f.name);
             if constexpr (F::is_optional) {
               const auto& x = a.*f.member;
               const auto& y = b.*f.member;
               ASSERT_EQ(x.has_value(), y.has_value()) << name;
               if (x) expect_close(f.codec, *x, *y, name, dialect);
             } else {
               expect_close(f.codec, a.*f.member, b.*f.member, name, dialect);
             }
           }
         }()),
         ...);
      },
      Body::describe());
}

}  // namespace jaus::test
