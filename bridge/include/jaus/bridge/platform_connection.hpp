// One Clearpath platform as every bridge backend on it sees it. A
// clearpath::Client has one data callback and one state callback; the
// vehicle, the camera mounts and the arm share the platform, so this fans
// both out, by data type and to every listener.
//
// Alive: the link is up AND the platform has been heard from since it came
// up (a UDP socket is "connected" with nobody behind it). The client marks
// the link down after ClientConfig::data_silence without data, so a backend
// that subscribes to something always learns of a silent platform.
//
// Input the client passes over (a frame with a bad CRC, one that does not
// decode) is logged here, where and why, a few lines per window and then a
// count: a noisy serial line is a handful of lines, not thousands.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "jaus/base/log.hpp"
#include "jaus/base/time.hpp"
#include "jaus/clearpath/client.hpp"
#include "jaus/runtime/repeat_limiter.hpp"

namespace jaus::bridge {

class PlatformConnection {
 public:
  static constexpr int kProblemLinesPerWindow = 5;

  using DataHandler = std::function<void(const clearpath::Envelope&)>;
  using AliveHandler = std::function<void(bool alive)>;

  // Takes over the client's data, state and problem callbacks until destroyed.
  PlatformConnection(clearpath::Client& client, const rt::Clock& clock, rt::LogFn log = {});
  ~PlatformConnection();
  PlatformConnection(const PlatformConnection&) = delete;
  PlatformConnection& operator=(const PlatformConnection&) = delete;

  clearpath::Client& client() { return client_; }
  const rt::Clock& clock() const { return clock_; }
  void log(rt::LogLevel level, const std::string& text) const { log_(level, text); }

  // Every data message of `data_type` (0x8000-0xBFFF), in arrival order.
  void on_data(std::uint16_t data_type, DataHandler handler);
  // Every change of alive(); each listener is called in registration order.
  void on_alive(AliveHandler handler);
  bool alive() const { return alive_; }
  // How many data messages arrived, of any type (tests, status).
  std::uint64_t data_received() const { return data_received_; }

 private:
  void data(const clearpath::Envelope& envelope);
  void state(clearpath::ConnectionState state);
  void set_alive(bool alive);
  void problem(const Error& error);

  clearpath::Client& client_;
  const rt::Clock& clock_;
  rt::LogFn log_;
  rt::RepeatLimiter problem_lines_{rt::kRepeatedLogWindow, kProblemLinesPerWindow};
  std::map<std::uint16_t, std::vector<DataHandler>> data_handlers_;
  std::vector<AliveHandler> alive_handlers_;
  bool alive_ = false;
  std::uint64_t data_received_ = 0;
};

}  // namespace jaus::bridge
