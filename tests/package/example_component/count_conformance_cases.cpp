// Links the top of jaus-node's library graph (jaus::conform) from the installed tree.
#include <iostream>

#include "jaus/conform/runner.hpp"

int main() {
  const auto count = jaus::conform::all_cases().size();
  std::cout << "jaus::conform: " << count << " conformance cases\n";
  return count > 0 ? 0 : 1;
}
