// JSS contents written and read field by field, little-endian (jss-notes.md
// 0.4), for the core service messages the face answers itself.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "jaus/core/byte_io.hpp"

namespace jaus::jss_face {

// Contents being written: the message ID first.
class ContentsWriter {
 public:
  explicit ContentsWriter(std::uint16_t message_id) { u16(message_id); }
  ContentsWriter& u8(std::uint8_t v) {
    bytes_.push_back(v);
    return *this;
  }
  ContentsWriter& u16(std::uint16_t v) {
    bytes_.push_back(static_cast<std::uint8_t>(v));
    bytes_.push_back(static_cast<std::uint8_t>(v >> 8));
    return *this;
  }
  ContentsWriter& u32(std::uint32_t v) {
    for (int i = 0; i < 4; ++i) bytes_.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
    return *this;
  }
  // u8 length then the characters (at most 255).
  ContentsWriter& str8(std::string_view text) {
    const std::size_t n = std::min<std::size_t>(text.size(), 255);
    u8(static_cast<std::uint8_t>(n));
    bytes_.insert(bytes_.end(), text.begin(), text.begin() + static_cast<std::ptrdiff_t>(n));
    return *this;
  }
  ContentsWriter& raw(std::span<const std::uint8_t> bytes) {
    bytes_.insert(bytes_.end(), bytes.begin(), bytes.end());
    return *this;
  }
  // Exactly n bytes: text, NUL-padded.
  ContentsWriter& fixed(std::string_view text, std::size_t n) {
    for (std::size_t i = 0; i < n; ++i) u8(i < text.size() ? static_cast<std::uint8_t>(text[i]) : 0);
    return *this;
  }
  // Patches a u8 count written earlier (at byte offset `at`).
  void patch_u8(std::size_t at, std::uint8_t v) { bytes_[at] = v; }
  void patch_u16(std::size_t at, std::uint16_t v) {
    bytes_[at] = static_cast<std::uint8_t>(v);
    bytes_[at + 1] = static_cast<std::uint8_t>(v >> 8);
  }
  std::size_t size() const { return bytes_.size(); }
  const std::vector<std::uint8_t>& bytes() const { return bytes_; }
  operator std::span<const std::uint8_t>() const { return bytes_; }  // NOLINT: contents are bytes

 private:
  std::vector<std::uint8_t> bytes_;
};

// A body being read; every read fails once the bytes run out.
class BodyReader {
 public:
  explicit BodyReader(std::span<const std::uint8_t> body) : reader_(body, 2) {}
  bool u8(std::uint8_t& v) { return reader_.read(v); }
  bool u16(std::uint16_t& v) { return reader_.read(v); }
  bool u32(std::uint32_t& v) { return reader_.read(v); }
  bool str8(std::string& v) {
    std::uint8_t n = 0;
    std::span<const std::uint8_t> chars;
    if (!u8(n) || !reader_.read_bytes(n, chars)) return false;
    v.assign(chars.begin(), chars.end());
    return true;
  }
  bool bytes(std::size_t n, std::span<const std::uint8_t>& out) { return reader_.read_bytes(n, out); }
  bool done() const { return !reader_.failed() && reader_.remaining() == 0; }
  bool failed() const { return reader_.failed(); }
  std::size_t remaining() const { return reader_.remaining(); }

 private:
  ByteReader reader_;
};

// "0x200D", for logs.
inline std::string hex_id(std::uint16_t id) {
  static constexpr char kDigits[] = "0123456789ABCDEF";
  std::string text = "0x";
  for (int shift = 12; shift >= 0; shift -= 4) text += kDigits[(id >> shift) & 0xF];
  return text;
}

// Event rates: U16 scaled over 0..1092 Hz (jss-notes.md 3.2).
inline constexpr double kMaxEventRateHz = 1092.0;
inline double event_rate_from_wire(std::uint16_t v) { return v * kMaxEventRateHz / 65535.0; }
inline std::uint16_t event_rate_to_wire(double hz) {
  const double clamped = std::clamp(hz, 0.0, kMaxEventRateHz);
  return static_cast<std::uint16_t>(std::lround(clamped * 65535.0 / kMaxEventRateHz));
}

}  // namespace jaus::jss_face
