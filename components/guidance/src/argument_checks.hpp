#pragma once
// The argument checks every guidance file makes, written once (file-scope
// copies would also collide when the library compiles as a unity build).

#include <cmath>

#include "jaus/base/error.hpp"

namespace jaus::components::guidance::detail {

inline bool positive(double v) { return std::isfinite(v) && v > 0; }
inline Error bad(const char* what) { return make_error(ErrorCode::invalid_argument, what); }

}  // namespace jaus::components::guidance::detail
