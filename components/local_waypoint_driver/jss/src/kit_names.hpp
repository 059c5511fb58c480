// The translator kit's names (jaus/jss_face/) this library's files use
// unqualified, declared once for all of them: every file of a unity batch
// sees the same names whatever the order (docs/internals.md, "What a unity
// build asks of a file"), instead of a using-directive in one file reaching
// the next.
#pragma once

#include "jaus/jss_face/scaling.hpp"
#include "jaus/jss_face/translator.hpp"
#include "jaus/jss_face/translator_kit.hpp"

namespace jaus::components_jss {

using jss_face::FacePort;
using jss_face::is_one_of;
using jss_face::JssInbound;
using jss_face::RaOutbound;
using jss_face::reply_jss;
using jss_face::ServiceTranslator;
using jss_face::ServiceUri;
namespace kit = jss_face::kit;
namespace scaling = jss_face::scaling;

}  // namespace jaus::components_jss
