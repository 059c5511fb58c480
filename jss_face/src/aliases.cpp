#include "aliases.hpp"

#include <algorithm>

namespace jaus::jss_face {

AliasTable::AliasTable(std::uint8_t alias_subsystem, std::size_t max_clients)
    : alias_subsystem_(alias_subsystem),
      slots_(std::clamp<std::size_t>(max_clients, 1, kMaxClientSlots)) {}

std::optional<std::uint8_t> AliasTable::find(const jss::JssId& client) const {
  const jss::JssId node = client_node_of(client);
  for (std::size_t i = 0; i < slots_.size(); ++i)
    if (slots_[i].client == node) return static_cast<std::uint8_t>(i + 1);
  return std::nullopt;
}

std::optional<AliasTable::Assigned> AliasTable::assign(const jss::JssId& client, rt::TimePoint now,
                                                        const Reusable& reusable) {
  // An existing slot is not "heard" here: the face's own event queries use
  // it too, and only the client's messages (heard()) keep it.
  if (auto slot = find(client)) return Assigned{*slot, std::nullopt};
  const jss::JssId node = client_node_of(client);
  for (std::size_t i = 0; i < slots_.size(); ++i) {
    if (slots_[i].client) continue;
    slots_[i] = Slot{node, now};
    return Assigned{static_cast<std::uint8_t>(i + 1), std::nullopt};
  }
  // Full: the least recently heard slot whose client leaves nothing behind.
  std::optional<std::size_t> oldest;
  for (std::size_t i = 0; i < slots_.size(); ++i) {
    if (!reusable(static_cast<std::uint8_t>(i + 1), *slots_[i].client)) continue;
    if (!oldest || slots_[i].last_heard < slots_[*oldest].last_heard) oldest = i;
  }
  if (!oldest) return std::nullopt;
  Assigned assigned{static_cast<std::uint8_t>(*oldest + 1), slots_[*oldest].client};
  slots_[*oldest] = Slot{node, now};
  return assigned;
}

bool AliasTable::reserve(std::uint8_t slot, const jss::JssId& client, rt::TimePoint now) {
  if (slot < 1 || slot > slots_.size()) return false;
  const jss::JssId node = client_node_of(client);
  Slot& s = slots_[slot - 1];
  if (s.client && *s.client != node) return false;
  if (const auto other = find(node); other && *other != slot) return false;  // one slot a client node
  s = Slot{node, now};
  return true;
}

void AliasTable::heard(const jss::JssId& client, rt::TimePoint now) {
  if (auto slot = find(client)) slots_[*slot - 1].last_heard = now;
}

void AliasTable::release(std::uint8_t slot) {
  if (slot >= 1 && slot <= slots_.size()) slots_[slot - 1] = Slot{};
}

Address AliasTable::alias(std::uint8_t slot, const ReplyTo& origin) const {
  const std::uint8_t channel =
      origin.event_id ? static_cast<std::uint8_t>(kFirstEventChannel + *origin.event_id) : kOwnChannel;
  return Address{alias_subsystem_, slot, origin.client.component, channel};
}

std::optional<ReplyTo> AliasTable::client_of(const Address& alias) const {
  if (!is_alias(alias) || !alias.is_valid()) return std::nullopt;
  const auto node = client_in(alias.node);
  if (!node) return std::nullopt;
  ReplyTo to{jss::JssId{node->subsystem, node->node, alias.component}, std::nullopt};
  if (alias.instance >= kFirstEventChannel) to.event_id = static_cast<std::uint8_t>(alias.instance - kFirstEventChannel);
  return to;
}

std::optional<jss::JssId> AliasTable::client_in(std::uint8_t slot) const {
  if (slot < 1 || slot > slots_.size()) return std::nullopt;
  return slots_[slot - 1].client;
}

std::size_t AliasTable::in_use() const {
  return static_cast<std::size_t>(
      std::count_if(slots_.begin(), slots_.end(), [](const Slot& s) { return s.client.has_value(); }));
}

}  // namespace jaus::jss_face
