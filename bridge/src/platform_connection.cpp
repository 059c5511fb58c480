#include "jaus/bridge/platform_connection.hpp"

namespace jaus::bridge {

PlatformConnection::PlatformConnection(clearpath::Client& client, const rt::Clock& clock, rt::LogFn log)
    : client_(client), clock_(clock), log_(log ? std::move(log) : rt::silent_log()) {
  client_.on_data([this](const clearpath::Envelope& e) { data(e); });
  client_.on_state([this](clearpath::ConnectionState s) { state(s); });
  client_.on_problem([this](const Error& error) { problem(error); });
}

PlatformConnection::~PlatformConnection() {
  client_.on_data({});
  client_.on_state({});
  client_.on_problem({});
}

void PlatformConnection::on_data(std::uint16_t data_type, DataHandler handler) {
  data_handlers_[data_type].push_back(std::move(handler));
}

void PlatformConnection::on_alive(AliveHandler handler) { alive_handlers_.push_back(std::move(handler)); }

void PlatformConnection::data(const clearpath::Envelope& envelope) {
  ++data_received_;
  // Data is only ever delivered on a link that is up: hearing it is being alive.
  if (!alive_) set_alive(true);
  const auto it = data_handlers_.find(envelope.header.type);
  if (it == data_handlers_.end()) return;
  for (const auto& handler : it->second) handler(envelope);
}

void PlatformConnection::state(clearpath::ConnectionState s) {
  if (s == clearpath::ConnectionState::down || s == clearpath::ConnectionState::connecting) {
    // Logged once per loss: while it stays lost (a platform that still does not
    // hear us goes down again after every reconnect) alive_ stays false.
    if (alive_) {
      const auto& why = client_.down_reason();
      log_(rt::LogLevel::warn, "Clearpath platform: " + (s == clearpath::ConnectionState::down && !why.empty()
                                                              ? why
                                                              : "link " + std::string(clearpath::to_string(s))));
    }
    set_alive(false);
  }
}

// Bad input from the platform: never acted on (the client drops it and counts
// it), said in the log with where and why.
void PlatformConnection::problem(const Error& error) {
  std::string note;
  if (problem_lines_.admit(clock_.now(), note))
    log_(rt::LogLevel::warn, "Clearpath platform: input passed over: " + error.message() + note);
}

void PlatformConnection::set_alive(bool alive) {
  if (alive == alive_) return;
  alive_ = alive;
  if (alive) log_(rt::LogLevel::info, "Clearpath platform: link up, data arriving");
  for (const auto& handler : alive_handlers_) handler(alive);
}

}  // namespace jaus::bridge
