// Still images as Report Image carries them: an RGB frame encoded as a whole
// PNG (libpng) or JPEG (libjpeg) file, and what a file's first bytes say it is.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "jaus/base/expected.hpp"
#include "jaus/components/camera.hpp"

namespace jaus::components {

// 8-bit RGB, rows top to bottom, no padding: rgb.size() == width * height * 3.
struct RgbImage {
  std::uint16_t width = 0;
  std::uint16_t height = 0;
  std::vector<std::uint8_t> rgb;
};

Expected<std::vector<std::uint8_t>> encode_png(const RgbImage& image);
Expected<std::vector<std::uint8_t>> encode_jpeg(const RgbImage& image, int quality = 85);
// PNG (11) or JPEG (7); any other format code is an error.
Expected<Image> encode_image(const RgbImage& image, std::uint8_t format, int jpeg_quality = 85);

// The format code of an encoded file from its magic bytes (PNG or JPEG), or nullopt.
std::optional<std::uint8_t> sniff_image_format(std::span<const std::uint8_t> bytes);
struct ImageSize {
  std::uint16_t width = 0;
  std::uint16_t height = 0;
};
// The size a PNG (IHDR) or JPEG (first SOF marker) file declares, or nullopt.
std::optional<ImageSize> encoded_image_size(std::span<const std::uint8_t> bytes);

}  // namespace jaus::components
