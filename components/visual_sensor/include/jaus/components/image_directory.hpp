// A directory of still images played as video: its PNG and JPEG files (by
// their magic bytes, whatever their names), in name order, one per frame
// period, in a loop. Files are served as they are (their own format and
// size). The listing is read on first use and again whenever it was empty
// or unreadable, so a directory filled later works; each frame reads its file.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "jaus/base/expected.hpp"
#include "jaus/components/camera.hpp"

namespace jaus::components {

class ImageDirectory {
 public:
  explicit ImageDirectory(std::string path) : path_(std::move(path)) {}

  // The image of frame number `frame` (file frame mod count). Never throws.
  Expected<Image> frame(std::uint64_t frame);
  // The files it plays, in order (read now if not yet).
  const std::vector<std::filesystem::path>& files();

 private:
  Expected<void> scan();

  std::string path_;
  std::vector<std::filesystem::path> files_;
};

}  // namespace jaus::components
