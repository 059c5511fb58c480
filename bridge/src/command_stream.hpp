// What the bridge's backends share when they command a Clearpath platform:
// a one-line text for a command's outcome and for a number, and an ordered
// command stream.
// Private to bridge/src.
#pragma once

#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <sstream>
#include <string>

#include "jaus/clearpath/client.hpp"

namespace jaus::bridge::detail {

namespace cp = clearpath;

inline std::string outcome_text(const cp::CommandOutcome& o) {
  switch (o.error) {
    case cp::CommandError::none: return "ok";
    case cp::CommandError::refused: {
      std::ostringstream s;
      s << "refused by the platform, result 0x" << std::hex << o.result;
      return s.str();
    }
    case cp::CommandError::no_ack: return "no answer after " + std::to_string(o.attempts) + " attempts";
    case cp::CommandError::link_down: return "link down";
    case cp::CommandError::not_encodable: return "not encodable";
    case cp::CommandError::superseded: return "superseded by a newer command";
    case cp::CommandError::queue_full: return "refused: too many commands waiting";
  }
  return "failed";
}

// A subscription's outcome: one unanswered or cut by the link is asked for
// again by the client (after resubscribe_delay, or at the reconnect).
inline std::string subscription_outcome_text(const cp::CommandOutcome& o) {
  const bool asked_again = o.error == cp::CommandError::no_ack || o.error == cp::CommandError::link_down;
  return outcome_text(o) + (asked_again ? "; asked again" : "");
}

// A number as a log line shows it (shortest form, as `<<` writes it).
inline std::string number_text(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

// One ordered stream of commands to the platform: one in flight at a time,
// the rest waiting in order, so a retried older command never overtakes a
// newer one. A motion target replaces a waiting one of its type (latest
// wins). Callbacks that arrive after the stream is gone do nothing.
class CommandStream {
 public:
  using Failed = std::function<void(const cp::AnyMessage&, const cp::CommandOutcome&)>;

  CommandStream(cp::Client& client, std::uint64_t& sent, Failed failed)
      : client_(client), sent_(sent), failed_(std::move(failed)) {}
  CommandStream(const CommandStream&) = delete;
  CommandStream& operator=(const CommandStream&) = delete;

  void post(cp::AnyMessage message, bool latest_wins) {
    if (latest_wins) {
      const auto type = cp::type_of(message);
      std::erase_if(waiting_, [&](const cp::AnyMessage& m) { return cp::type_of(m) == type; });
    }
    waiting_.push_back(std::move(message));
    if (!in_flight_) next();
  }
  // Forget what has not gone out yet (what is in flight is the client's).
  void clear() { waiting_.clear(); }

 private:
  void next() {
    if (waiting_.empty()) return;
    cp::AnyMessage message = std::move(waiting_.front());
    waiting_.pop_front();
    in_flight_ = true;
    ++sent_;
    std::weak_ptr<int> token = token_;
    client_.send(message, [this, token, message](const cp::CommandOutcome& outcome) {
      if (token.expired()) return;
      in_flight_ = false;
      if (!outcome.ok()) {
        if (outcome.error == cp::CommandError::link_down) waiting_.clear();
        failed_(message, outcome);
      }
      if (!in_flight_) next();
    });
  }

  cp::Client& client_;
  std::uint64_t& sent_;
  Failed failed_;
  std::deque<cp::AnyMessage> waiting_;
  bool in_flight_ = false;
  std::shared_ptr<int> token_ = std::make_shared<int>(0);
};

}  // namespace jaus::bridge::detail
