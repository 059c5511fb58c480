// `--save-image FILE` of `jausctl query` and `jausctl subscribe`: the image a
// Report Image carries (camera ID, format code, then a whole PNG or JPEG
// file; environment_messages.hpp) written to FILE, and the report's JSON
// line with the image bytes replaced by what was saved, so a terminal is not
// flooded with hex.
#pragma once

#include <string>

#include "jaus/base/expected.hpp"
#include "jaus/ocu/message_json.hpp"
#include "jaus/ocu/session.hpp"

namespace jausctl::ocu {

// Writes the image to `path` through a temporary file renamed over it, so a
// reader never sees half an image (subscribe overwrites the file with each
// new frame). An error (malformed or invalid_argument) when `report` is not a
// Report Image that decodes, or the file cannot be written.
jaus::Expected<std::size_t> save_report_image(const jaus::ocu::Received& report, const std::string& path);

// The report's JSON with `data` replaced by {"bytes": N, "saved_to": path}.
jaus::ocu::Json with_saved_image(jaus::ocu::Json report, std::size_t bytes, const std::string& path);

}  // namespace jausctl::ocu
