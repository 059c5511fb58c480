// AnyMessage's copy, move and destruction, instantiated for the 110
// alternatives once, here (messages.hpp says why), in a file of their own so
// that they compile beside the message factories of messages.cpp.
#include "jaus/clearpath/messages.hpp"

namespace jaus::clearpath {

AnyMessage::AnyMessage(const AnyMessage& other) = default;
AnyMessage::AnyMessage(AnyMessage&& other) noexcept = default;
AnyMessage& AnyMessage::operator=(const AnyMessage& other) = default;
AnyMessage& AnyMessage::operator=(AnyMessage&& other) noexcept = default;
AnyMessage::~AnyMessage() = default;

}  // namespace jaus::clearpath
