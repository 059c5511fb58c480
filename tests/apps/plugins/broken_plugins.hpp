// What the broken test plugins share: a kind that makes nothing useful.
#pragma once

#include "jaus/runtime/component_plugin.hpp"

namespace broken {

inline jaus::rt::ComponentKind kind(std::string_view name) {
  return jaus::rt::ComponentKind{
      .name = name,
      .default_id = 200,
      .options = {},
      .needs = {},
      .moves_hardware = false,
      .one_per_node = false,
      .check = {},
      .make = [](const jaus::rt::KindContext&) -> jaus::Expected<std::unique_ptr<jaus::rt::Component>> {
        return std::unique_ptr<jaus::rt::Component>();
      }};
}

inline std::vector<jaus::rt::ComponentKind> one_kind() { return {kind("broken_kind")}; }

}  // namespace broken
