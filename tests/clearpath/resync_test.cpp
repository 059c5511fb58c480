// The incremental parser recovers every valid frame from a stream polluted
// with truncated frames, garbage and false headers, fed in arbitrary chunks.
#include <gtest/gtest.h>

#include <random>

#include "jaus/clearpath/codec.hpp"
#include "jaus/clearpath/frame_parser.hpp"
#include "random_message.hpp"

namespace cp = jaus::clearpath;

namespace {

std::vector<std::uint8_t> frame_of(const cp::AnyMessage& m, std::uint32_t ts, std::uint16_t type) {
  return *cp::encode(cp::Envelope{{0, ts, 0, type}, m});
}

std::vector<cp::Frame> drain(cp::FrameParser& parser, std::vector<cp::RejectedBytes>* errors = nullptr) {
  std::vector<cp::Frame> frames;
  while (auto event = parser.poll()) {
    if (auto* f = std::get_if<cp::Frame>(&*event)) frames.push_back(std::move(*f));
    else if (errors != nullptr) errors->push_back(std::get<cp::RejectedBytes>(*event));
  }
  return frames;
}

}  // namespace

TEST(ClearpathParser, RecoversAllFramesFromAPollutedStream) {
  std::mt19937 rng(12345);
  const auto catalogue = cp::message_catalogue();
  constexpr int kFrames = 400;

  std::vector<std::vector<std::uint8_t>> valid;
  std::vector<std::uint8_t> stream;
  for (int i = 0; i < kFrames; ++i) {
    const auto& info = catalogue[rng() % catalogue.size()];
    cp::AnyMessage m = *cp::make_message(info.type);
    cp::testing::randomize(m, rng);
    valid.push_back(frame_of(m, static_cast<std::uint32_t>(i), info.type));

    switch (rng() % 4) {
      case 0: {  // truncated copy of a real frame
        const auto& v = valid.back();
        const std::size_t cut = 1 + rng() % (v.size() - 1);
        stream.insert(stream.end(), v.begin(), v.begin() + static_cast<std::ptrdiff_t>(cut));
        break;
      }
      case 1: {  // garbage, with start bytes in it
        const std::size_t n = 1 + rng() % 40;
        for (std::size_t k = 0; k < n; ++k) stream.push_back(rng() % 5 == 0 ? 0xAA : static_cast<std::uint8_t>(rng()));
        break;
      }
      case 2: {  // false header: valid length pair and STX, then junk
        const auto length = static_cast<std::uint8_t>(11 + rng() % 200);
        stream.insert(stream.end(), {0xAA, length, static_cast<std::uint8_t>(~length), 0, 1, 2, 3, 4, 0, 4, 2, 0x55});
        const std::size_t junk = rng() % 30;
        for (std::size_t k = 0; k < junk; ++k) stream.push_back(static_cast<std::uint8_t>(rng()));
        break;
      }
      default:
        break;  // frames back to back
    }
    stream.insert(stream.end(), valid.back().begin(), valid.back().end());
  }

  cp::FrameParser parser;
  std::vector<cp::Frame> frames;
  std::size_t at = 0;
  while (at < stream.size()) {
    const std::size_t chunk = std::min<std::size_t>(1 + rng() % 64, stream.size() - at);
    parser.feed(std::span(stream).subspan(at, chunk));
    at += chunk;
    auto got = drain(parser);
    frames.insert(frames.end(), got.begin(), got.end());
  }

  ASSERT_EQ(frames.size(), valid.size());
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const auto expected = cp::decode_frame(valid[i]);
    ASSERT_TRUE(expected);
    EXPECT_EQ(frames[i], *expected) << "frame " << i;
  }
  EXPECT_GT(parser.counters().errors(), 0u);
  EXPECT_EQ(parser.counters().frames, valid.size());
}

TEST(ClearpathParser, ByteByByteFeeding) {
  cp::AnyMessage m{cp::SetVelocity{}};
  const auto bytes = frame_of(m, 5, 0x0204);
  cp::FrameParser parser;
  for (std::size_t i = 0; i + 1 < bytes.size(); ++i) {
    parser.feed(std::span(bytes).subspan(i, 1));
    EXPECT_FALSE(parser.poll()) << "frame reported before its last byte";
  }
  parser.feed(std::span(bytes).subspan(bytes.size() - 1));
  const auto event = parser.poll();
  ASSERT_TRUE(event);
  EXPECT_TRUE(std::holds_alternative<cp::Frame>(*event));
}

TEST(ClearpathParser, BadCrcIsCountedAndReportsTheHeader) {
  auto bad = frame_of(cp::AnyMessage{cp::SetVelocity{}}, 77, 0x0204);
  bad[13] ^= 0x01;
  const auto good = frame_of(cp::AnyMessage{cp::SetMaxSpeed{}}, 78, 0x0210);
  cp::FrameParser parser;
  parser.feed(bad);
  parser.feed(good);
  std::vector<cp::RejectedBytes> errors;
  const auto frames = drain(parser, &errors);
  ASSERT_EQ(frames.size(), 1u);
  EXPECT_EQ(frames[0].header.type, 0x0210);
  ASSERT_FALSE(errors.empty());
  EXPECT_EQ(errors[0].reason, cp::RejectReason::bad_crc);
  ASSERT_TRUE(errors[0].header);
  EXPECT_EQ(errors[0].header->type, 0x0204);
  EXPECT_EQ(errors[0].header->timestamp, 77u);
  EXPECT_EQ(errors[0].stream_offset, 0u);
  EXPECT_EQ(parser.counters().bad_crc, 1u);
  const auto error = errors[0].to_error();
  EXPECT_EQ(error.code, jaus::ErrorCode::bad_frame);
  EXPECT_EQ(error.field, "crc");
  EXPECT_EQ(error.message().rfind("offset 0, field 'crc': bad frame (bad CRC, type 0x0204", 0), 0u) << error.message();
}

TEST(ClearpathParser, TruncatedFrameDoesNotHoldBackTheNextOne) {
  // A frame cut short, then a complete frame: the complete one is delivered
  // at once, without waiting for bytes that would complete the first.
  const auto first = frame_of(cp::AnyMessage{cp::PlatformName{std::string(60, 'n'), false}}, 1, 0x8002);
  const auto second = frame_of(cp::AnyMessage{cp::SetVelocity{}}, 2, 0x0204);
  cp::FrameParser parser;
  parser.feed(std::span(first).first(20));
  parser.feed(second);
  std::vector<cp::RejectedBytes> errors;
  const auto frames = drain(parser, &errors);
  ASSERT_EQ(frames.size(), 1u);
  EXPECT_EQ(frames[0].header.timestamp, 2u);
  EXPECT_EQ(parser.counters().truncated, 1u);
}

TEST(ClearpathParser, LengthAndStxErrorsAreCounted) {
  cp::FrameParser parser;
  const std::vector<std::uint8_t> bad_pair = {0xAA, 0x10, 0x10};
  const std::vector<std::uint8_t> short_len = {0xAA, 0x05, 0xFA};
  std::vector<std::uint8_t> no_stx = frame_of(cp::AnyMessage{cp::SetVelocity{}}, 1, 0x0204);
  no_stx[11] = 0x54;
  parser.feed(bad_pair);
  parser.feed(short_len);
  parser.feed(no_stx);
  drain(parser);
  EXPECT_EQ(parser.counters().bad_length, 2u);
  EXPECT_EQ(parser.counters().missing_stx, 1u);
  EXPECT_EQ(parser.counters().frames, 0u);
}

TEST(ClearpathParser, OversizeAgainstAConfiguredLimit) {
  cp::FrameParser parser(64);
  cp::PlatformInfo info;
  info.model = std::string(100, 'x');
  parser.feed(frame_of(cp::AnyMessage{info}, 1, 0x8001));
  drain(parser);
  EXPECT_EQ(parser.counters().oversize, 1u);
  EXPECT_EQ(parser.counters().frames, 0u);
}
