// The random filler behind random_message.hpp, compiled once for every test
// that uses it.
#include "random_message.hpp"

#include <cmath>
#include <cstdint>
#include <string>
#include <type_traits>

#include "jaus/clearpath/fields.hpp"
#include "jaus/clearpath/packed_date_time.hpp"

namespace jaus::clearpath::testing {

namespace {

class RandomFiller {
 public:
  explicit RandomFiller(std::mt19937& rng) : rng_(rng) {}

  template <class W, class T>
  void operator()(const fields::Number<W, T>& f) { f.value = pick<W, T>(f.scale, f.min, f.max); }
  template <class S, class B>
  void operator()(const fields::LengthPrefixedText<S, B>& f) {
    const std::size_t length = std::uniform_int_distribution<std::size_t>(0, std::min<std::size_t>(f.max_length, 16))(rng_);
    f.value.clear();
    for (std::size_t i = 0; i < length; ++i)
      f.value += static_cast<char>(std::uniform_int_distribution<int>('A', 'z')(rng_));
    if (f.nul_terminated != nullptr) *f.nul_terminated = coin();
  }
  template <class B>
  void operator()(const fields::Flag<B>& f) { f.value = coin(); }
  template <class T>
  void operator()(const fields::PackedDateTime<T>& f) {
    const auto part = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng_); };
    const DateTimeParts p{part(2000, 2127), part(1, 12), part(1, 31), part(0, 23), part(0, 59)};
    f.value = *pack_date_time(p);
  }
  template <class W, class V>
  void operator()(const fields::NumberList<W, V>& f) {
    f.values.resize(std::uniform_int_distribution<std::size_t>(0, 6)(rng_));
    for (auto& v : f.values) v = pick<W, std::remove_cvref_t<decltype(v)>>(f.scale, f.min, f.max);
  }
  template <class V>
  void operator()(const fields::RecordList<V>& f) {
    f.records.resize(std::uniform_int_distribution<std::size_t>(0, 4)(rng_));
    for (auto& r : f.records) std::remove_cvref_t<decltype(r)>::describe(r, *this);
  }
  template <class R>
  void operator()(const fields::Group<R>& f) { std::remove_cvref_t<R>::describe(f.record, *this); }

 private:
  bool coin() { return std::uniform_int_distribution<int>(0, 1)(rng_) == 1; }
  template <class W, class T>
  T pick(double scale, double min, double max) {
    // Draw on the wire grid so the value survives encoding exactly.
    const auto lo = static_cast<std::int64_t>(std::ceil(min * scale - 1e-9));
    const auto hi = static_cast<std::int64_t>(std::floor(max * scale + 1e-9));
    const std::int64_t raw = std::uniform_int_distribution<std::int64_t>(lo, hi)(rng_);
    if constexpr (std::is_floating_point_v<T>) {
      return static_cast<T>(static_cast<double>(raw) / scale);
    } else {
      return static_cast<T>(raw);
    }
  }
  std::mt19937& rng_;
};

}  // namespace

void randomize(AnyMessage& message, std::mt19937& rng) {
  RandomFiller filler(rng);
  clearpath::visit([&](auto& m) { std::remove_cvref_t<decltype(m)>::describe(m, filler); }, message);
}

}  // namespace jaus::clearpath::testing
