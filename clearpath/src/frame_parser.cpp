#include "jaus/clearpath/frame_parser.hpp"

#include <algorithm>
#include <cstdio>


namespace jaus::clearpath {

std::string_view to_string(RejectReason reason) {
  switch (reason) {
    case RejectReason::garbage: return "garbage before start byte";
    case RejectReason::bad_length: return "bad length";
    case RejectReason::oversize: return "oversize frame";
    case RejectReason::missing_stx: return "missing STX";
    case RejectReason::bad_crc: return "bad CRC";
    case RejectReason::truncated: return "truncated frame";
  }
  return "unknown";
}

Error RejectedBytes::to_error() const {
  Error error{ErrorCode::bad_frame, static_cast<std::size_t>(stream_offset), {}, std::string(to_string(reason))};
  char buf[96];
  switch (reason) {
    case RejectReason::garbage:
      error.detail += ", " + std::to_string(length) + " bytes skipped";
      break;
    case RejectReason::bad_length:
      error.field = "length";
      break;
    case RejectReason::missing_stx:
      error.field = "stx";
      break;
    case RejectReason::bad_crc:
      error.field = "crc";
      std::snprintf(buf, sizeof buf, ", type 0x%04X, expected 0x%04X, got 0x%04X", header ? header->type : 0,
                    expected_crc, received_crc);
      error.detail += buf;
      break;
    case RejectReason::oversize:
      error.field = "length";
      error.detail += ", announced " + std::to_string(length) + " bytes";
      break;
    case RejectReason::truncated:
      error.detail += ", announced " + std::to_string(length) + " bytes";
      break;
  }
  return error;
}

FrameParser::FrameParser(std::size_t max_frame_size) : max_frame_size_(max_frame_size) {}

void FrameParser::feed(std::span<const std::uint8_t> bytes) {
  counters_.bytes += bytes.size();
  // Compact before growing so the buffer stays about one frame long.
  if (start_ > 0 && (start_ == buffer_.size() || start_ >= 4096)) {
    buffer_.erase(buffer_.begin(), buffer_.begin() + static_cast<std::ptrdiff_t>(start_));
    start_ = 0;
  }
  buffer_.insert(buffer_.end(), bytes.begin(), bytes.end());
}

void FrameParser::reset() {
  start_offset_ += buffer_.size() - start_;
  buffer_.clear();
  start_ = 0;
}

void FrameParser::consume(std::size_t n) {
  start_ += n;
  start_offset_ += n;
}

FrameParser::Candidate FrameParser::check_candidate(std::size_t at, ParseEvent* out) {
  const auto bytes = std::span<const std::uint8_t>(buffer_).subspan(at);
  const auto inspection = inspect_frame(bytes, max_frame_size_);
  const auto reject = [&](RejectReason reason, std::size_t length) {
    if (out != nullptr) *out = RejectedBytes{reason, start_offset_ + (at - start_), length, std::nullopt};
    return Candidate::invalid;
  };
  switch (inspection.check) {
    case FrameCheck::need_more: return Candidate::need_more;
    case FrameCheck::bad_length: return reject(RejectReason::bad_length, 0);
    case FrameCheck::oversize: return reject(RejectReason::oversize, inspection.size);
    case FrameCheck::missing_stx: return reject(RejectReason::missing_stx, inspection.size);
    case FrameCheck::bad_crc:
      if (out != nullptr) {
        // The header was intact: a platform can answer it with a "bad checksum" ACK.
        RejectedBytes e{RejectReason::bad_crc, start_offset_ + (at - start_), inspection.size, inspection.header};
        e.expected_crc = inspection.expected_crc;
        e.received_crc = inspection.received_crc;
        *out = e;
      }
      return Candidate::invalid;
    case FrameCheck::complete:
      break;
  }
  if (out != nullptr)
    *out = Frame{inspection.header, std::vector<std::uint8_t>(bytes.begin() + kFrameHeaderSize,
                                                              bytes.begin() + static_cast<std::ptrdiff_t>(inspection.size - 2))};
  return Candidate::complete;
}

bool FrameParser::complete_frame_at(std::size_t at) const {
  return const_cast<FrameParser*>(this)->check_candidate(at, nullptr) == Candidate::complete;
}

std::optional<ParseEvent> FrameParser::poll() {
  if (start_ >= buffer_.size()) return std::nullopt;
  const auto first = buffer_.begin() + static_cast<std::ptrdiff_t>(start_);
  if (*first != kStartOfHeader) {
    const auto soh = std::find(first, buffer_.end(), kStartOfHeader);
    const auto skipped = static_cast<std::size_t>(soh - first);
    RejectedBytes e{RejectReason::garbage, start_offset_, skipped, std::nullopt};
    counters_.garbage_bytes += skipped;
    consume(skipped);
    return e;
  }

  ParseEvent event;
  switch (check_candidate(start_, &event)) {
    case Candidate::complete: {
      const auto& frame = std::get<Frame>(event);
      consume(frame.payload.size() + kFrameOverhead);
      ++counters_.frames;
      return event;
    }
    case Candidate::invalid: {
      switch (std::get<RejectedBytes>(event).reason) {
        case RejectReason::bad_length: ++counters_.bad_length; break;
        case RejectReason::oversize: ++counters_.oversize; break;
        case RejectReason::missing_stx: ++counters_.missing_stx; break;
        case RejectReason::bad_crc: ++counters_.bad_crc; break;
        default: break;
      }
      consume(1);  // resynchronise at the byte after the 0xAA that failed
      return event;
    }
    case Candidate::need_more:
      break;
  }
  // The candidate is incomplete. If a complete frame already sits behind it,
  // the candidate was cut short: drop it rather than wait for more bytes.
  for (std::size_t at = start_ + 1; at < buffer_.size(); ++at) {
    if (buffer_[at] != kStartOfHeader || !complete_frame_at(at)) continue;
    const std::size_t announced = buffer_.size() - start_ >= 2 ? std::size_t{buffer_[start_ + kLengthOffset]} + kLeadBytes : 0;
    RejectedBytes e{RejectReason::truncated, start_offset_, announced, std::nullopt};
    ++counters_.truncated;
    consume(at - start_);
    return e;
  }
  return std::nullopt;
}

}  // namespace jaus::clearpath
