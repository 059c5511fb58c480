// Lines from standard input, read asynchronously on the io_context. At end of
// input (stdin at /dev/null, a closed pipe) or on a read error it just stops
// reading: the simulator keeps serving.
#pragma once

#include <functional>
#include <string>
#include <utility>  // before Asio: Boost 1.74 awaitable.hpp uses std::exchange without it

#include <boost/asio.hpp>

namespace jaus::clearpath::sim {

class StdinLines {
 public:
  using LineHandler = std::function<void(const std::string&)>;
  StdinLines(boost::asio::io_context& io, LineHandler on_line);

  // Starts reading; false if standard input cannot be read at all (closed).
  bool start();

 private:
  void read_next();

  boost::asio::posix::stream_descriptor in_;
  boost::asio::streambuf buffer_;
  LineHandler on_line_;
};

}  // namespace jaus::clearpath::sim
