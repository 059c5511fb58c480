// The token rules of the node's small HTTP faces (jaus-console's page,
// jausd's metrics): a token compared in constant time, given as `?token=`
// or as `Authorization: Bearer TOKEN` (what Prometheus sends with a scrape
// job's `authorization: {credentials: ...}`).
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace jaus::host {

// The value of `name` in a target's query ("/ws?token=abc" -> "abc"); empty when absent.
std::string query_value(std::string_view target, std::string_view name);

// Equal, in a time independent of where they differ.
bool same_secret(std::string_view a, std::string_view b);

// The token of an Authorization header "Bearer TOKEN" (the scheme in any
// case); empty when it is not one.
std::string_view bearer_token(std::string_view authorization);

// 127.0.0.0/8.
constexpr bool is_loopback_address(std::uint32_t address) { return (address >> 24) == 127; }

}  // namespace jaus::host
