#include "face_events.hpp"

#include <algorithm>
#include <cmath>

#include "aliases.hpp"
#include "jaus/jss/contents.hpp"
#include "jaus/jss/messages/events.hpp"

namespace jaus::jss_face {
namespace {

namespace jss_msg = jss::msg;
namespace event_reject = jss::msg::reject_event;
constexpr std::uint8_t kPeriodic = jss_msg::event_type::kPeriodic;
constexpr std::uint8_t kEveryChange = jss_msg::event_type::kEveryChange;

bool is_query(std::uint16_t message_id) { return message_id >= 0x2000 && message_id < 0x4000; }

rt::Duration period_of(double hz) {
  return std::chrono::duration_cast<rt::Duration>(std::chrono::duration<double>(1.0 / hz));
}

}  // namespace

EventEngine::EventEngine(const FaceConfig& config, rt::Clock& clock, rt::Scheduler& scheduler, Host& host,
                         rt::LogFn log)
    : config_(config), clock_(clock), scheduler_(scheduler), host_(host), lines_(clock, scheduler, std::move(log)) {}

EventEngine::~EventEngine() {
  for (auto& [key, event] : events_) stop(event);
}

bool EventEngine::is_events_message(std::uint16_t message_id) {
  switch (message_id) {
    case jss_msg::CreateEvent::code:
    case jss_msg::UpdateEvent::code:
    case jss_msg::CancelEvent::code:
    case jss_msg::CreateCommandEvent::code:
    case jss_msg::QueryEvents::code:
    case jss_msg::QueryEventTimeout::code:
      return true;
    default:
      return false;
  }
}

template <class M>
std::optional<M> EventEngine::decode(const JssInbound& m) {
  auto decoded = jss::decode_body<M>(m.body);
  if (!decoded) {
    host_.malformed(std::string(M::name) + " from " + m.origin.client.to_string(), decoded.error().message());
    return std::nullopt;
  }
  return std::move(*decoded);
}

void EventEngine::send(const jss::JssId& to, const jss::JssId& from, std::span<const std::uint8_t> contents) {
  if (!contents.empty()) host_.send_contents(to, from, contents);
}

void EventEngine::from_jss(const JssInbound& m) {
  switch (m.message_id) {
    case jss_msg::CreateEvent::code: return create(m);
    case jss_msg::UpdateEvent::code: return update(m);
    case jss_msg::CancelEvent::code: return cancel(m);
    case jss_msg::QueryEvents::code: return query_events(m);
    case jss_msg::QueryEventTimeout::code: {
      jss_msg::ReportEventTimeout report;
      report.timeout_min = config_.event_timeout_min;
      return send(m.origin.client, m.our_component, jss::encode_contents(report));
    }
    case jss_msg::CreateCommandEvent::code: {
      // Core v1.1 command events: no service here supports them (as IOP).
      const auto request = decode<jss_msg::CreateCommandEvent>(m);
      if (!request) return;
      return reject(m, request->request_id, event_reject::kMessageNotSupported, "command events are not supported");
    }
    default:
      return;
  }
}

std::optional<std::uint8_t> EventEngine::check_setup(const JssInbound& m, std::uint8_t type, double requested_hz,
                                                     std::span<const std::uint8_t> query, Setup& setup) const {
  if (type != kPeriodic && type != kEveryChange) return event_reject::kInvalidEventSetup;
  if (query.size() < 2) return event_reject::kInvalidEventSetup;
  const std::uint16_t query_id = jss::message_id_of(query);
  if (!is_query(query_id) || is_events_message(query_id) || !host_.answers(query_id, m.ra_component.component))
    return event_reject::kMessageNotSupported;
  setup.type = type;
  if (type == kPeriodic) {
    if (requested_hz <= 0) return event_reject::kInvalidEventSetup;
    // The wire's step is 1092/65535 Hz: 5 Hz arrives as 4.9989. Rounded to
    // 0.01 Hz (within a step, so the confirmed value encodes the same) the
    // rate is what the client meant: 5 Events a second, not 4.
    setup.rate_hz = std::min(std::round(requested_hz * 100.0) / 100.0, kMaxRateHz);
    if (setup.rate_hz <= 0) return event_reject::kInvalidEventSetup;
  } else {
    setup.rate_hz = 0;
  }
  return std::nullopt;
}

void EventEngine::create(const JssInbound& m) {
  const auto request = decode<jss_msg::CreateEvent>(m);
  if (!request) return;
  // An event is state the node must end when its client goes: not for a
  // client the transport could not record.
  if (m.standing == rt::SenderStanding::unrecorded)
    return reject(m, request->request_id, event_reject::kConnectionRefused, "the node cannot record this client");
  Setup setup;
  if (auto code = check_setup(m, request->event_type, request->requested_rate_hz, request->query_message, setup))
    return reject(m, request->request_id, *code, "invalid event setup, or the query is not supported");
  const jss::JssId client_node = client_node_of(m.origin.client);
  const std::uint16_t query_id = jss::message_id_of(request->query_message);
  // "Already exists" (docs/jss.md, "Events"): the same client, component and query message.
  auto existing = std::find_if(events_.begin(), events_.end(), [&](const auto& entry) {
    const Event& e = entry.second;
    return e.client == m.origin.client && e.our_component == m.our_component && jss::message_id_of(e.query) == query_id;
  });
  Event* event = nullptr;
  if (existing != events_.end()) {
    event = &existing->second;
    stop(*event);
  } else {
    const auto event_id = free_event_id(client_node);
    if (!event_id || count_of(client_node) >= config_.max_events_per_client || events_.size() >= config_.max_events)
      return reject(m, request->request_id, event_reject::kConnectionRefused,
                    "event table full (jss.max_events_per_client, jss.max_events)");
    event = &events_[Key{client_node, *event_id}];
    event->client = m.origin.client;
    event->our_component = m.our_component;
    event->ra_component = m.ra_component;
    event->event_id = *event_id;
  }
  event->type = setup.type;
  event->rate_hz = setup.rate_hz;
  event->query = request->query_message;
  event->request_id = request->request_id;
  event->standing = m.standing;
  event->last_report.reset();
  confirm(m.origin.client, m.our_component, request->request_id, *event);
  start(*event);
}

void EventEngine::update(const JssInbound& m) {
  const auto request = decode<jss_msg::UpdateEvent>(m);
  if (!request) return;
  const auto it = events_.find(Key{client_node_of(m.origin.client), request->event_id});
  if (it == events_.end() || it->second.our_component != m.our_component)
    return reject(m, request->request_id, event_reject::kInvalidEventIdForUpdate, "no such event");
  Setup setup;
  if (auto code = check_setup(m, request->event_type, request->requested_rate_hz, request->query_message, setup))
    return reject(m, request->request_id, *code, "invalid event setup, or the query is not supported");
  Event& event = it->second;
  stop(event);
  event.client = m.origin.client;
  event.type = setup.type;
  event.rate_hz = setup.rate_hz;
  event.query = request->query_message;
  event.request_id = request->request_id;
  event.last_report.reset();
  confirm(m.origin.client, m.our_component, request->request_id, event);
  start(event);
}

void EventEngine::cancel(const JssInbound& m) {
  const auto request = decode<jss_msg::CancelEvent>(m);
  if (!request) return;
  const std::uint8_t event_id = request->event_id.value_or(0);  // always sent in JSS
  const auto it = events_.find(Key{client_node_of(m.origin.client), event_id});
  if (it == events_.end() || it->second.our_component != m.our_component)
    return reject(m, request->request_id, event_reject::kInvalidEventIdForUpdate, "no such event");
  stop(it->second);
  confirm(m.origin.client, m.our_component, request->request_id, it->second);
  events_.erase(it);
}

void EventEngine::query_events(const JssInbound& m) {
  const auto query = decode<jss_msg::QueryEvents>(m);
  if (!query) return;
  const auto& filter = query->filter;
  jss_msg::ReportEvents report;
  for (const auto& [key, e] : events_) {
    if (e.our_component != m.our_component || report.events.size() == 255) continue;
    const bool wanted = filter.tag == jss_msg::events_filter::kAll ||
                        (filter.tag == jss_msg::events_filter::kMessageId && jss::message_id_of(e.query) == filter.value) ||
                        (filter.tag == jss_msg::events_filter::kEventType && e.type == filter.value) ||
                        (filter.tag == jss_msg::events_filter::kEventId && e.event_id == filter.value);
    if (wanted) report.events.push_back(jss_msg::EventEntry{e.type, e.event_id, e.query});
  }
  send(m.origin.client, m.our_component, jss::encode_contents(report));
}

void EventEngine::reject(const JssInbound& m, std::uint8_t request_id, std::uint8_t code, const char* why) {
  lines_.write("JSS event requests rejected", rt::LogLevel::info, [&] {
    return "jss: event request " + std::to_string(request_id) + " from " + host_.describe_client(m.origin.client) + " to " +
           m.our_component.to_string() + " rejected (code " + std::to_string(code) + "): " + why;
  });
  jss_msg::RejectEventRequest reply;
  reply.request_id = request_id;
  reply.response_code = code;
  reply.error_message = std::string(why).substr(0, 80);
  send(m.origin.client, m.our_component, jss::encode_contents(reply));
}

void EventEngine::confirm(const jss::JssId& to, const jss::JssId& from, std::uint8_t request_id, const Event& event) {
  jss_msg::ConfirmEventRequest reply;
  reply.request_id = request_id;
  reply.event_id = event.event_id;
  reply.confirmed_rate_hz = event.rate_hz;
  send(to, from, jss::encode_contents(reply));
}

void EventEngine::start(Event& event) {
  const Key key{client_node_of(event.client), event.event_id};
  // The first answer at once (the client has the data now), then at the rate.
  event.next_tick = clock_.now();
  event.tick = scheduler_.call_at(event.next_tick, [this, key] { tick(key); });
  arm_expiry(event);
}

void EventEngine::stop(Event& event) {
  if (event.tick != rt::kNoTimer) scheduler_.cancel(event.tick);
  if (event.expiry != rt::kNoTimer) scheduler_.cancel(event.expiry);
  event.tick = rt::kNoTimer;
  event.expiry = rt::kNoTimer;
}

void EventEngine::arm_expiry(Event& event) {
  if (event.expiry != rt::kNoTimer) scheduler_.cancel(event.expiry);
  event.expiry = rt::kNoTimer;
  if (config_.event_timeout_min == 0) return;
  const Key key{client_node_of(event.client), event.event_id};
  event.expiry =
      scheduler_.call_at(clock_.now() + std::chrono::minutes(config_.event_timeout_min), [this, key] { expire(key); });
}

void EventEngine::tick(Key key) {
  const auto it = events_.find(key);
  if (it == events_.end()) return;
  Event& event = it->second;
  event.tick = rt::kNoTimer;
  const rt::Duration period = event.type == kPeriodic
                                  ? period_of(event.rate_hz)
                                  : std::max(config_.change_poll_period, rt::Duration(std::chrono::milliseconds(1)));
  // From the due time, not from now: the rate does not drift.
  event.next_tick = std::max(event.next_tick + period, clock_.now());
  event.tick = scheduler_.call_at(event.next_tick, [this, key] { tick(key); });
  const JssInbound query{event.our_component,
                         event.ra_component,
                         ReplyTo{event.client, event.event_id},
                         jss::message_id_of(event.query),
                         std::span<const std::uint8_t>(event.query).subspan(2),
                         event.standing,
                         1};
  host_.ask(query);
}

void EventEngine::expire(Key key) {
  const auto it = events_.find(key);
  if (it == events_.end()) return;
  Event& event = it->second;
  event.expiry = rt::kNoTimer;
  lines_.write({"JSS events timed out", rt::kNoteworthyBurst}, rt::LogLevel::info, [&] {
    return "jss: event " + std::to_string(event.event_id) + " of " + event.client.to_string() +
           " cancelled: not refreshed within " + std::to_string(config_.event_timeout_min) + " min";
  });
  stop(event);
  confirm(event.client, event.our_component, event.request_id, event);
  events_.erase(it);
}

void EventEngine::on_report(const ReplyTo& to, const jss::JssId& our_component, std::span<const std::uint8_t> report) {
  if (!to.event_id) return;
  const auto it = events_.find(Key{client_node_of(to.client), *to.event_id});
  if (it == events_.end() || it->second.our_component != our_component) return;  // cancelled meanwhile
  Event& event = it->second;
  if (event.type == kEveryChange) {
    if (event.last_report && std::equal(event.last_report->begin(), event.last_report->end(), report.begin(),
                                        report.end()))
      return;
    event.last_report.emplace(report.begin(), report.end());
  }
  jss_msg::Event wrapped;
  wrapped.event_id = event.event_id;
  wrapped.sequence_number = event.sequence++;
  wrapped.report_message.assign(report.begin(), report.end());
  send(event.client, event.our_component, jss::encode_contents(wrapped));
}

bool EventEngine::has_events_of(const jss::JssId& client_node) const { return count_of(client_node) > 0; }

std::size_t EventEngine::count_of(const jss::JssId& client_node) const {
  std::size_t n = 0;
  for (auto it = events_.lower_bound(Key{client_node, 0}); it != events_.end() && it->first.first == client_node; ++it)
    ++n;
  return n;
}

std::optional<std::uint8_t> EventEngine::free_event_id(const jss::JssId& client_node) const {
  for (unsigned id = 0; id <= kMaxAliasEventId; ++id)
    if (!events_.contains(Key{client_node, static_cast<std::uint8_t>(id)})) return static_cast<std::uint8_t>(id);
  return std::nullopt;
}

void EventEngine::forget(const jss::JssId& client_node) {
  for (auto it = events_.lower_bound(Key{client_node, 0}); it != events_.end() && it->first.first == client_node;) {
    stop(it->second);
    it = events_.erase(it);
  }
}

}  // namespace jaus::jss_face
