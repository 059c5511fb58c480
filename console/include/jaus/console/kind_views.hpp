// What the console shows of a component, by its ID: the operator views
// (rt::operator_view) of every kind the host knows (host::component_kinds():
// built-in, then added ones such as plugins') whose RA ID it is. An ID no
// kind has shows in the tree and nothing of it is followed. The console
// names no kind and no ID: a kind says what is shown for it.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace jaus::console {

std::vector<std::string_view> views_of(std::uint8_t component_id);
// Every ID that has a view, with its views (the welcome frame's `views`).
std::map<std::uint8_t, std::vector<std::string>> views_by_id();

}  // namespace jaus::console
