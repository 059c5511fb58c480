#include "jaus/components/image_directory.hpp"

#include <algorithm>
#include <fstream>
#include <iterator>
#include <system_error>

#include "jaus/components/image_codec.hpp"

namespace jaus::components {

namespace {

namespace fs = std::filesystem;

// At most this much of one file: a Report Image (camera ID, format, file) is at most 1 MiB.
constexpr std::uintmax_t kMaxFileSize = 1024 * 1024 - 2;

Error io_error(const std::string& text) { return make_error(ErrorCode::io, text); }

std::vector<std::uint8_t> read_head(const fs::path& file, std::size_t bytes) {
  std::ifstream in(file, std::ios::binary);
  std::vector<std::uint8_t> head(bytes);
  in.read(reinterpret_cast<char*>(head.data()), static_cast<std::streamsize>(bytes));
  head.resize(in ? bytes : static_cast<std::size_t>(std::max<std::streamsize>(in.gcount(), 0)));
  return head;
}

}  // namespace

Expected<void> ImageDirectory::scan() {
  std::error_code ec;
  fs::directory_iterator it(path_, ec);
  if (ec) return unexpected(io_error("image directory " + path_ + ": " + ec.message()));
  std::vector<fs::path> found;
  for (const fs::directory_iterator end; it != end; it.increment(ec)) {
    if (ec) return unexpected(io_error("image directory " + path_ + ": " + ec.message()));
    std::error_code type_ec;
    if (!it->is_regular_file(type_ec) || type_ec) continue;
    if (sniff_image_format(read_head(it->path(), 8))) found.push_back(it->path());
  }
  std::sort(found.begin(), found.end());
  files_ = std::move(found);
  return {};
}

const std::vector<std::filesystem::path>& ImageDirectory::files() {
  if (files_.empty()) (void)scan();
  return files_;
}

Expected<Image> ImageDirectory::frame(std::uint64_t frame) {
  if (files_.empty()) {
    if (auto scanned = scan(); !scanned) return unexpected(scanned.error());
    if (files_.empty()) return unexpected(io_error("image directory " + path_ + " has no PNG or JPEG file"));
  }
  const fs::path file = files_[frame % files_.size()];
  std::error_code ec;
  const std::uintmax_t size = fs::file_size(file, ec);
  if (ec) {
    files_.clear();  // the directory changed: read it again next time
    return unexpected(io_error(file.string() + ": " + ec.message()));
  }
  if (size > kMaxFileSize)
    return unexpected(
        io_error(file.string() + ": " + std::to_string(size) + " bytes, too large for a Report Image (1 MiB)"));
  std::ifstream in(file, std::ios::binary);
  std::vector<std::uint8_t> data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (!in.good() && !in.eof()) return unexpected(io_error(file.string() + ": cannot be read"));
  const auto format = sniff_image_format(data);
  if (!format) return unexpected(io_error(file.string() + " is no longer a PNG or JPEG file"));
  Image image;
  image.format = *format;
  if (const auto declared = encoded_image_size(data)) {
    image.width = declared->width;
    image.height = declared->height;
  }
  image.data = std::move(data);
  return image;
}

}  // namespace jaus::components
