// JSS events from the client side (docs/jss.md, "Events"): Create Event with an
// embedded query, periodic at a rate or on every change; each Event the
// provider sends is handed to a callback with the report it carries.
// Update and Cancel; the provider's event timeout (core v1.1, Query Event
// Timeout) is kept off by an Update Event every half of it, as fkie IOP's
// client does.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string_view>
#include <string>
#include <vector>

#include "jaus/ocu/jss_session.hpp"

namespace jaus::ocu {

enum class JssEventType : std::uint8_t { periodic = 0, every_change = 1 };

// One Event as received.
struct JssEventReport {
  jss::JssId provider;
  std::uint8_t event_id = 0;
  std::uint8_t sequence = 0;
  std::vector<std::uint8_t> report;  // the embedded report: message ID + body
  std::uint16_t report_id() const { return jss::message_id_of(report); }
  template <class Report>
  Expected<Report> decode() const {
    return jss::decode_contents<Report>(report);
  }
};

struct JssEventOptions {
  JssEventType type = JssEventType::periodic;
  double rate_hz = 1.0;  // periodic: 0..1092 Hz; every change sends 0
  rt::Duration request_timeout = kJssDefaultTimeout;
  // Update Event this often when the provider did not say its event timeout
  // (Report Event Timeout 0 or no answer: refreshing costs little).
  rt::Duration refresh_when_unknown = std::chrono::seconds(30);
};

// Reject Event Request response codes (1 periodic not supported, ... 6 invalid event ID).
std::string_view jss_reject_event_text(std::uint8_t code);

class JssEvent {
 public:
  using Callback = std::function<void(const JssEventReport&)>;

  // Create Event (resent every 250 ms until confirmed or rejected). Errors:
  // rejected ("1.1.42 rejected the event: 1 periodic not supported"), no
  // reply, interrupted.
  static Expected<std::unique_ptr<JssEvent>> create(JssSession& session, const jss::JssId& provider,
                                                    std::vector<std::uint8_t> query, JssEventOptions options,
                                                    Callback callback);
  template <class Query>
  static Expected<std::unique_ptr<JssEvent>> create(JssSession& session, const jss::JssId& provider, const Query& query,
                                                    JssEventOptions options, Callback callback) {
    return create(session, provider, jss::encode_contents(query), options, std::move(callback));
  }
  // Cancels the event when still open (best effort, no wait).
  ~JssEvent();
  JssEvent(const JssEvent&) = delete;
  JssEvent& operator=(const JssEvent&) = delete;

  std::uint8_t event_id() const { return event_id_; }
  const jss::JssId& provider() const { return provider_; }
  double confirmed_rate_hz() const { return confirmed_rate_hz_; }
  std::uint64_t events_received() const { return events_received_; }
  // Events missed by their sequence numbers.
  std::uint64_t events_missed() const { return events_missed_; }
  // Minutes, as Report Event Timeout said (0: none, or not answered).
  std::uint8_t provider_timeout_min() const { return provider_timeout_min_; }
  bool open() const { return open_; }
  // Ended by the provider: a Confirm Event Request that we did not ask for
  // (its event timeout cancelled it) or a Reject on refresh.
  bool ended_by_provider() const { return ended_by_provider_; }

  // Update Event with a new type and rate; waits for the confirmation.
  Expected<void> update(JssEventType type, double rate_hz);
  // Cancel Event; waits for Confirm Event Request (goes on after a stop was requested).
  Expected<void> cancel();

 private:
  // A Confirm or Reject Event Request answering the request in flight.
  struct Answer {
    bool confirmed = false;
    std::uint8_t event_id = 0;
    double rate_hz = 0;
    std::optional<std::uint8_t> reject_code;
  };
  JssEvent(JssSession& session, const jss::JssId& provider, std::vector<std::uint8_t> query, JssEventOptions options,
           Callback callback);
  // Sends `contents` (Create, Update or Cancel Event with `request_id`) until answered.
  Expected<Answer> request(const std::vector<std::uint8_t>& contents, std::uint8_t request_id, bool through_stop);
  // Request IDs come from one counter for every event of the process: the
  // provider's Confirm/Reject names only the request ID, and each JssEvent
  // hears every answer from its provider.
  static std::uint8_t take_request_id();
  void heard(const JssReceived& message);
  void schedule_refresh();
  void refresh();
  void cancel_refresh();

  JssSession& session_;
  jss::JssId provider_;
  std::vector<std::uint8_t> query_;
  JssEventOptions options_;
  Callback callback_;
  JssSession::ListenerId listener_ = 0;
  std::uint8_t event_id_ = 0;
  std::optional<std::uint8_t> pending_request_;  // waited for by request()
  std::optional<Answer> answer_;
  std::optional<std::uint8_t> refresh_request_;  // an Update Event sent by the refresh timer
  double confirmed_rate_hz_ = 0;
  std::uint64_t events_received_ = 0;
  std::uint64_t events_missed_ = 0;
  std::optional<std::uint8_t> last_sequence_;
  std::uint8_t provider_timeout_min_ = 0;
  rt::Duration refresh_period_{};
  bool open_ = false;
  bool ended_by_provider_ = false;
  rt::TimerId refresh_timer_ = rt::kNoTimer;
};

}  // namespace jaus::ocu
