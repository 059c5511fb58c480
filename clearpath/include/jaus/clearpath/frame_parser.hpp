// Incremental frame parser: feed it chunks of any size, poll frames and
// counted errors. It resynchronises one byte at a time: after a bad length
// pair, a missing STX or a bad CRC the search restarts at the byte after the
// 0xAA that failed, so a damaged or truncated frame never hides the next one.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <variant>
#include <vector>

#include "jaus/base/error.hpp"
#include "jaus/clearpath/frame.hpp"

namespace jaus::clearpath {

// Why the parser passed over bytes.
enum class RejectReason {
  garbage,      // bytes before a start-of-header (counted once per run)
  bad_length,   // LEN and ~LEN disagree, or LEN < 11
  oversize,     // LEN announces a frame larger than the configured limit
  missing_stx,  // no 0x55 where the header ends
  bad_crc,      // checksum mismatch
  truncated,    // a candidate frame cut short by the start of a complete frame
};

std::string_view to_string(RejectReason reason);

// A parser event, not a failure of the parser: bytes of the stream it passed
// over, where and why, with what a platform needs to answer a damaged frame.
// to_error() is the project's one error for it, for logs and callers that
// report errors.
struct RejectedBytes {
  RejectReason reason{};
  std::uint64_t stream_offset = 0;  // where in the byte stream the candidate started
  std::size_t length = 0;           // bytes dropped (garbage) or the announced frame size
  // Set for bad_crc: the header was intact, so a platform can answer the
  // (type, timestamp) with a "bad checksum" ACK.
  std::optional<FrameHeader> header;
  std::uint16_t expected_crc = 0;
  std::uint16_t received_crc = 0;

  // ErrorCode::bad_frame at the stream offset, the field that failed ("crc",
  // "length", "stx") and the details: "offset 42, field 'crc': bad frame
  // (bad CRC, type 0x0204, expected 0x1234, got 0x4321)".
  Error to_error() const;
};

struct ParserCounters {
  std::uint64_t bytes = 0;
  std::uint64_t frames = 0;
  std::uint64_t garbage_bytes = 0;
  std::uint64_t bad_length = 0;
  std::uint64_t oversize = 0;
  std::uint64_t missing_stx = 0;
  std::uint64_t bad_crc = 0;
  std::uint64_t truncated = 0;
  std::uint64_t errors() const { return bad_length + oversize + missing_stx + bad_crc + truncated; }
};

using ParseEvent = std::variant<Frame, RejectedBytes>;

class FrameParser {
 public:
  explicit FrameParser(std::size_t max_frame_size = kMaxFrameSize);

  void feed(std::span<const std::uint8_t> bytes);
  // Next frame or rejected bytes, or nullopt when more bytes are needed.
  std::optional<ParseEvent> poll();
  // Bytes buffered but not yet resolved.
  std::size_t pending() const { return buffer_.size() - start_; }
  const ParserCounters& counters() const { return counters_; }
  // Forget buffered bytes (e.g. after a reconnect).
  void reset();

 private:
  enum class Candidate { complete, need_more, invalid };
  Candidate check_candidate(std::size_t at, ParseEvent* out);
  bool complete_frame_at(std::size_t at) const;
  void consume(std::size_t n);

  std::size_t max_frame_size_;
  std::vector<std::uint8_t> buffer_;
  std::size_t start_ = 0;            // first unresolved byte in buffer_
  std::uint64_t start_offset_ = 0;   // stream offset of buffer_[start_]
  ParserCounters counters_;
};

}  // namespace jaus::clearpath
