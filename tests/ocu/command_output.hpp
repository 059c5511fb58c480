// What a jausctl command run in a test printed: its stdout and stderr, kept
// for the test to read (shared by the socket and the virtual-time fixtures).
#pragma once

#include <sstream>
#include <string>
#include <vector>

#include "ocu/ocu_commands.hpp"

namespace jausctl::test {

struct CommandOutput {
  ocu::CommandIo io() { return ocu::CommandIo{out, err}; }
  bool out_has(const std::string& text) const { return out.str().find(text) != std::string::npos; }
  std::vector<std::string> out_lines() const {
    std::vector<std::string> lines;
    std::istringstream in(out.str());
    for (std::string line; std::getline(in, line);) lines.push_back(line);
    return lines;
  }

  std::ostringstream out;
  std::ostringstream err;
};

}  // namespace jausctl::test
