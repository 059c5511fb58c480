// How `jausctl discover` prints what it found: a table for people, JSON for
// scripts. Sans-I/O: strings and JSON out.
#pragma once

#include <cstddef>
#include <string>

#include "jaus/ocu/discovery.hpp"
#include "cli_values.hpp"
#include "jaus/ocu/message_json.hpp"

namespace jausctl::ocu {

// {"subsystems":[{"subsystem":1,"identification":{...}|null,"nodes":[{"node":1,...,
//   "components":[{"address":"1.1.35.1","kind":"communicator","identification":...,
//   "inputs":[{"code":"0x0001","name":...,"presence_vector":0}],"outputs":[...]}]}]}]}
Json discovery_json(const Discovery& discovery);

// One row per subsystem, node and component, each component followed by what
// it accepts and provides.
std::string discovery_table(const Discovery& discovery);

// A cell of discover's tables: `text` padded to `width`, then two spaces.
std::string table_cell(std::string text, std::size_t width);

}  // namespace jausctl::ocu
