// The first message from one peer after this is made (any code), kept while
// a command is retransmitted: its reply may come before the ACK. One class
// for the sessions of both dialects (OcuSession, JssSession), which hand
// their listeners what they received (ocu::SessionCore). Private to
// apps/jausctl/ocu.
#pragma once

#include <optional>

#include "jaus/ocu/session_core.hpp"

namespace jausctl::ocu {

template <class Session>
class FirstReply {
 public:
  using Message = typename Session::Message;

  // `from`: the peer's ID in the session's dialect (jaus::Address, JssId), a wildcard matching any of its members.
  template <class Id>
  FirstReply(Session& session, const Id& from)
      : session_(session), id_(session.listen([this, from](const Message& message) {
          if (!reply_ && from.matches(message.source())) reply_ = message;
        })) {}
  ~FirstReply() { session_.unlisten(id_); }
  FirstReply(const FirstReply&) = delete;
  FirstReply& operator=(const FirstReply&) = delete;
  const std::optional<Message>& reply() const { return reply_; }

 private:
  Session& session_;
  std::optional<Message> reply_;
  typename Session::ListenerId id_;
};

}  // namespace jausctl::ocu
