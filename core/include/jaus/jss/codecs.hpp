// Field codecs that JSS messages need and the RA set does not (docs/jss.md,
// "The bytes on the wire"): u8-length strings (str8), embedded JSS messages with their byte
// count (msg32: the count includes the embedded message's 2-byte ID), u8-tag
// variants of integers (Query Events), and the 4-byte JSS ID of Report Control
// and Report Subsystem List (u16 subsystem, node, component). They plug into
// the description machinery of jaus/wire/describe.hpp like the RA codecs:
// binary, JSON, doc text and the Wireshark table come from one description.
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "jaus/jss/jss_id.hpp"
#include "jaus/wire/codecs.hpp"

namespace jaus::jss::codec {

// Text with a u8 length in front, no terminator (JSIDL variable_length_string).
struct Str8 {
  using value_type = std::string;
  std::string doc() const { return "u8 length + text"; }
  void encode(const std::string& v, ByteWriter& w, auto&) const {
    if (v.size() > 255) {
      w.fail(ErrorCode::string_too_long, std::to_string(v.size()) + " > 255 characters");
      return;
    }
    w.write(static_cast<std::uint8_t>(v.size()));
    w.write_bytes({reinterpret_cast<const std::uint8_t*>(v.data()), v.size()});
  }
  void decode(ByteReader& r, std::string& v, auto&) const {
    std::uint8_t n = 0;
    if (!r.read(n)) return;
    std::span<const std::uint8_t> bytes;
    if (r.read_bytes(n, bytes)) v.assign(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  }
  template <class Json>
  Json to_json(const std::string& v) const { return Json(v); }
  template <class Json>
  Expected<void> from_json(const Json& j, std::string& v) const {
    if (!j.is_string()) return wire::detail::json_error("expected a string");
    v = j.template get<std::string>();
    if (v.size() > 255) return wire::detail::json_error("longer than 255 characters");
    return {};
  }
};

// The JSON form of an embedded message, by the JSS catalogue (catalogue.cpp):
// {"id": "0x2403", "name": "Query Local Pose", "fields": {...}} when the bytes
// are a known message that re-encodes to the same bytes, else {"hex": "..."}.
// Declared here, defined for nlohmann::ordered_json in the catalogue, so that
// this header does not pull in a JSON library.
template <class Json>
Json embedded_message_to_json(std::span<const std::uint8_t> contents);
template <class Json>
Expected<void> embedded_message_from_json(const Json& j, std::vector<std::uint8_t>& contents);

// A complete JSS message (u16 ID + body) inside another, after a byte count of
// type SizeT that includes the ID (msg32 of Create Event, Event, Report
// Events; u16 element data of the list manager). The value is the embedded
// contents, ID first: decode them with jss::decode_contents<M>.
template <std::unsigned_integral SizeT>
struct Embedded {
  using value_type = std::vector<std::uint8_t>;
  using size_type = SizeT;
  std::uint32_t min_size = 2;  // the message ID; 0 where the bytes may be user data (element data)
  std::string doc() const {
    return wire::detail::wire_name<SizeT>() + " byte count + embedded JSS message (ID included)";
  }
  void encode(const value_type& v, ByteWriter& w, auto&) const {
    if (v.size() < min_size || v.size() > std::numeric_limits<SizeT>::max()) {
      w.fail(ErrorCode::count_out_of_range, std::to_string(v.size()) + " bytes; allowed " + std::to_string(min_size) +
                                                "-" + std::to_string(std::numeric_limits<SizeT>::max()));
      return;
    }
    w.write(static_cast<SizeT>(v.size()));
    w.write_bytes(v);
  }
  void decode(ByteReader& r, value_type& v, auto&) const {
    SizeT size{};
    if (!r.read(size)) return;
    if (size < min_size) {
      r.fail_at(ErrorCode::count_out_of_range, r.offset() - sizeof(SizeT),
                "byte count " + std::to_string(size) + " is below " + std::to_string(min_size) +
                    " (the embedded message's ID)");
      return;
    }
    if (size > r.remaining()) {
      r.fail_at(ErrorCode::count_out_of_range, r.offset() - sizeof(SizeT),
                "byte count " + std::to_string(size) + " but " + std::to_string(r.remaining()) + " bytes left");
      return;
    }
    std::span<const std::uint8_t> bytes;
    if (r.read_bytes(size, bytes)) v.assign(bytes.begin(), bytes.end());
  }
  template <class Json>
  Json to_json(const value_type& v) const { return embedded_message_to_json<Json>(v); }
  template <class Json>
  Expected<void> from_json(const Json& j, value_type& v) const {
    if (auto read = embedded_message_from_json<Json>(j, v); !read) return read;
    if (v.size() < min_size || v.size() > std::numeric_limits<SizeT>::max())
      return wire::detail::json_error(std::to_string(v.size()) + " bytes; allowed " + std::to_string(min_size) + "-" +
                                      std::to_string(std::numeric_limits<SizeT>::max()));
    return {};
  }
};

// A variant whose members are integers: a u8 tag (the member's index), then
// that member's integer (JSIDL variant, as Query Events uses it).
struct TaggedValue {
  std::uint8_t tag = 0;
  std::uint32_t value = 0;
  bool operator==(const TaggedValue&) const = default;
};

struct TagAlternative {
  std::uint8_t tag;
  std::string_view name;
  std::uint8_t size;  // bytes of the member's integer: 1, 2 or 4
};

template <std::size_t N>
struct Tagged {
  using value_type = TaggedValue;
  std::array<TagAlternative, N> alternatives;
  constexpr std::span<const TagAlternative> tag_alternatives() const { return alternatives; }

  constexpr const TagAlternative* find(std::uint8_t tag) const {
    for (const auto& a : alternatives)
      if (a.tag == tag) return &a;
    return nullptr;
  }
  std::string doc() const {
    std::string out = "u8 tag, then: ";
    for (std::size_t i = 0; i < N; ++i)
      out += (i == 0 ? "" : ", ") + std::to_string(alternatives[i].tag) + " " + std::string(alternatives[i].name) +
             " (u" + std::to_string(8 * alternatives[i].size) + ")";
    return out;
  }
  void encode(const TaggedValue& v, ByteWriter& w, auto&) const {
    const auto* a = find(v.tag);
    if (a == nullptr) {
      w.fail(ErrorCode::bad_value, "variant tag " + std::to_string(v.tag) + " is not defined");
      return;
    }
    if (a->size < 4 && v.value >> (8 * a->size) != 0) {
      w.fail(ErrorCode::bad_value, std::to_string(v.value) + " does not fit " + std::string(a->name));
      return;
    }
    w.write(v.tag);
    if (a->size == 1) w.write(static_cast<std::uint8_t>(v.value));
    else if (a->size == 2) w.write(static_cast<std::uint16_t>(v.value));
    else w.write(v.value);
  }
  void decode(ByteReader& r, TaggedValue& v, auto&) const {
    if (!r.read(v.tag)) return;
    const auto* a = find(v.tag);
    if (a == nullptr) {
      r.fail_at(ErrorCode::bad_value, r.offset() - 1, "variant tag " + std::to_string(v.tag) + " is not defined");
      return;
    }
    if (a->size == 1) {
      std::uint8_t x = 0;
      if (r.read(x)) v.value = x;
    } else if (a->size == 2) {
      std::uint16_t x = 0;
      if (r.read(x)) v.value = x;
    } else {
      r.read(v.value);
    }
  }
  // {"message_id": 1027}: the member's name and its value.
  template <class Json>
  Json to_json(const TaggedValue& v) const {
    Json out = Json::object();
    if (const auto* a = find(v.tag)) out[std::string(a->name)] = v.value;
    else out["tag_" + std::to_string(v.tag)] = v.value;
    return out;
  }
  template <class Json>
  Expected<void> from_json(const Json& j, TaggedValue& v) const {
    if (!j.is_object() || j.size() != 1) return wire::detail::json_error("expected {" + names() + ": value}");
    const std::string key = j.begin().key();
    const Json& value = j.begin().value();
    for (const auto& a : alternatives) {
      if (a.name != key) continue;
      v.tag = a.tag;
      if (auto read = wire::detail::integer_from_json(value, v.value); !read) return read;
      if (a.size < 4 && v.value >> (8 * a.size) != 0) return wire::detail::json_error("out of range for its wire type");
      return {};
    }
    return wire::detail::json_error("unknown variant member '" + key + "' (expected one of: " + names() + ")");
  }

 private:
  std::string names() const {
    std::string out;
    for (std::size_t i = 0; i < N; ++i) out += (i == 0 ? "" : ", ") + std::string(alternatives[i].name);
    return out;
  }
};

template <std::size_t N>
constexpr Tagged<N> tagged_of(const TagAlternative (&alternatives)[N]) {
  Tagged<N> out{};
  for (std::size_t i = 0; i < N; ++i) out.alternatives[i] = alternatives[i];
  return out;
}

// A JSS ID in a message body: u16 subsystem, u8 node, u8 component (Report
// Control, Report Subsystem List). The header packs the same ID as a u32 with
// the component first (JssId::packed); these are the body's bytes.
struct IdCodec {
  using value_type = JssId;
  static constexpr std::size_t fixed_size = 4;
  std::string doc() const { return "JSS ID: u16 subsystem, u8 node, u8 component"; }
  JAUS_ALWAYS_INLINE void encode(const JssId& v, auto& w, auto&) const {
    w.write(v.subsystem);
    w.write(v.node);
    w.write(v.component);
  }
  JAUS_ALWAYS_INLINE void decode(auto& r, JssId& v, auto&) const {
    r.read(v.subsystem);
    r.read(v.node);
    r.read(v.component);
  }
  template <class Json>
  Json to_json(const JssId& v) const { return Json(v.to_string()); }
  template <class Json>
  Expected<void> from_json(const Json& j, JssId& v) const {
    const auto parsed = j.is_string() ? JssId::parse(j.template get<std::string>()) : std::nullopt;
    if (!parsed) return wire::detail::json_error("expected a JSS ID \"S.N.C\"");
    v = *parsed;
    return {};
  }
};

}  // namespace jaus::jss::codec
