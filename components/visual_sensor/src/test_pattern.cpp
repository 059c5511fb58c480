#include "jaus/components/test_pattern.hpp"

#include <algorithm>
#include <array>

namespace jaus::components {

namespace {

struct Rgb {
  std::uint8_t r, g, b;
};

// White, yellow, cyan, green, magenta, red, blue, black.
constexpr std::array<Rgb, 8> kBars{{{235, 235, 235},
                                    {235, 235, 16},
                                    {16, 235, 235},
                                    {16, 235, 16},
                                    {235, 16, 235},
                                    {235, 16, 16},
                                    {16, 16, 235},
                                    {16, 16, 16}}};

// A small deterministic hash: the noise of pixel (x, y) in `frame`.
std::uint32_t noise(std::uint32_t x, std::uint32_t y, std::uint64_t frame) {
  std::uint64_t h = (static_cast<std::uint64_t>(x) << 32 | y) ^ (frame * 0x9E3779B97F4A7C15ull);
  h ^= h >> 33;
  h *= 0xFF51AFD7ED558CCDull;
  h ^= h >> 33;
  return static_cast<std::uint32_t>(h);
}

}  // namespace

RgbImage test_pattern(std::uint16_t width, std::uint16_t height, std::uint64_t frame) {
  RgbImage image;
  image.width = width;
  image.height = height;
  image.rgb.resize(static_cast<std::size_t>(width) * height * 3);
  if (width == 0 || height == 0) return image;
  auto put = [&](std::uint32_t x, std::uint32_t y, Rgb c) {
    std::uint8_t* p = &image.rgb[(static_cast<std::size_t>(y) * width + x) * 3];
    p[0] = c.r;
    p[1] = c.g;
    p[2] = c.b;
  };

  const std::uint32_t bars_end = height * 7u / 12u;  // bars, then a ramp, then the moving band
  const std::uint32_t ramp_end = height * 3u / 4u;
  for (std::uint32_t y = 0; y < height; ++y)
    for (std::uint32_t x = 0; x < width; ++x) {
      if (y < bars_end) {
        put(x, y, kBars[std::min<std::size_t>(x * kBars.size() / width, kBars.size() - 1)]);
      } else if (y < ramp_end) {
        const auto v = static_cast<std::uint8_t>(x * 255u / std::max<std::uint32_t>(width - 1, 1));
        put(x, y, {v, v, v});
      } else {
        const auto n = static_cast<std::uint8_t>(48 + (noise(x, y, frame) & 0x0F));
        put(x, y, {n, n, n});
      }
    }

  // The moving square: one side a third of the band, a step of 4 pixels per frame, wrapping.
  const std::uint32_t band = height - ramp_end;
  const std::uint32_t side = std::max<std::uint32_t>(1, std::min<std::uint32_t>(band / 3, width));
  const std::uint32_t travel = width - side + 1;
  const auto x0 = static_cast<std::uint32_t>((frame * 4) % travel);
  const std::uint32_t y0 = ramp_end + (band - side) / 2;
  for (std::uint32_t y = y0; y < y0 + side && y < height; ++y)
    for (std::uint32_t x = x0; x < x0 + side; ++x) put(x, y, {255, 255, 255});

  // The frame number: 16 blocks along the bottom of the band.
  const std::uint32_t cell = std::max<std::uint32_t>(1, width / 16);
  const std::uint32_t cell_h = std::max<std::uint32_t>(1, band / 6);
  for (std::uint32_t bit = 0; bit < 16; ++bit) {
    const bool one = (frame >> (15 - bit)) & 1u;
    for (std::uint32_t y = height - cell_h; y < height; ++y)
      for (std::uint32_t x = bit * cell; x < (bit + 1) * cell && x < width; ++x)
        put(x, y, one ? Rgb{255, 255, 255} : Rgb{0, 0, 0});
  }
  return image;
}

}  // namespace jaus::components
