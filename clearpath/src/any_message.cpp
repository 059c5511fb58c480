// AnyMessage's copy, move, comparison and destruction: one small function
// per message type each, instantiated here once.
#include "jaus/clearpath/any_message.hpp"

#include <memory>

namespace jaus::clearpath {

AnyMessage::AnyMessage(const AnyMessage& other) {
  other.visit([this](const auto& message) {
    using M = std::remove_cvref_t<decltype(message)>;
    ::new (static_cast<void*>(storage_)) M(message);
  });
  index_ = other.index_;
}

AnyMessage::AnyMessage(AnyMessage&& other) noexcept {
  other.visit([this](auto& message) {
    using M = std::remove_cvref_t<decltype(message)>;
    static_assert(std::is_nothrow_move_constructible_v<M>);
    ::new (static_cast<void*>(storage_)) M(std::move(message));
  });
  index_ = other.index_;
}

AnyMessage& AnyMessage::operator=(const AnyMessage& other) {
  if (this != &other) *this = AnyMessage(other);  // a throwing copy leaves *this as it was
  return *this;
}

AnyMessage& AnyMessage::operator=(AnyMessage&& other) noexcept {
  if (this == &other) return *this;
  visit([](auto& message) { std::destroy_at(&message); });
  other.visit([this](auto& message) {
    using M = std::remove_cvref_t<decltype(message)>;
    ::new (static_cast<void*>(storage_)) M(std::move(message));
  });
  index_ = other.index_;
  return *this;
}

bool operator==(const AnyMessage& a, const AnyMessage& b) {
  if (a.index() != b.index()) return false;
  return a.visit([&b](const auto& message) {
    using M = std::remove_cvref_t<decltype(message)>;
    return message == *b.get_if<M>();
  });
}

AnyMessage::~AnyMessage() {
  visit([](auto& message) { std::destroy_at(&message); });
}

}  // namespace jaus::clearpath
