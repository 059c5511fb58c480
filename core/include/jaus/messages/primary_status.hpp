// Primary status codes of Report Component Status (bits 0-3). Kept free of
// C++20 so that the Boost.MSM translation unit (C++17, see lifecycle.cpp) can
// include it.
#pragma once

#include <cstdint>

namespace jaus::msg {
enum class PrimaryStatus : std::uint8_t { initialize = 0, ready = 1, standby = 2, shutdown = 3, failure = 4, emergency = 5 };
}  // namespace jaus::msg
