// Every message of the RA 3.x message set that the framework speaks.
#pragma once

#include "jaus/messages/communications_messages.hpp"
#include "jaus/messages/core_messages.hpp"
#include "jaus/messages/discovery_messages.hpp"
#include "jaus/messages/environment_messages.hpp"
#include "jaus/messages/event_messages.hpp"
#include "jaus/messages/manipulator_messages.hpp"
#include "jaus/messages/platform_messages.hpp"
