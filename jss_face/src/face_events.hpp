// The Events service (docs/jss.md, "Events"), kept natively by the face: RA has
// no JSS events, and its own events cannot be forwarded. A client's event
// asks its query message through the translators (origin.event_id set) at
// the confirmed rate (periodic) or every FaceConfig::change_poll_period
// (every change: an Event only when the report's bytes changed); the answer
// comes back to on_report(), which wraps it in Event with the event's
// sequence number. Queries of events reach the RA components from the
// client's alias channel 2 + event ID, so their answers find the event.
//
// Bounded: max_events_per_client per client node, max_events in all; event
// IDs are per client node (0..252, one alias channel each). An event not
// refreshed by Create/Update Event within event_timeout_min is cancelled
// with a Confirm Event Request (core v1.1); events end with their client.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <span>
#include <vector>

#include "jaus/base/log.hpp"
#include "jaus/base/time.hpp"
#include "jaus/jss/jss_id.hpp"
#include "jaus/jss_face/face.hpp"
#include "jaus/jss_face/translator.hpp"
#include "jaus/runtime/repeat_limiter.hpp"

namespace jaus::jss_face {

class EventEngine {
 public:
  // What the engine needs of the face.
  struct Host {
    virtual ~Host() = default;
    // Asks a query (an event's) through the translators.
    virtual void ask(const JssInbound& query) = 0;
    // Whether some translator answers this query on that component.
    virtual bool answers(std::uint16_t query_id, std::uint8_t ra_component_id) const = 0;
    // Sends JSS contents from our component to a client.
    virtual void send_contents(const jss::JssId& to, const jss::JssId& from, std::span<const std::uint8_t> contents) = 0;
    // Counts and logs a message that does not decode.
    virtual void malformed(const std::string& what, const std::string& why) = 0;
    // A client as log lines name it (FacePort::describe_client).
    virtual std::string describe_client(const jss::JssId& client) const = 0;
  };

  EventEngine(const FaceConfig& config, rt::Clock& clock, rt::Scheduler& scheduler, Host& host, rt::LogFn log);
  ~EventEngine();
  EventEngine(const EventEngine&) = delete;
  EventEngine& operator=(const EventEngine&) = delete;

  // Whether the message is the Events service's (the engine answers it).
  static bool is_events_message(std::uint16_t message_id);
  void from_jss(const JssInbound& message);
  // An answer to an event's query: wrapped in Event and sent (every change: only when changed).
  void on_report(const ReplyTo& to, const jss::JssId& our_component, std::span<const std::uint8_t> report);
  bool has_events_of(const jss::JssId& client_node) const;
  // The client node is forgotten: its events end without a word.
  void forget(const jss::JssId& client_node);
  std::size_t size() const { return events_.size(); }

  static constexpr double kMaxRateHz = 100.0;  // periodic rates above are confirmed at this

 private:
  struct Event {
    jss::JssId client;         // the requester
    jss::JssId our_component;
    Address ra_component;
    std::uint8_t event_id = 0;
    std::uint8_t type = 0;     // 0 periodic, 1 every change
    double rate_hz = 0;        // confirmed
    std::vector<std::uint8_t> query;  // contents: ID + body
    std::uint8_t request_id = 0;      // of the last Create/Update (the timeout's Confirm)
    rt::SenderStanding standing = rt::SenderStanding::trusted;
    std::uint8_t sequence = 0;        // of the next Event
    std::optional<std::vector<std::uint8_t>> last_report;  // every change: what was last sent
    rt::TimerId tick = rt::kNoTimer;
    rt::TimePoint next_tick{};
    rt::TimerId expiry = rt::kNoTimer;
  };
  // Events by (client node, event ID): the event ID is unique per client node.
  using Key = std::pair<jss::JssId, std::uint8_t>;

  void create(const JssInbound& m);
  void update(const JssInbound& m);
  void cancel(const JssInbound& m);
  void query_events(const JssInbound& m);
  void reject(const JssInbound& m, std::uint8_t request_id, std::uint8_t code, const char* why);
  void confirm(const jss::JssId& to, const jss::JssId& from, std::uint8_t request_id, const Event& event);
  // Checks a Create/Update's type, rate and query; the rate to confirm, or the reject code.
  struct Setup {
    std::uint8_t type = 0;
    double rate_hz = 0;
  };
  std::optional<std::uint8_t> check_setup(const JssInbound& m, std::uint8_t type, double requested_hz,
                                          std::span<const std::uint8_t> query, Setup& setup) const;
  template <class M>
  std::optional<M> decode(const JssInbound& m);
  void send(const jss::JssId& to, const jss::JssId& from, std::span<const std::uint8_t> contents);
  void start(Event& event);
  void stop(Event& event);
  void arm_expiry(Event& event);
  void tick(Key key);
  void expire(Key key);
  std::optional<std::uint8_t> free_event_id(const jss::JssId& client_node) const;
  std::size_t count_of(const jss::JssId& client_node) const;

  const FaceConfig& config_;
  rt::Clock& clock_;
  rt::Scheduler& scheduler_;
  Host& host_;
  rt::RepeatedLines lines_;
  std::map<Key, Event> events_;
};

}  // namespace jaus::jss_face
