// The first message from one peer after this is made (any code), kept while
// a command is retransmitted: its reply may come before the ACK. One class
// for the sessions of both dialects (OcuSession, JssSession), which hand
// their listeners what they received. Private to apps/jausctl/ocu.
#pragma once

#include <functional>
#include <optional>

#include "jaus/ocu/jss_session.hpp"
#include "jaus/ocu/session.hpp"

namespace jausctl::ocu {

inline const jaus::Address& source_of(const jaus::ocu::Received& message) { return message.header.source; }
inline const jaus::jss::JssId& source_of(const jaus::ocu::JssReceived& message) { return message.source(); }

namespace detail {
template <class Listener>
struct ListenerMessage;
template <class Message>
struct ListenerMessage<std::function<void(const Message&)>> {
  using type = Message;
};
}  // namespace detail

template <class Session>
class FirstReply {
 public:
  using Message = typename detail::ListenerMessage<typename Session::Listener>::type;

  // `from`: the peer's ID in the session's dialect (jaus::Address, JssId), a wildcard matching any of its members.
  template <class Id>
  FirstReply(Session& session, const Id& from)
      : session_(session), id_(session.listen([this, from](const Message& message) {
          if (!reply_ && from.matches(source_of(message))) reply_ = message;
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
