#include "jaus/runtime/service_connections.hpp"

#include <algorithm>
#include <cmath>
#include <set>

namespace jaus::rt {

namespace {
using msg::sc_response::kCommandNotSupported;
using msg::sc_response::kCreated;
using msg::sc_response::kInsufficientAuthority;
using msg::sc_response::kInvalidParameters;
using msg::sc_response::kRefused;

// The RA's slowest rate: one report a minute.
constexpr double kMinimumRateHz = 0.0166;

std::string code_text(std::uint16_t code) { return "0x" + wire::detail::hex_u32(code); }

Duration after_periods(double periods, double rate_hz) {
  return Duration(static_cast<Duration::rep>(std::llround(periods * 1e9 / rate_hz)));
}
}  // namespace

ServiceConnectionProvider::ServiceConnectionProvider(Environment& env, Address self, ServiceConnectionLimits limits,
                                                     Send send, MayCommand may_command, CommandLost command_lost)
    : env_(env),
      self_(self),
      limits_(limits),
      send_(std::move(send)),
      may_command_(std::move(may_command)),
      command_lost_(std::move(command_lost)),
      lines_(env_.clock, env_.scheduler, [this](LogLevel level, const std::string& text) { log(level, text); }) {}

ServiceConnectionProvider::~ServiceConnectionProvider() {
  for (auto& [key, c] : connections_)
    if (c.timer != kNoTimer) env_.scheduler.cancel(c.timer);
}

void ServiceConnectionProvider::log(LogLevel level, const std::string& text) const {
  env_.log(level, "service connections " + self_.to_string() + ": " + text);
}

void ServiceConnectionProvider::provide(std::uint16_t report_code, std::uint32_t available_presence,
                                        Producer producer, double max_rate_hz) {
  provided_[report_code] = Provided{available_presence, std::move(producer), max_rate_hz};
}

void ServiceConnectionProvider::confirm(const Header& h, std::uint16_t code, std::uint8_t instance, double rate,
                                        std::uint8_t response) {
  msg::ConfirmServiceConnection reply;
  reply.command_code = code;
  reply.instance_id = instance;
  reply.confirmed_rate_hz = rate;
  reply.response_code = response;
  std::vector<std::uint8_t> payload(16);
  const auto size = wire::encode_payload(reply, payload);
  Header out;
  out.command_code = msg::ConfirmServiceConnection::code;
  out.destination = h.source;
  out.source = self_;
  out.data_size = static_cast<std::uint16_t>(*size);
  send_(out, std::span(payload).first(*size));
  if (response != kCreated) {
    ++counters_.refused;
    lines_.write("Create Service Connection refused", LogLevel::info, [&] {
      return "Create Service Connection for " + code_text(code) + " from " + h.source.to_string() +
             " refused (response " + std::to_string(response) + ")";
    });
  }
}

std::uint8_t ServiceConnectionProvider::instance_for(std::uint16_t code, std::uint32_t presence, bool command,
                                                     const Address& requester) {
  std::set<std::uint8_t> used;
  for (const auto& [key, c] : connections_) {
    if (key.code != code) continue;
    used.insert(key.instance);
    // Inform SCs with the same code and presence vector share one instance;
    // a command SC belongs to its commander.
    if (!command && !c.command && c.presence == presence) return key.instance;
    if (command && c.command && key.requester == requester) return key.instance;
  }
  std::uint8_t instance = 0;
  while (used.count(instance) != 0 && instance < 255) ++instance;
  return instance;
}

bool ServiceConnectionProvider::accepts_command(std::uint16_t code) const {
  return std::find(command_codes_.begin(), command_codes_.end(), code) != command_codes_.end();
}

bool ServiceConnectionProvider::has_requester_under(const Address& where) const {
  return std::any_of(connections_.begin(), connections_.end(),
                     [&](const auto& entry) { return where.covers(entry.first.requester); });
}

void ServiceConnectionProvider::refuse(const Header& h, const msg::CreateServiceConnection& m, std::uint8_t response) {
  confirm(h, m.command_code, 0, 0, response);
}

void ServiceConnectionProvider::on_create(const Header& h, const msg::CreateServiceConnection& m) {
  const std::uint16_t code = m.command_code;
  const bool command = accepts_command(code);
  const auto provided = provided_.find(code);
  if (!command && provided == provided_.end()) return confirm(h, code, 0, 0, kCommandNotSupported);
  if (!(m.periodic_rate_hz >= kMinimumRateHz)) return confirm(h, code, 0, 0, kInvalidParameters);
  if (command && !may_command_(h.source, code)) return confirm(h, code, 0, 0, kInsufficientAuthority);

  const std::uint32_t presence = command ? 0 : (m.presence_vector & provided->second.available);
  const std::uint8_t instance = instance_for(code, presence, command, h.source);
  const Key key{h.source, code, instance};
  auto existing = connections_.find(key);
  if (existing == connections_.end() && connections_.size() >= limits_.max_connections)
    return confirm(h, code, 0, 0, kRefused);
  if (const auto cap = limits_.max_per_requester_node.find(code);
      !command && existing == connections_.end() && cap != limits_.max_per_requester_node.end()) {
    const auto held = std::count_if(connections_.begin(), connections_.end(), [&](const auto& entry) {
      const Address& r = entry.first.requester;
      return entry.first.code == code && r.subsystem == h.source.subsystem && r.node == h.source.node;
    });
    if (static_cast<std::size_t>(held) >= cap->second) return confirm(h, code, 0, 0, kRefused);
  }

  // The confirmed rate never exceeds the requested one, the limits' maximum,
  // nor the rate the report's source updates at.
  double rate = std::min(m.periodic_rate_hz, limits_.max_rate_hz);
  if (!command && provided->second.max_rate_hz > 0) rate = std::min(rate, provided->second.max_rate_hz);
  if (!command) {
    // What the other inform connections already send (a connection created
    // again gives its own rate back first).
    double sending = 0;
    for (const auto& [other, c] : connections_)
      if (!c.command && !(other == key)) sending += c.rate_hz;
    rate = std::min(rate, limits_.max_total_rate_hz - sending);
    if (!(rate >= kMinimumRateHz)) return confirm(h, code, 0, 0, kRefused);
  }
  Connection& c = existing != connections_.end() ? existing->second : connections_[key];
  if (c.timer != kNoTimer) env_.scheduler.cancel(c.timer);
  c = Connection{};
  c.command = command;
  c.presence = presence;
  c.rate_hz = rate;
  c.start = env_.clock.now();
  c.last_command = c.start;
  ++counters_.created;
  lines_.write({"service connections created", kNoteworthyBurst}, LogLevel::info, [&] {
    return std::string(command ? "command" : "inform") + " SC " + code_text(code) + "/" + std::to_string(instance) +
           " for " + h.source.to_string() + " at " + std::to_string(rate) + " Hz";
  });
  confirm(h, code, instance, rate, kCreated);
  if (command)
    schedule(key, c);
  else
    fire(key);  // first report at once, then every period
}

Duration ServiceConnectionProvider::deadman_limit(const Connection& c) const {
  const Duration most = std::max(limits_.deadman_minimum, limits_.deadman_maximum);
  return std::clamp(after_periods(limits_.deadman_periods, c.rate_hz), limits_.deadman_minimum, most);
}

void ServiceConnectionProvider::schedule(const Key& key, Connection& c) {
  if (!c.active) return;
  // Reports go at ideal times start + k * period, so rounding never
  // accumulates. A command SC's deadman timer is set for the moment the last
  // command would expire: commands only move last_command, they arm nothing.
  const TimePoint next = c.command ? c.last_command + deadman_limit(c)
                                   : c.start + after_periods(static_cast<double>(c.sent), c.rate_hz);
  c.timer = env_.scheduler.call_at(next, [this, key] { fire(key); });
}

void ServiceConnectionProvider::fire(const Key& key) {
  auto it = connections_.find(key);
  if (it == connections_.end()) return;
  Connection& c = it->second;
  c.timer = kNoTimer;
  if (!c.active) return;
  if (c.command) {
    // Deadman: the commander must keep commanding. A command since the timer
    // was set moved the expiry: wait for the new one.
    if (env_.clock.now() - c.last_command < deadman_limit(c)) return schedule(key, c);
    c.command_lost = true;
    ++counters_.commands_lost;
    lines_.write({"command service connections lost", kNoteworthyBurst}, LogLevel::warn, [&] {
      return "command SC " + code_text(key.code) + " from " + key.requester.to_string() + " silent: loss of command";
    });
    // Safety: the component stops its actuators here (Component::enforce_stop).
    // The timer is set again by the next command (on_command).
    command_lost_(key.requester, key.code);
    return;
  }
  const auto& provided = provided_.at(key.code);
  if (provided.produce(c.presence, report_buffer_)) {
    Header h;
    h.command_code = key.code;
    h.destination = key.requester;
    h.source = self_;
    h.service_connection = true;
    h.sequence = c.sequence++;
    send_(h, report_buffer_);
    ++counters_.reports_sent;
  }
  ++c.sent;
  schedule(key, c);
}

void ServiceConnectionProvider::on_command(const Header& h) {
  for (auto& [key, c] : connections_)
    if (c.command && key.requester == h.source && key.code == h.command_code) {
      c.last_command = env_.clock.now();
      if (c.command_lost) {
        c.command_lost = false;
        lines_.write({"command service connections resumed", kNoteworthyBurst}, LogLevel::info,
                     [&, &resumed = key] {  // a structured binding is captured through a reference of its own
                       return "command SC " + code_text(resumed.code) + " from " + resumed.requester.to_string() +
                              " resumed";
                     });
        if (c.timer == kNoTimer) schedule(key, c);
      }
    }
}

void ServiceConnectionProvider::end_commands_not_from(const std::optional<Address>& controller,
                                                      std::string_view why) {
  for (auto it = connections_.begin(); it != connections_.end();) {
    auto next = std::next(it);
    if (it->second.command && (!controller || it->first.requester != *controller)) stop(it, why);
    it = next;
  }
}

void ServiceConnectionProvider::on_activate(const Header& h, const msg::ActivateServiceConnection& m) {
  auto it = connections_.find(Key{h.source, m.command_code, m.instance_id});
  // Part 3: Activate "has no effect if sent by Inform requesters".
  if (it == connections_.end() || !it->second.command || it->second.active) return;
  it->second.active = true;
  it->second.last_command = env_.clock.now();
  schedule(it->first, it->second);
}

void ServiceConnectionProvider::on_suspend(const Header& h, const msg::SuspendServiceConnection& m) {
  auto it = connections_.find(Key{h.source, m.command_code, m.instance_id});
  if (it == connections_.end()) return;
  it->second.active = false;
  if (it->second.timer != kNoTimer) env_.scheduler.cancel(it->second.timer);
  it->second.timer = kNoTimer;
}

void ServiceConnectionProvider::on_terminate(const Header& h, const msg::TerminateServiceConnection& m) {
  auto it = connections_.find(Key{h.source, m.command_code, m.instance_id});
  if (it == connections_.end()) {
    lines_.write("Terminate for an unknown service connection", LogLevel::debug, [&] {
      return "Terminate for unknown SC " + code_text(m.command_code) + "/" + std::to_string(m.instance_id) + " from " +
             h.source.to_string();
    });
    return;
  }
  stop(it, "terminated by requester");
}

void ServiceConnectionProvider::stop(std::map<Key, Connection>::iterator it, std::string_view why) {
  if (it->second.timer != kNoTimer) env_.scheduler.cancel(it->second.timer);
  ++counters_.terminated;
  lines_.write({"service connections ended", kNoteworthyBurst}, LogLevel::info, [&] {
    return "SC " + code_text(it->first.code) + "/" + std::to_string(it->first.instance) + " for " +
           it->first.requester.to_string() + " ended: " + std::string(why);
  });
  connections_.erase(it);
}

void ServiceConnectionProvider::end_all_from(const Address& requester, std::string_view why) {
  for (auto it = connections_.begin(); it != connections_.end();) {
    auto next = std::next(it);
    if (requester.covers(it->first.requester)) stop(it, why);
    it = next;
  }
}

void ServiceConnectionProvider::end_all(std::string_view why) {
  while (!connections_.empty()) stop(connections_.begin(), why);
}

}  // namespace jaus::rt
