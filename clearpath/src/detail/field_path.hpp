// Dotted path of the field a visitor is at ("left.p", "channels[2].value"),
// so errors can say where they happened.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace jaus::clearpath::detail {

class FieldPath {
 public:
  std::string at(std::string_view leaf) const { return prefix_ + std::string(leaf); }
  // Enters a nested record; leave() restores the previous prefix.
  std::size_t enter(std::string_view name) {
    const auto saved = prefix_.size();
    prefix_ += std::string(name) + ".";
    return saved;
  }
  std::size_t enter(std::string_view name, std::size_t index) {
    const auto saved = prefix_.size();
    prefix_ += std::string(name) + "[" + std::to_string(index) + "].";
    return saved;
  }
  void leave(std::size_t saved) { prefix_.resize(saved); }

 private:
  std::string prefix_;
};

}  // namespace jaus::clearpath::detail
