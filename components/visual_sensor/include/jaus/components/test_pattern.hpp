// The simulated cameras' picture: colour bars over a grey ramp, and below
// them a band of faint sensor noise with a white square that moves one step
// per frame and the frame number as 16 black/white blocks (most significant
// first). A pure function of the frame number: consecutive frames differ,
// and the same frame is the same image.
#pragma once

#include <cstdint>

#include "jaus/components/image_codec.hpp"

namespace jaus::components {

RgbImage test_pattern(std::uint16_t width, std::uint16_t height, std::uint64_t frame);

}  // namespace jaus::components
