// jaus_wireshark_gen FILE: writes the Wireshark plugin (wireshark_plugin.hpp)
// to FILE. The build's wireshark/jaus.lua, without waiting for jausctl, which
// prints the same plugin (`jausctl msg wireshark`).
#include <fstream>
#include <iostream>

#include "wireshark_plugin.hpp"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: jaus_wireshark_gen FILE\n";
    return 2;
  }
  std::ofstream out(argv[1], std::ios::binary);
  out << jaus::wireshark::plugin_lua();
  if (!out.flush()) {
    std::cerr << "jaus_wireshark_gen: cannot write " << argv[1] << "\n";
    return 1;
  }
  return 0;
}
