// The camera's JPEG quality on a slow link (jpeg_quality.hpp), and that the
// simulated camera's frames really shrink with it.
#include "jaus/components/jpeg_quality.hpp"

#include <gtest/gtest.h>

#include "jaus/components/image_codec.hpp"
#include "jaus/components/test_pattern.hpp"

namespace jaus::components {
namespace {

TEST(JpegQuality, WithoutALinkRateTheDefaultQuality) {
  EXPECT_EQ(next_jpeg_quality(40, 100'000, 0), kDefaultJpegQuality);
  EXPECT_EQ(frame_bytes_for(0), SIZE_MAX);
}

TEST(JpegQuality, StepsDownWhileFramesAreOverATenthOfASecondOfTheLinkAndBackUpWellUnder) {
  // 256 kbit/s: 3,200 bytes a frame at most.
  EXPECT_EQ(frame_bytes_for(256'000), 3200u);
  EXPECT_EQ(next_jpeg_quality(85, 9000, 256'000), 64);   // a quarter off
  EXPECT_EQ(next_jpeg_quality(16, 9000, 256'000), 11);   // at least 5 off
  EXPECT_EQ(next_jpeg_quality(12, 9000, 256'000), kLeastJpegQuality);
  EXPECT_EQ(next_jpeg_quality(40, 2500, 256'000), 40);   // within: kept
  EXPECT_EQ(next_jpeg_quality(40, 1500, 256'000), 45);   // well under: up
  EXPECT_EQ(next_jpeg_quality(83, 100, 256'000), kDefaultJpegQuality);
}

TEST(JpegQuality, TheTestPatternComesUnderTheSizeForA256KbitRadio) {
  const auto image = test_pattern(320, 240, 7);
  int quality = kDefaultJpegQuality;
  std::size_t size = 0;
  for (int frame = 0; frame < 20; ++frame) {
    auto jpeg = encode_image(image, image_format::kJpeg, quality);
    ASSERT_TRUE(jpeg);
    size = jpeg->data.size();
    quality = next_jpeg_quality(quality, size, 256'000);
  }
  EXPECT_LE(size, frame_bytes_for(256'000));
  EXPECT_LT(quality, kDefaultJpegQuality);
}

}  // namespace
}  // namespace jaus::components
