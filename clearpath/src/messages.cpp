#include "jaus/clearpath/messages.hpp"

#include <algorithm>
#include <array>
#include <utility>

namespace jaus::clearpath {
namespace {

// MessageTypes[1..N] are the typed messages (0 is Ack).
constexpr std::size_t kTyped = MessageTypes::size - 1;

template <class... Typed>
constexpr std::array<MessageTypeInfo, kTyped> build_catalogue(TypeList<Ack, Typed...>) {
  return {MessageTypeInfo{Typed::kType, Typed::kName, kind_of(Typed::kType)}...};
}

template <class M>
AnyMessage make_default() {
  return AnyMessage(M{});
}

template <class... Typed>
constexpr std::array<AnyMessage (*)(), kTyped> build_factories(TypeList<Ack, Typed...>) {
  return {&make_default<Typed>...};
}

// Catalogue entries in the order of MessageTypes, and a by-type permutation.
constexpr auto kInListOrder = build_catalogue(MessageTypes{});
constexpr auto kFactories = build_factories(MessageTypes{});

struct Sorted {
  std::array<MessageTypeInfo, kTyped> infos;
  std::array<std::size_t, kTyped> list_index;
};

constexpr Sorted build_sorted() {
  Sorted s{kInListOrder, {}};
  for (std::size_t i = 0; i < kTyped; ++i) s.list_index[i] = i;
  // Insertion sort: constexpr-friendly and the list is short.
  for (std::size_t i = 1; i < kTyped; ++i)
    for (std::size_t j = i; j > 0 && s.infos[j - 1].type > s.infos[j].type; --j) {
      std::swap(s.infos[j - 1], s.infos[j]);
      std::swap(s.list_index[j - 1], s.list_index[j]);
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
  return kFactories[kSorted.list_index[*at]]();
}

std::optional<std::uint16_t> type_of(const AnyMessage& message) {
  return visit(
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
  return visit([](const auto& m) { return std::remove_cvref_t<decltype(m)>::kName; }, message);
}

}  // namespace jaus::clearpath
