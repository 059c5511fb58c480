// Service connections, provider side (Create/Confirm/Activate/Suspend/
// Terminate Service Connection, Part 3 0x0008-0x000C).
//
// - Inform SCs: a requester asks for a report at a rate; reports go out with
//   the SC flag and a per-SC sequence number, at ideal times start + k * period
//   (no cumulative drift). Inform SCs with the same command code and presence
//   vector share one instance ID; a repeat Create from the same requester
//   updates its SC. The presence vector sent is the AND of the requested one
//   and what the component provides.
// - Command SCs: the controller announces it will send a command at a rate.
//   The provider watches it as a deadman: no command for several periods (but
//   never longer than a maximum) is a loss of command, reported to the
//   component (a driver stops). Only commands that decoded and came from the
//   controller feed it; a command SC ends when control changes hands.
// - SCs end on Terminate, when their requester is gone, and at shutdown.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "jaus/core/header.hpp"
#include "jaus/messages/core_messages.hpp"
#include "jaus/runtime/environment.hpp"
#include "jaus/runtime/repeat_limiter.hpp"

namespace jaus::rt {

struct ServiceConnectionLimits {
  double max_rate_hz = 1092;         // confirmed rate is at most this
  std::size_t max_connections = 64;  // beyond this, Create is refused (response 4)
  // Reports a second of all inform SCs together: a new one is confirmed at
  // most at what is left, and refused (response 4) when that is below the
  // RA's slowest rate. 64 connections at 1092 Hz would be 70,000 reports a
  // second, most of them for spoofed requesters in a flood.
  double max_total_rate_hz = 4000;
  // A command SC is lost after this many periods without its command...
  double deadman_periods = 3;
  // ...never sooner than this (jitter)...
  Duration deadman_minimum = std::chrono::milliseconds(200);
  // ...and never later than this: at the RA's slowest rate (one a minute),
  // three periods would leave a vehicle on its last command for 3 minutes.
  Duration deadman_maximum = std::chrono::seconds(1);
  // Inform SCs of a report code that one requesting node (subsystem and node:
  // its components together) may hold, by code; beyond, Create is refused
  // (response 4). A code not listed has no cap of its own (Report Image: the
  // visual sensor's, each an image stream).
  std::map<std::uint16_t, std::size_t> max_per_requester_node;
};

struct ServiceConnectionCounters {
  std::uint64_t created = 0;
  std::uint64_t refused = 0;
  std::uint64_t terminated = 0;
  std::uint64_t reports_sent = 0;
  std::uint64_t commands_lost = 0;
};

class ServiceConnectionProvider {
 public:
  // Writes the payload of a report for the given presence mask into
  // `payload` (the provider's buffer, resized to it); false: nothing to send
  // this period.
  using Producer = std::function<bool(std::uint32_t presence_mask, std::vector<std::uint8_t>& payload)>;
  // Sends one SC message (header prepared by the provider: SC flag, sequence).
  using Send = std::function<void(Header header, std::span<const std::uint8_t> payload)>;
  // Asks the component whether `who` may command it with `code` (command SCs).
  using MayCommand = std::function<bool(const Address& who, std::uint16_t code)>;
  using CommandLost = std::function<void(const Address& commander, std::uint16_t code)>;

  ServiceConnectionProvider(Environment& env, Address self, ServiceConnectionLimits limits, Send send,
                            MayCommand may_command, CommandLost command_lost);
  ~ServiceConnectionProvider();

  // Reports this component can send on inform SCs, with the fields it has
  // and the fastest rate its source updates (0: only the limits' maximum).
  void provide(std::uint16_t report_code, std::uint32_t available_presence, Producer producer,
               double max_rate_hz = 0);
  // Commands this component accepts on command SCs.
  void accept_commands(std::uint16_t command_code) { command_codes_.push_back(command_code); }

  void on_create(const Header& h, const msg::CreateServiceConnection& m);
  // Answers a Create the component refuses before the provider sees it (a
  // sender the node could not record, an observer asking for a command SC):
  // Confirm Service Connection with `response`, counted as refused; nothing kept.
  void refuse(const Header& h, const msg::CreateServiceConnection& m, std::uint8_t response);
  // Whether `code` is a command this component accepts on command SCs.
  bool accepts_command(std::uint16_t code) const;
  void on_activate(const Header& h, const msg::ActivateServiceConnection& m);
  void on_suspend(const Header& h, const msg::SuspendServiceConnection& m);
  void on_terminate(const Header& h, const msg::TerminateServiceConnection& m);
  // A command from the controller that decoded and executed: feeds the
  // deadman of its command SC.
  void on_command(const Header& h);
  // Control changed hands: command SCs of anyone but `controller` (none:
  // nobody controls) end; a new controller announces its own.
  void end_commands_not_from(const std::optional<Address>& controller, std::string_view why);

  // The requester is gone (liveness) or the component shuts down.
  // Ends every connection whose requester `requester` covers (Address::covers).
  void end_all_from(const Address& requester, std::string_view why);
  void end_all(std::string_view why);

  std::size_t active() const { return connections_.size(); }
  // Whether some connection's requester lies under `where` (Address::covers).
  bool has_requester_under(const Address& where) const;
  // Report code -> available presence vector of everything provided.
  std::map<std::uint16_t, std::uint32_t> provided() const {
    std::map<std::uint16_t, std::uint32_t> out;
    for (const auto& [code, p] : provided_) out[code] = p.available;
    return out;
  }
  const ServiceConnectionCounters& counters() const { return counters_; }

 private:
  struct Key {
    Address requester;
    std::uint16_t code;
    std::uint8_t instance;
    auto operator<=>(const Key&) const = default;
  };
  struct Connection {
    bool command = false;
    bool active = true;
    std::uint32_t presence = 0;  // requested AND available
    double rate_hz = 0;
    Duration period{};
    TimePoint start{};
    std::uint64_t sent = 0;      // reports sent: next ideal time is start + (sent + 1) * period
    std::uint16_t sequence = 0;
    TimePoint last_command{};
    bool command_lost = false;
    TimerId timer = kNoTimer;
  };
  struct Provided {
    std::uint32_t available = 0;
    Producer produce;
    double max_rate_hz = 0;
  };

  void confirm(const Header& h, std::uint16_t code, std::uint8_t instance, double rate, std::uint8_t response);
  std::uint8_t instance_for(std::uint16_t code, std::uint32_t presence, bool command, const Address& requester);
  void schedule(const Key& key, Connection& c);
  Duration deadman_limit(const Connection& c) const;
  void fire(const Key& key);
  void stop(std::map<Key, Connection>::iterator it, std::string_view why);
  void log(LogLevel level, const std::string& text) const;

  Environment& env_;
  Address self_;
  ServiceConnectionLimits limits_;
  Send send_;
  MayCommand may_command_;
  CommandLost command_lost_;
  std::map<std::uint16_t, Provided> provided_;
  std::vector<std::uint16_t> command_codes_;
  std::map<Key, Connection> connections_;
  std::vector<std::uint8_t> report_buffer_;  // every report's payload, written in place
  ServiceConnectionCounters counters_;
  RepeatedLines lines_;  // a create/terminate loop is a few lines and a count
};

}  // namespace jaus::rt
