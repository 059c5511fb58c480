// Random values for the JSS codecs (jaus/jss/codecs.hpp), found by
// argument-dependent lookup from the description walkers of
// tests/core/described_values.hpp, so every JSS body is randomised and
// compared the way the RA bodies are.
#pragma once

#include "described_values.hpp"
#include "jaus/jss/all.hpp"

namespace jaus::jss::codec {

inline void random_value(const Str8&, std::string& v, test::Rng& rng, wire::CodecContext&) {
  v.assign(test::uniform_int<std::size_t>(rng, 0, 40), 'a');
  for (auto& c : v) c = static_cast<char>(test::uniform_int<int>(rng, 32, 126));
}

// A real query (Query Local Pose with a random presence vector) or, half the
// time, random bytes after a random ID: the codec carries either.
template <class SizeT>
void random_value(const Embedded<SizeT>& c, std::vector<std::uint8_t>& v, test::Rng& rng, wire::CodecContext&) {
  if (rng() & 1) {
    msg::QueryLocalPose query;
    query.presence_vector = test::uniform_int<std::uint16_t>(rng, 0, 0x1FF);
    v = encode_contents(query);
    return;
  }
  v.resize(test::uniform_int<std::size_t>(rng, c.min_size, 24));
  for (auto& b : v) b = test::uniform_int<std::uint8_t>(rng, 0, 255);
}

template <std::size_t N>
void random_value(const Tagged<N>& c, TaggedValue& v, test::Rng& rng, wire::CodecContext&) {
  const auto& a = c.alternatives[test::uniform_int<std::size_t>(rng, 0, N - 1)];
  v.tag = a.tag;
  const std::uint64_t max = a.size >= 4 ? 0xFFFFFFFFull : (1ull << (8 * a.size)) - 1;
  v.value = static_cast<std::uint32_t>(test::uniform_int<std::uint64_t>(rng, 0, max));
}

inline void random_value(const IdCodec&, JssId& v, test::Rng& rng, wire::CodecContext&) {
  v = JssId{test::uniform_int<std::uint16_t>(rng, 0, 65535), test::uniform_int<std::uint8_t>(rng, 0, 255),
            test::uniform_int<std::uint8_t>(rng, 0, 255)};
}

}  // namespace jaus::jss::codec

namespace jaus::test {

// Every JSS message, as one list for typed tests.
template <class... Lists>
struct ConcatLists;
template <class... A>
struct ConcatLists<msg::TypeList<A...>> {
  using type = msg::TypeList<A...>;
};
template <class... A, class... B, class... Rest>
struct ConcatLists<msg::TypeList<A...>, msg::TypeList<B...>, Rest...> {
  using type = typename ConcatLists<msg::TypeList<A..., B...>, Rest...>::type;
};
using AllJssMessages =
    ConcatLists<jss::msg::AccessControlMessages, jss::msg::ManagementMessages, jss::msg::TimeMessages,
                jss::msg::LivenessMessages, jss::msg::EventsMessages, jss::msg::DiscoveryMessages,
                jss::msg::SensorDriverMessages, jss::msg::WaypointMessages>::type;

}  // namespace jaus::test
