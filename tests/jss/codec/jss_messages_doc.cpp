// Prints docs/jss-messages.md, generated from the JSS message descriptions
// (jss::messages_markdown); the test docs_jss_messages_up_to_date compares.
#include <cstdio>

#include "jaus/jss/catalogue.hpp"

int main() {
  const std::string doc = jaus::jss::messages_markdown();
  return std::fwrite(doc.data(), 1, doc.size(), stdout) == doc.size() ? 0 : 1;
}
