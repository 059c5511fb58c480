// The JSON form of every message body's fields (wire::fields_to_json and
// fields_from_json with nlohmann::ordered_json), compiled once in jaus_core
// beside the codec (compiled_codecs.hpp); declared extern here for the code
// that converts bodies to and from JSON (the catalogue, the typed tests).
// Apart from compiled_codecs.hpp so that only that code parses nlohmann/json.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "jaus/messages/compiled_codecs.hpp"

#define JAUS_JSON_CODEC_INSTANCES(extern_or_not, Body)                                                      \
  extern_or_not template nlohmann::ordered_json wire::fields_to_json<nlohmann::ordered_json, Body>(          \
      const Body&, wire::Dialect);                                                                             \
  extern_or_not template Expected<void> wire::fields_from_json<nlohmann::ordered_json, Body>(                 \
      const nlohmann::ordered_json&, Body&, wire::Dialect);
#define JAUS_DECLARE_JSON_CODEC(Body) JAUS_JSON_CODEC_INSTANCES(extern, Body)
// In the catalogue file of the body's group: the codec and its JSON form.
#define JAUS_DEFINE_CODEC(Body) JAUS_CODEC_INSTANCES(, Body) JAUS_JSON_CODEC_INSTANCES(, Body)

namespace jaus {
JAUS_ALL_BODIES(JAUS_DECLARE_JSON_CODEC)
}  // namespace jaus
