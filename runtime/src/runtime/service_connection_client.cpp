#include "jaus/runtime/service_connection_client.hpp"

#include <algorithm>
#include <cmath>

namespace jaus::rt {

ServiceConnectionClient::ServiceConnectionClient(Environment& env, Options options, SendCreate send_create,
                                                 SendTerminate send_terminate)
    : env_(env),
      options_(options),
      send_create_(std::move(send_create)),
      send_terminate_(std::move(send_terminate)),
      lines_(env_.clock, env_.scheduler, [this](LogLevel level, const std::string& text) { env_.log(level, text); }) {}

ServiceConnectionClient::~ServiceConnectionClient() {
  for (auto& [id, s] : subscriptions_)
    if (s.watchdog != kNoTimer) env_.scheduler.cancel(s.watchdog);
}

SubscriptionId ServiceConnectionClient::subscribe(const Address& provider, std::uint16_t report_code, double rate_hz,
                                                  std::uint32_t presence_vector, Deliver deliver) {
  const SubscriptionId id = ++last_id_;
  Subscription& s = subscriptions_[id];
  s.provider = provider;
  s.code = report_code;
  s.rate_hz = rate_hz;
  s.presence = presence_vector;
  s.deliver = std::move(deliver);
  create(s);
  arm(id, s);
  return id;
}

void ServiceConnectionClient::create(Subscription& s) {
  s.status.confirmed = false;
  s.status.refused.reset();
  s.last_heard = env_.clock.now();
  msg::CreateServiceConnection m;
  m.command_code = s.code;
  m.periodic_rate_hz = s.rate_hz;
  m.presence_vector = s.presence;
  send_create_(s.provider, m);
}

Duration ServiceConnectionClient::silence_limit(const Subscription& s) const {
  const double rate = s.status.confirmed && s.status.confirmed_rate_hz > 0 ? s.status.confirmed_rate_hz : s.rate_hz;
  const auto periods = Duration(static_cast<Duration::rep>(std::llround(options_.silent_periods * 1e9 / rate)));
  return std::max(periods, options_.minimum_silence);
}

void ServiceConnectionClient::arm(SubscriptionId id, Subscription& s) {
  s.watchdog = env_.scheduler.call_at(env_.clock.now() + silence_limit(s), [this, id] { check(id); });
}

void ServiceConnectionClient::check(SubscriptionId id) {
  auto it = subscriptions_.find(id);
  if (it == subscriptions_.end()) return;
  Subscription& s = it->second;
  s.watchdog = kNoTimer;
  if (!s.status.refused && env_.clock.now() - s.last_heard >= silence_limit(s)) {
    ++s.status.recreated;
    env_.log(LogLevel::warn, "reports 0x" + wire::detail::hex_u32(s.code) + " from " + s.provider.to_string() +
                                 " stopped: creating the service connection again");
    create(s);
  }
  arm(id, s);
}

void ServiceConnectionClient::unsubscribe(SubscriptionId id) {
  auto it = subscriptions_.find(id);
  if (it == subscriptions_.end()) return;
  Subscription& s = it->second;
  if (s.watchdog != kNoTimer) env_.scheduler.cancel(s.watchdog);
  if (s.status.confirmed) send_terminate_(s.provider, msg::TerminateServiceConnection{{s.code, s.status.instance}});
  subscriptions_.erase(it);
}

void ServiceConnectionClient::unsubscribe_all() {
  while (!subscriptions_.empty()) unsubscribe(subscriptions_.begin()->first);
}

void ServiceConnectionClient::on_confirm(const Header& h, const msg::ConfirmServiceConnection& m) {
  for (auto& [id, s] : subscriptions_) {
    if (s.provider != h.source || s.code != m.command_code) continue;
    if (m.response_code == msg::sc_response::kCreated) {
      s.status.confirmed = true;
      s.status.instance = m.instance_id;
      s.status.confirmed_rate_hz = m.confirmed_rate_hz;
      s.last_heard = env_.clock.now();
    } else {
      s.status.refused = m.response_code;
      const std::uint16_t code = s.code;  // (a structured binding cannot be captured here)
      lines_.write({"service connections refused", kNoteworthyBurst}, LogLevel::warn, [&] {
        return "service connection 0x" + wire::detail::hex_u32(code) + " refused by " + h.source.to_string() +
               " (response " + std::to_string(m.response_code) + ")";
      });
    }
  }
}

bool ServiceConnectionClient::on_report(const Header& h, std::span<const std::uint8_t> payload) {
  // Reports on a service connection carry the SC flag (RA, and the common
  // peer does so too); the same report answering a query is not ours.
  if (!h.service_connection) return false;
  bool ours = false;
  for (auto& [id, s] : subscriptions_) {
    if (s.provider != h.source || s.code != h.command_code) continue;
    ours = true;
    s.last_heard = env_.clock.now();
    ++s.status.reports;
    s.deliver(h, payload);
  }
  return ours;
}

const SubscriptionStatus* ServiceConnectionClient::status(SubscriptionId id) const {
  const auto it = subscriptions_.find(id);
  return it == subscriptions_.end() ? nullptr : &it->second.status;
}

}  // namespace jaus::rt
