// The floor for the codec benchmark (issue 50): Report Global Pose and Set
// Wrench Effort encoded (header + payload) and decoded (header checked, payload
// into the same message types) by hand, without the message descriptions, the
// field codecs or ByteReader/ByteWriter: a few tens of bytes copied with
// scaling arithmetic. It does what the codec must do for these messages and no
// more: the presence vector from the optional members, each scaled field
// clamped and rounded as the RA says, the header's version, data flag and data
// size checked, reserved presence bits and a wrong size refused. It writes the
// same bytes as wire::encode_message and decodes the same values as
// wire::decode_payload_into (codec_speed_guard checks both before it times
// anything), so the codec's time over this one says what the codec's
// generality costs. Deliberately independent of jaus/core/scaled_integer.hpp:
// a slower scaling there slows the codec, not this.
#pragma once

#include <cstdint>
#include <cstring>
#include <optional>
#include <span>

#include "jaus/messages/all.hpp"

namespace jaus::bench {

// The messages every codec benchmark uses: every presence bit set.
inline msg::ReportGlobalPose full_global_pose() {
  msg::ReportGlobalPose m;
  m.latitude_deg = 41.616;
  m.longitude_deg = -100.332;
  m.elevation_m = 1893.5;
  m.position_rms_m = 1.87;
  m.roll_rad = 0.0123;
  m.pitch_rad = -0.0456;
  m.yaw_rad = 2.5;
  m.attitude_rms_rad = 0.01;
  m.time_stamp = TimeStamp{789, 42, 37, 13, 21};
  return m;
}

inline msg::SetWrenchEffort full_wrench_effort() {
  msg::SetWrenchEffort m;
  m.propulsive_linear_effort_x_percent = 46.24;
  m.propulsive_linear_effort_y_percent = -5.5;
  m.propulsive_linear_effort_z_percent = 0;
  m.propulsive_rotational_effort_x_percent = 1;
  m.propulsive_rotational_effort_y_percent = -2;
  m.propulsive_rotational_effort_z_percent = -76.86;
  m.resistive_linear_effort_x_percent = 10;
  m.resistive_linear_effort_y_percent = 0;
  m.resistive_linear_effort_z_percent = 0;
  m.resistive_rotational_effort_x_percent = 0;
  m.resistive_rotational_effort_y_percent = 0;
  m.resistive_rotational_effort_z_percent = 5;
  return m;
}

namespace reference {

inline constexpr double kPi = 3.14159265358979323846;

// A scaled integer field of wire type I over [R::lower, R::upper] (signed:
// 2^n - 2 steps around the middle; unsigned: 2^n - 1 steps from the lower
// limit). The limits come in a type, not as double template arguments, which
// clang 14 does not take.
template <class I, class R>
struct Scaled {
  static constexpr double Lower = R::lower;
  static constexpr double Upper = R::upper;
  static constexpr bool is_signed = static_cast<I>(-1) < 0;
  static constexpr double steps = is_signed ? static_cast<double>(static_cast<std::uint64_t>(1) << (8 * sizeof(I))) - 2
                                            : static_cast<double>(static_cast<std::uint64_t>(1) << (8 * sizeof(I))) - 1;
  static constexpr double bias = is_signed ? (Upper + Lower) / 2 : Lower;
  static constexpr double scale = (Upper - Lower) / steps;
  static constexpr double per_unit = steps / (Upper - Lower);

  static void put(std::uint8_t*& p, double v) {
    v = v > Lower ? v : Lower;  // NaN becomes the lower limit
    v = v < Upper ? v : Upper;
    const double exact = (v - bias) * per_unit;
    const auto raw = static_cast<I>(static_cast<std::int64_t>(exact + (exact < 0 ? -0.5 : 0.5)));
    std::memcpy(p, &raw, sizeof raw);  // little-endian host (x86, arm64)
    p += sizeof raw;
  }
  static double get(const std::uint8_t*& p) {
    I raw;
    std::memcpy(&raw, p, sizeof raw);
    p += sizeof raw;
    if constexpr (is_signed) {
      if (raw == static_cast<I>(static_cast<I>(1) << (8 * sizeof(I) - 1))) return Lower;
    }
    return static_cast<double>(raw) * scale + bias;
  }
};

inline void put_header(std::uint8_t* p, const Header& h, std::uint16_t code, std::uint16_t size) {
  p[0] = static_cast<std::uint8_t>(h.priority | (static_cast<unsigned>(h.ack_nak) << 4) |
                                   (h.service_connection ? 0x40 : 0) | (h.experimental ? 0x80 : 0));
  p[1] = h.version;
  p[2] = static_cast<std::uint8_t>(code);
  p[3] = static_cast<std::uint8_t>(code >> 8);
  p[4] = h.destination.instance;
  p[5] = h.destination.component;
  p[6] = h.destination.node;
  p[7] = h.destination.subsystem;
  p[8] = h.source.instance;
  p[9] = h.source.component;
  p[10] = h.source.node;
  p[11] = h.source.subsystem;
  p[12] = static_cast<std::uint8_t>(size);
  p[13] = static_cast<std::uint8_t>(((size >> 8) & 0x0F) | (static_cast<unsigned>(h.data_flag) << 4));
  p[14] = static_cast<std::uint8_t>(h.sequence);
  p[15] = static_cast<std::uint8_t>(h.sequence >> 8);
}

// The header's checks (version, data flag, data size); the payload, or empty
// with ok false.
struct Payload {
  const std::uint8_t* data = nullptr;
  std::size_t size = 0;
  bool ok = false;
};
inline Payload check_header(std::span<const std::uint8_t> packet) {
  if (packet.size() < 16) return {};
  const unsigned version = packet[1] & 0x3F;
  const unsigned flag = packet[13] >> 4;
  const unsigned size = packet[12] | ((packet[13] & 0x0F) << 8);
  if ((version != 1 && version != 2) || (flag != 0 && flag != 1 && flag != 2 && flag != 4 && flag != 8) ||
      size > 4080 || size != packet.size() - 16)
    return {};
  return {packet.data() + 16, size, true};
}

template <class Codec>
void put_if(std::uint8_t*& p, const std::optional<double>& v) {
  if (v) Codec::put(p, *v);
}
template <class Codec>
void get_if(const std::uint8_t*& p, unsigned pv, int bit, std::optional<double>& v) {
  if ((pv >> bit) & 1u)
    v = Codec::get(p);
  else
    v.reset();
}

struct LatitudeRange {
  static constexpr double lower = -90.0, upper = 90.0;
};
using Latitude = Scaled<std::int32_t, LatitudeRange>;
struct LongitudeRange {
  static constexpr double lower = -180.0, upper = 180.0;
};
using Longitude = Scaled<std::int32_t, LongitudeRange>;
struct ElevationRange {
  static constexpr double lower = -10000.0, upper = 35000.0;
};
using Elevation = Scaled<std::int32_t, ElevationRange>;
struct PositionRmsRange {
  static constexpr double lower = 0.0, upper = 100.0;
};
using PositionRms = Scaled<std::uint32_t, PositionRmsRange>;
struct AngleRange {
  static constexpr double lower = -kPi, upper = kPi;
};
using Angle = Scaled<std::int16_t, AngleRange>;
struct AttitudeRmsRange {
  static constexpr double lower = 0.0, upper = kPi;
};
using AttitudeRms = Scaled<std::uint16_t, AttitudeRmsRange>;

// Header + payload into `out` (room for the whole message); the bytes
// written, 0 if a time stamp part does not fit its bits.
inline std::size_t encode(const Header& h, const msg::ReportGlobalPose& m, std::span<std::uint8_t> out) {
  std::uint8_t* p = out.data() + 18;
  const unsigned pv = m.latitude_deg.has_value() | m.longitude_deg.has_value() << 1 | m.elevation_m.has_value() << 2 |
                      m.position_rms_m.has_value() << 3 | m.roll_rad.has_value() << 4 | m.pitch_rad.has_value() << 5 |
                      m.yaw_rad.has_value() << 6 | m.attitude_rms_rad.has_value() << 7 |
                      m.time_stamp.has_value() << 8;
  put_if<Latitude>(p, m.latitude_deg);
  put_if<Longitude>(p, m.longitude_deg);
  put_if<Elevation>(p, m.elevation_m);
  put_if<PositionRms>(p, m.position_rms_m);
  put_if<Angle>(p, m.roll_rad);
  put_if<Angle>(p, m.pitch_rad);
  put_if<Angle>(p, m.yaw_rad);
  put_if<AttitudeRms>(p, m.attitude_rms_rad);
  if (m.time_stamp) {
    const TimeStamp& t = *m.time_stamp;
    if (t.millisecond > 0x3FF || t.second > 0x3F || t.minute > 0x3F || t.hour > 0x1F || t.day > 0x1F) return 0;
    const std::uint32_t raw = t.millisecond | t.second << 10 | t.minute << 16 | static_cast<std::uint32_t>(t.hour) << 22 |
                              static_cast<std::uint32_t>(t.day) << 27;
    std::memcpy(p, &raw, 4);
    p += 4;
  }
  out[16] = static_cast<std::uint8_t>(pv);
  out[17] = static_cast<std::uint8_t>(pv >> 8);
  const auto size = static_cast<std::uint16_t>(p - out.data() - 16);
  put_header(out.data(), h, msg::ReportGlobalPose::code, size);
  return 16 + size;
}

// Header checked, payload into `m`; false for a packet the codec refuses.
inline bool decode(std::span<const std::uint8_t> packet, msg::ReportGlobalPose& m) {
  const Payload payload = check_header(packet);
  if (!payload.ok || payload.size < 2) return false;
  const std::uint8_t* p = payload.data;
  const unsigned pv = p[0] | p[1] << 8;
  p += 2;
  if (pv & ~0x1FFu) return false;
  const std::size_t size = 2 + ((pv & 1) + (pv >> 1 & 1) + (pv >> 2 & 1) + (pv >> 3 & 1)) * 4 +
                           ((pv >> 4 & 1) + (pv >> 5 & 1) + (pv >> 6 & 1) + (pv >> 7 & 1)) * 2 + (pv >> 8 & 1) * 4;
  if (size != payload.size) return false;
  get_if<Latitude>(p, pv, 0, m.latitude_deg);
  get_if<Longitude>(p, pv, 1, m.longitude_deg);
  get_if<Elevation>(p, pv, 2, m.elevation_m);
  get_if<PositionRms>(p, pv, 3, m.position_rms_m);
  get_if<Angle>(p, pv, 4, m.roll_rad);
  get_if<Angle>(p, pv, 5, m.pitch_rad);
  get_if<Angle>(p, pv, 6, m.yaw_rad);
  get_if<AttitudeRms>(p, pv, 7, m.attitude_rms_rad);
  if (pv >> 8 & 1) {
    std::uint32_t raw;
    std::memcpy(&raw, p, 4);
    m.time_stamp = TimeStamp{static_cast<std::uint16_t>(raw & 0x3FF), static_cast<std::uint8_t>(raw >> 10 & 0x3F),
                             static_cast<std::uint8_t>(raw >> 16 & 0x3F), static_cast<std::uint8_t>(raw >> 22 & 0x1F),
                             static_cast<std::uint8_t>(raw >> 27 & 0x1F)};
  } else {
    m.time_stamp.reset();
  }
  return true;
}

struct PropulsiveRange {
  static constexpr double lower = -100.0, upper = 100.0;
};
using Propulsive = Scaled<std::int16_t, PropulsiveRange>;
struct ResistiveRange {
  static constexpr double lower = 0.0, upper = 100.0;
};
using Resistive = Scaled<std::uint8_t, ResistiveRange>;

inline std::size_t encode(const Header& h, const msg::SetWrenchEffort& m, std::span<std::uint8_t> out) {
  std::uint8_t* p = out.data() + 18;
  const std::optional<double>* propulsive[] = {
      &m.propulsive_linear_effort_x_percent,     &m.propulsive_linear_effort_y_percent,
      &m.propulsive_linear_effort_z_percent,     &m.propulsive_rotational_effort_x_percent,
      &m.propulsive_rotational_effort_y_percent, &m.propulsive_rotational_effort_z_percent};
  const std::optional<double>* resistive[] = {
      &m.resistive_linear_effort_x_percent,     &m.resistive_linear_effort_y_percent,
      &m.resistive_linear_effort_z_percent,     &m.resistive_rotational_effort_x_percent,
      &m.resistive_rotational_effort_y_percent, &m.resistive_rotational_effort_z_percent};
  unsigned pv = 0;
  for (int i = 0; i < 6; ++i) {
    pv |= static_cast<unsigned>(propulsive[i]->has_value()) << i;
    put_if<Propulsive>(p, *propulsive[i]);
  }
  for (int i = 0; i < 6; ++i) {
    pv |= static_cast<unsigned>(resistive[i]->has_value()) << (6 + i);
    put_if<Resistive>(p, *resistive[i]);
  }
  out[16] = static_cast<std::uint8_t>(pv);
  out[17] = static_cast<std::uint8_t>(pv >> 8);
  const auto size = static_cast<std::uint16_t>(p - out.data() - 16);
  put_header(out.data(), h, msg::SetWrenchEffort::code, size);
  return 16 + size;
}

inline bool decode(std::span<const std::uint8_t> packet, msg::SetWrenchEffort& m) {
  const Payload payload = check_header(packet);
  if (!payload.ok || payload.size < 2) return false;
  const std::uint8_t* p = payload.data;
  const unsigned pv = p[0] | p[1] << 8;
  p += 2;
  if (pv & ~0xFFFu) return false;
  std::size_t size = 2;
  for (int i = 0; i < 12; ++i) size += ((pv >> i) & 1u) * (i < 6 ? 2 : 1);
  if (size != payload.size) return false;
  std::optional<double>* propulsive[] = {
      &m.propulsive_linear_effort_x_percent,     &m.propulsive_linear_effort_y_percent,
      &m.propulsive_linear_effort_z_percent,     &m.propulsive_rotational_effort_x_percent,
      &m.propulsive_rotational_effort_y_percent, &m.propulsive_rotational_effort_z_percent};
  std::optional<double>* resistive[] = {
      &m.resistive_linear_effort_x_percent,     &m.resistive_linear_effort_y_percent,
      &m.resistive_linear_effort_z_percent,     &m.resistive_rotational_effort_x_percent,
      &m.resistive_rotational_effort_y_percent, &m.resistive_rotational_effort_z_percent};
  for (int i = 0; i < 6; ++i) get_if<Propulsive>(p, pv, i, *propulsive[i]);
  for (int i = 0; i < 6; ++i) get_if<Resistive>(p, pv, 6 + i, *resistive[i]);
  return true;
}

}  // namespace reference
}  // namespace jaus::bench
