#include "jaus/node/ack_tracker.hpp"

namespace jaus::node {

AckKey ack_key_of_sent(const Header& sent) {
  return AckKey{sent.source, sent.destination, sent.command_code, sent.sequence};
}

std::string_view to_string(AckOutcome outcome) {
  switch (outcome) {
    case AckOutcome::acknowledged: return "acknowledged";
    case AckOutcome::refused: return "refused (NAK)";
    case AckOutcome::exhausted: return "no answer after the last transmission";
  }
  return "unknown";
}

template class BasicAckTracker<RaAcks>;

}  // namespace jaus::node
