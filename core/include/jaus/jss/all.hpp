// Every JSS message in scope (core v1.1, mobility v1.0), described once
// (jaus/jss/messages/), and the contents codec (contents.hpp). Catalogue by
// ID, name, service and JSON: catalogue.hpp.
#pragma once

#include "jaus/jss/compiled_codecs.hpp"
#include "jaus/jss/contents.hpp"
#include "jaus/jss/messages/core.hpp"
#include "jaus/jss/messages/discovery.hpp"
#include "jaus/jss/messages/events.hpp"
#include "jaus/jss/messages/mobility.hpp"
#include "jaus/jss/messages/waypoints.hpp"
