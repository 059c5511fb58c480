#include "stdin_lines.hpp"

#include <unistd.h>

#include <csignal>
#include <istream>

namespace jaus::clearpath::sim {

StdinLines::StdinLines(boost::asio::io_context& io, LineHandler on_line) : in_(io), on_line_(std::move(on_line)) {}

bool StdinLines::start() {
  // Started in the background of a shell (`clearpath-sim ... &`), reading the
  // terminal would stop the whole simulator (SIGTTIN); ignored, the read fails
  // with EIO instead and only the reading stops.
  std::signal(SIGTTIN, SIG_IGN);
  // A duplicate, so closing the descriptor at exit leaves fd 0 alone.
  const int fd = ::dup(STDIN_FILENO);
  if (fd < 0) return false;
  boost::system::error_code ec;
  // /dev/null and regular files cannot be polled; Asio then reads them directly.
  in_.assign(fd, ec);
  if (ec) {
    ::close(fd);
    return false;
  }
  read_next();
  return true;
}

void StdinLines::read_next() {
  boost::asio::async_read_until(in_, buffer_, '\n', [this](const boost::system::error_code& ec, std::size_t) {
    if (ec) {
      // End of input: a last line without a newline still counts.
      if (ec == boost::asio::error::eof && buffer_.size() > 0) {
        std::istream in(&buffer_);
        std::string last;
        std::getline(in, last);
        on_line_(last);
      }
      return;  // EOF or error: stop reading, keep serving
    }
    std::istream in(&buffer_);
    std::string line;
    std::getline(in, line);
    on_line_(line);
    read_next();
  });
}

}  // namespace jaus::clearpath::sim
