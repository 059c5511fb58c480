#include "jaus/clearpath/messages.hpp"

#include <algorithm>
#include <array>
#include <utility>

namespace jaus::clearpath {
namespace {

// Alternatives 1..N of AnyMessage are the typed messages (0 is Ack).
constexpr std::size_t kTyped = std::variant_size_v<MessageVariant> - 1;

template <std::size_t... I>
constexpr std::array<MessageTypeInfo, kTyped> build_catalogue(std::index_sequence<I...>) {
  return {MessageTypeInfo{std::variant_alternative_t<I + 1, MessageVariant>::kType,
                      std::variant_alternative_t<I + 1, MessageVariant>::kName,
                      kind_of(std::variant_alternative_t<I + 1, MessageVariant>::kType)}...};
}

template <std::size_t... I>
constexpr std::array<AnyMessage (*)(), kTyped> build_factories(std::index_sequence<I...>) {
  return {+[]() -> AnyMessage { return AnyMessage(std::in_place_index<I + 1>); }...};
}

// Catalogue entries in variant order, and a by-type permutation.
constexpr auto kInVariantOrder = build_catalogue(std::make_index_sequence<kTyped>{});
constexpr auto kFactories = build_factories(std::make_index_sequence<kTyped>{});

struct Sorted {
  std::array<MessageTypeInfo, kTyped> infos;
  std::array<std::size_t, kTyped> variant_index;
};

constexpr Sorted build_sorted() {
  Sorted s{kInVariantOrder, {}};
  for (std::size_t i = 0; i < kTyped; ++i) s.variant_index[i] = i;
  // Insertion sort: constexpr-friendly and the list is short.
  for (std::size_t i = 1; i < kTyped; ++i)
    for (std::size_t j = i; j > 0 && s.infos[j - 1].type > s.infos[j].type; --j) {
      std::swap(s.infos[j - 1], s.infos[j]);
      std::swap(s.variant_index[j - 1], s.variant_index[j]);
    }
  return s;
}

constexpr Sorted kSorted = build_sorted();

constexpr bool types_unique() {
  for (std::size_t i = 1; i < kTyped; ++i)
    if (kSorted.infos[i - 1].type == kSorted.infos[i].type) return false;
  return true;
}
static_assert(types_unique(), "two messages share a type code");

std::optional<std::size_t> sorted_position(std::uint16_t type) {
  const auto it = std::lower_bound(kSorted.infos.begin(), kSorted.infos.end(), type,
                                   [](const MessageTypeInfo& info, std::uint16_t t) { return info.type < t; });
  if (it == kSorted.infos.end() || it->type != type) return std::nullopt;
  return static_cast<std::size_t>(it - kSorted.infos.begin());
}

}  // namespace

std::span<const MessageTypeInfo> message_catalogue() { return kSorted.infos; }

std::optional<MessageTypeInfo> find_message(std::uint16_t type) {
  const auto at = sorted_position(type);
  if (!at) return std::nullopt;
  return kSorted.infos[*at];
}

std::optional<MessageTypeInfo> find_message(std::string_view name) {
  for (const auto& info : kSorted.infos)
    if (info.name == name) return info;
  return std::nullopt;
}

std::optional<AnyMessage> make_message(std::uint16_t type) {
  const auto at = sorted_position(type);
  if (!at) return std::nullopt;
  return kFactories[kSorted.variant_index[*at]]();
}

std::optional<std::uint16_t> type_of(const AnyMessage& message) {
  return std::visit(
      [](const auto& m) -> std::optional<std::uint16_t> {
        if constexpr (requires { std::remove_cvref_t<decltype(m)>::kType; }) {
          return std::remove_cvref_t<decltype(m)>::kType;
        } else {
          return std::nullopt;
        }
      },
      message);
}

std::string_view name_of(const AnyMessage& message) {
  return std::visit([](const auto& m) { return std::remove_cvref_t<decltype(m)>::kName; }, message);
}

}  // namespace jaus::clearpath
