// Service connections, requester side: open an SC to another component,
// deliver each report to a callback, re-create the SC when reports stop (the
// provider restarted or forgot us), and terminate it on request.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <span>
#include <string>

#include "jaus/core/header.hpp"
#include "jaus/messages/core_messages.hpp"
#include "jaus/runtime/environment.hpp"
#include "jaus/runtime/repeat_limiter.hpp"

namespace jaus::rt {

using SubscriptionId = std::uint32_t;

struct SubscriptionStatus {
  bool confirmed = false;
  std::optional<std::uint8_t> refused;  // response code of a refusal
  std::uint8_t instance = 0;
  double confirmed_rate_hz = 0;
  std::uint64_t reports = 0;
  std::uint64_t recreated = 0;
};

class ServiceConnectionClient {
 public:
  // Delivers one report payload (the caller decodes it).
  using Deliver = std::function<void(const Header&, std::span<const std::uint8_t>)>;
  using SendCreate = std::function<void(const Address& provider, const msg::CreateServiceConnection&)>;
  using SendTerminate = std::function<void(const Address& provider, const msg::TerminateServiceConnection&)>;

  // Reports silent for this many periods (and at least `minimum_silence`) re-create the SC.
  struct Options {
    double silent_periods = 5;
    Duration minimum_silence = std::chrono::seconds(1);
  };

  ServiceConnectionClient(Environment& env, Options options, SendCreate send_create, SendTerminate send_terminate);
  ~ServiceConnectionClient();

  SubscriptionId subscribe(const Address& provider, std::uint16_t report_code, double rate_hz,
                           std::uint32_t presence_vector, Deliver deliver);
  void unsubscribe(SubscriptionId id);
  // Terminates every subscription (the component is shutting down).
  void unsubscribe_all();

  void on_confirm(const Header& h, const msg::ConfirmServiceConnection& m);
  // True when the message was a report for one of our subscriptions.
  bool on_report(const Header& h, std::span<const std::uint8_t> payload);

  const SubscriptionStatus* status(SubscriptionId id) const;

 private:
  struct Subscription {
    Address provider;
    std::uint16_t code = 0;
    double rate_hz = 0;
    std::uint32_t presence = 0;
    Deliver deliver;
    SubscriptionStatus status;
    TimePoint last_heard{};
    TimerId watchdog = kNoTimer;
  };
  void create(Subscription& s);
  void arm(SubscriptionId id, Subscription& s);
  void check(SubscriptionId id);
  Duration silence_limit(const Subscription& s) const;

  Environment& env_;
  Options options_;
  SendCreate send_create_;
  SendTerminate send_terminate_;
  SubscriptionId last_id_ = 0;
  std::map<SubscriptionId, Subscription> subscriptions_;
  // A provider (or a sender forging its address) can refuse at will: limited.
  RepeatedLines lines_;
};

}  // namespace jaus::rt
