#include "jaus/node/ack_reply.hpp"

namespace jaus::node {

std::optional<Header> ack_reply_for(const Header& received, const Address& responder, Delivery delivery) {
  if (received.ack_nak != AckNak::ack_requested) return std::nullopt;
  Header reply;
  reply.priority = received.priority;
  reply.ack_nak = delivery == Delivery::delivered ? AckNak::ack : AckNak::nak;
  reply.version = kVersionRa32;
  reply.command_code = received.command_code;
  reply.destination = received.source;
  reply.source = responder;
  reply.data_size = 0;
  reply.data_flag = DataFlag::single;
  reply.sequence = received.sequence;
  return reply;
}

}  // namespace jaus::node
