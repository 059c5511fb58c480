#include "jaus/ocu/jss_events.hpp"

#include <algorithm>
#include <atomic>

namespace jaus::ocu {

namespace {

namespace jss_msg = jss::msg;
constexpr rt::Duration kMinRefresh = std::chrono::seconds(1);

}  // namespace

std::string_view jss_reject_event_text(std::uint8_t code) {
  switch (code) {
    case jss_msg::reject_event::kPeriodicNotSupported: return "periodic events not supported";
    case jss_msg::reject_event::kChangeBasedNotSupported: return "change-based events not supported";
    case jss_msg::reject_event::kConnectionRefused: return "connection refused";
    case jss_msg::reject_event::kInvalidEventSetup: return "invalid event setup";
    case jss_msg::reject_event::kMessageNotSupported: return "message not supported";
    case jss_msg::reject_event::kInvalidEventIdForUpdate: return "invalid event ID for update";
    default: return "unknown response code";
  }
}

std::uint8_t JssEvent::take_request_id() {
  static std::atomic<std::uint8_t> next{0};  // sessions on several threads share it
  return next.fetch_add(1, std::memory_order_relaxed);
}

JssEvent::JssEvent(JssSession& session, const jss::JssId& provider, std::vector<std::uint8_t> query,
                   JssEventOptions options, Callback callback)
    : session_(session),
      provider_(provider),
      query_(std::move(query)),
      options_(options),
      callback_(std::move(callback)) {
  listener_ = session_.listen([this](const JssReceived& m) { heard(m); });
}

Expected<std::unique_ptr<JssEvent>> JssEvent::create(JssSession& session, const jss::JssId& provider,
                                                     std::vector<std::uint8_t> query, JssEventOptions options,
                                                     Callback callback) {
  if (query.size() < jss::kMessageIdSize)
    return unexpected(make_error(ErrorCode::invalid_argument, "an event needs a query message (its ID at least)"));
  if (provider.is_broadcast())
    return unexpected(
        make_error(ErrorCode::invalid_argument, "an event is created with one component, not " + provider.to_string()));
  std::unique_ptr<JssEvent> event(new JssEvent(session, provider, std::move(query), options, std::move(callback)));
  jss_msg::CreateEvent create;
  create.request_id = event->take_request_id();
  create.event_type = static_cast<std::uint8_t>(options.type);
  create.requested_rate_hz = options.type == JssEventType::periodic ? std::clamp(options.rate_hz, 0.0, 1092.0) : 0.0;
  create.query_message = event->query_;
  auto answer = event->request(jss::encode_contents(create), create.request_id, false);
  if (!answer) return unexpected(answer.error());
  if (!answer->confirmed)
    return unexpected(make_error(ErrorCode::refused,
                                 provider.to_string() + " rejected the event: " +
                                     (answer->reject_code ? std::to_string(*answer->reject_code) + " " +
                                                                std::string(jss_reject_event_text(*answer->reject_code))
                                                          : std::string("no reason given"))));
  event->event_id_ = answer->event_id;
  event->confirmed_rate_hz_ = answer->rate_hz;
  event->open_ = true;
  // Core v1.1 providers cancel an event not refreshed within their event timeout.
  if (auto timeout =
          session.query<jss_msg::ReportEventTimeout>(provider, jss_msg::QueryEventTimeout{}, options.request_timeout))
    event->provider_timeout_min_ = timeout->timeout_min;
  const rt::Duration half = std::chrono::seconds(30) * event->provider_timeout_min_;
  event->refresh_period_ =
      std::max(event->provider_timeout_min_ == 0 ? options.refresh_when_unknown : half, kMinRefresh);
  if (event->open_) event->schedule_refresh();
  return event;
}

JssEvent::~JssEvent() {
  cancel_refresh();
  if (open_) {  // best effort: the provider's event timeout ends it otherwise
    jss_msg::CancelEvent cancel;
    cancel.request_id = take_request_id();
    cancel.event_id = event_id_;
    session_.send(provider_, cancel);
  }
  session_.unlisten(listener_);
}

Expected<JssEvent::Answer> JssEvent::request(const std::vector<std::uint8_t>& contents, std::uint8_t request_id,
                                             bool through_stop) {
  pending_request_ = request_id;
  answer_.reset();
  session_.resend_until([&] { session_.send_contents(provider_, contents); }, [&] { return answer_.has_value(); },
                        options_.request_timeout, kQueryResendPeriod, through_stop);
  pending_request_.reset();
  if (answer_) return *answer_;
  if (session_.interrupted() && !through_stop) return unexpected(make_error(ErrorCode::interrupted, "interrupted"));
  return unexpected(no_reply_error(provider_, options_.request_timeout));
}

void JssEvent::heard(const JssReceived& m) {
  if (m.source() != provider_) return;
  const auto id = m.message_id();
  if (id == jss_msg::Event::code) {
    if (!open_) return;
    auto event = jss::decode_contents<jss_msg::Event>(m.contents);
    if (!event || event->event_id != event_id_) return;
    if (last_sequence_) events_missed_ += static_cast<std::uint8_t>(event->sequence_number - *last_sequence_ - 1);
    last_sequence_ = event->sequence_number;
    ++events_received_;
    if (callback_)
      callback_(JssEventReport{provider_, event->event_id, event->sequence_number, std::move(event->report_message)});
  } else if (id == jss_msg::ConfirmEventRequest::code) {
    auto confirm = jss::decode_contents<jss_msg::ConfirmEventRequest>(m.contents);
    if (!confirm) return;
    if (pending_request_ && confirm->request_id == *pending_request_) {
      answer_ = Answer{true, confirm->event_id, confirm->confirmed_rate_hz.value_or(0), std::nullopt};
    } else if (refresh_request_ && confirm->request_id == *refresh_request_) {
      refresh_request_.reset();
      confirmed_rate_hz_ = confirm->confirmed_rate_hz.value_or(0);
    } else if (open_ && confirm->event_id == event_id_) {
      // Not asked for: the provider cancelled the event (its event timeout).
      open_ = false;
      ended_by_provider_ = true;
      cancel_refresh();
    }
  } else if (id == jss_msg::RejectEventRequest::code) {
    auto reject = jss::decode_contents<jss_msg::RejectEventRequest>(m.contents);
    if (!reject) return;
    if (pending_request_ && reject->request_id == *pending_request_) {
      answer_ = Answer{false, 0, 0, reject->response_code};
    } else if (refresh_request_ && reject->request_id == *refresh_request_) {
      refresh_request_.reset();  // the provider no longer knows the event
      open_ = false;
      ended_by_provider_ = true;
      cancel_refresh();
    }
  }
}

void JssEvent::schedule_refresh() {
  refresh_timer_ = session_.scheduler().call_at(session_.clock().now() + refresh_period_, [this] {
    refresh_timer_ = rt::kNoTimer;
    refresh();
  });
}

void JssEvent::cancel_refresh() {
  if (refresh_timer_ != rt::kNoTimer) session_.scheduler().cancel(refresh_timer_);
  refresh_timer_ = rt::kNoTimer;
}

void JssEvent::refresh() {
  if (!open_) return;
  jss_msg::UpdateEvent update;
  update.request_id = take_request_id();
  update.event_type = static_cast<std::uint8_t>(options_.type);
  update.requested_rate_hz = options_.type == JssEventType::periodic ? std::clamp(options_.rate_hz, 0.0, 1092.0) : 0.0;
  update.event_id = event_id_;
  update.query_message = query_;
  refresh_request_ = update.request_id;
  session_.send(provider_, update);
  schedule_refresh();
}

Expected<void> JssEvent::update(JssEventType type, double rate_hz) {
  if (!open_) return unexpected(make_error(ErrorCode::invalid_argument, "the event is not open"));
  jss_msg::UpdateEvent update;
  update.request_id = take_request_id();
  update.event_type = static_cast<std::uint8_t>(type);
  update.requested_rate_hz = type == JssEventType::periodic ? std::clamp(rate_hz, 0.0, 1092.0) : 0.0;
  update.event_id = event_id_;
  update.query_message = query_;
  auto answer = request(jss::encode_contents(update), update.request_id, false);
  if (!answer) return unexpected(answer.error());
  if (!answer->confirmed)
    return unexpected(make_error(ErrorCode::refused,
                                 provider_.to_string() + " rejected the update: " +
                                     (answer->reject_code ? std::string(jss_reject_event_text(*answer->reject_code))
                                                          : std::string("no reason given"))));
  options_.type = type;
  options_.rate_hz = rate_hz;
  confirmed_rate_hz_ = answer->rate_hz;
  return {};
}

Expected<void> JssEvent::cancel() {
  if (!open_) return {};
  cancel_refresh();
  open_ = false;  // no more Events taken, whatever the answer
  jss_msg::CancelEvent cancel;
  cancel.request_id = take_request_id();
  cancel.event_id = event_id_;
  auto answer = request(jss::encode_contents(cancel), cancel.request_id, true);
  if (!answer) return unexpected(answer.error());
  if (!answer->confirmed)
    return unexpected(make_error(ErrorCode::refused, provider_.to_string() + " rejected Cancel Event"));
  return {};
}

}  // namespace jaus::ocu
