// Shared vocabulary of the message descriptions.
#pragma once

#include <array>
#include <cstdint>
#include <numbers>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include "jaus/wire/message.hpp"
#include "jaus/wire/named_codecs.hpp"

namespace jaus::msg {

using wire::Dialect;
using wire::Empty;
using wire::Message;

template <class... Ts>
struct TypeList {
  static constexpr std::size_t size = sizeof...(Ts);
};

inline constexpr double kPi = std::numbers::pi;

// Wire types by their RA names.
using Byte = wire::Int<std::uint8_t>;
using UShort = wire::Int<std::uint16_t>;
using UInt = wire::Int<std::uint32_t>;
using wire::NamedBits;
using wire::NamedValue;

// Names of enumerated values and bit fields that more than one body uses
// (written once, here); a table only one body uses lives beside that body.
// JSON shows a value by its name and accepts the name or the number.

// Primary status, bits 0-3 of Report Component Status (values 6-15 reserved,
// bits 4-7 available: such a byte shows as its number).
inline constexpr std::array<NamedValue, 6> kComponentStates{
    {{0, "initialize"}, {1, "ready"}, {2, "standby"}, {3, "shutdown"}, {4, "failure"}, {5, "emergency"}}};

// Set/Report Camera Format Options and Report Image.
inline constexpr std::array<NamedValue, 9> kAudioFormats{
    {{0, "unused"}, {1, "raw"}, {2, "pcm"}, {3, "au"}, {4, "wav"}, {5, "mid"}, {6, "mp3"}, {7, "mp2"}, {8, "asf"}}};
inline constexpr std::array<NamedValue, 17> kImageFormats{{{0, "unused"},
                                                           {1, "mpeg2"},
                                                           {2, "mpeg4"},
                                                           {3, "mjpeg"},
                                                           {4, "ntsc"},
                                                           {5, "pal"},
                                                           {6, "tiff"},
                                                           {7, "jpeg"},
                                                           {8, "gif"},
                                                           {9, "h263"},
                                                           {10, "h264"},
                                                           {11, "png"},
                                                           {12, "bmp"},
                                                           {13, "raw"},
                                                           {14, "ppm"},
                                                           {15, "pgm"},
                                                           {16, "pnm"}}};
inline constexpr auto kAudioFormat = wire::enum_of<std::uint8_t>(kAudioFormats);
inline constexpr auto kImageFormat = wire::enum_of<std::uint8_t>(kImageFormats);

// Set Camera Capabilities ("on") and Report Camera Capabilities ("available").
inline constexpr auto kImageryControl =
    wire::bits_of<std::uint16_t>({"auto_focus", "auto_exposure_iris", "image_stabilization", "white_balance",
                                  "sync_flash_strobe", "red_eye", "auto_shutter", "auto_gain", "non_interlaced"});
inline constexpr auto kAudioControl =
    wire::bits_of<std::uint16_t>({"audio", "auto_gain", "stereo", "directional", "front_microphone", "rear_microphone",
                                  "left_microphone", "right_microphone"});

// Frequently used scaled ranges.
inline constexpr wire::Scaled<std::int16_t> kAngleShort{-kPi, kPi};
inline constexpr wire::Scaled<std::int32_t> kAngleInt{-kPi, kPi};
inline constexpr wire::Scaled<std::int32_t> kLatitude{-90, 90};
inline constexpr wire::Scaled<std::int32_t> kLongitude{-180, 180};
inline constexpr wire::Scaled<std::int32_t> kElevation{-10'000, 35'000};
inline constexpr wire::Scaled<std::int32_t> kLocalXY{-100'000, 100'000};
inline constexpr wire::Scaled<std::uint16_t> kServiceRate{0, 1092};  // Hz

// Manipulator quantities: the openjaus dialect sends these signed values as
// unsigned with bias = lower limit (docs/wire-format.md, "Interoperability").
constexpr wire::Scaled<std::int32_t> manipulator_int(double lower, double upper) {
  return {lower, upper, wire::Quirk::openjaus_unsigned_bias};
}
constexpr wire::Scaled<std::int16_t> manipulator_short(double lower, double upper) {
  return {lower, upper, wire::Quirk::openjaus_unsigned_bias};
}

}  // namespace jaus::msg
