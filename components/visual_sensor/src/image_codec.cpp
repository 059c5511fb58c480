#include "jaus/components/image_codec.hpp"

// libjpeg needs FILE and size_t declared before its header.
#include <algorithm>
#include <csetjmp>
#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>

#include <jpeglib.h>
#include <png.h>

namespace jaus::components {

namespace {

Error codec_error(std::string what) { return make_error(ErrorCode::bad_value, std::move(what)); }

bool well_formed(const RgbImage& image) {
  return image.width > 0 && image.height > 0 &&
         image.rgb.size() == static_cast<std::size_t>(image.width) * image.height * 3;
}

// libjpeg reports errors through error_exit, which must not return: it jumps
// back to jpeg_compress_rgb. Everything libjpeg touches lives in the job, in
// the caller's frame, so nothing is indeterminate after the jump, and no
// object with a destructor lives in the frame that calls setjmp.
struct JpegJob {
  jpeg_compress_struct info;
  jpeg_error_mgr errors;
  std::jmp_buf jump;
  char message[JMSG_LENGTH_MAX];
  unsigned char* out;  // malloc'd by jpeg_mem_dest, grown as it writes
  unsigned long size;
};

[[noreturn]] void jpeg_fail(j_common_ptr info) {
  auto* job = reinterpret_cast<JpegJob*>(reinterpret_cast<char*>(info) - offsetof(JpegJob, info));
  (*info->err->format_message)(info, job->message);
  std::longjmp(job->jump, 1);
}

// True when job->out holds the JPEG file (job->size bytes); otherwise the
// message says why, and nothing is left allocated.
bool jpeg_compress_rgb(const RgbImage& image, int quality, JpegJob* job) {
  job->info.err = jpeg_std_error(&job->errors);
  job->errors.error_exit = jpeg_fail;
  job->out = nullptr;
  job->size = 0;
  if (setjmp(job->jump) != 0) {
    jpeg_destroy_compress(&job->info);
    std::free(job->out);
    job->out = nullptr;
    return false;
  }
  jpeg_create_compress(&job->info);
  jpeg_mem_dest(&job->info, &job->out, &job->size);
  job->info.image_width = image.width;
  job->info.image_height = image.height;
  job->info.input_components = 3;
  job->info.in_color_space = JCS_RGB;
  jpeg_set_defaults(&job->info);
  jpeg_set_quality(&job->info, quality, TRUE);
  jpeg_start_compress(&job->info, TRUE);
  const std::size_t stride = static_cast<std::size_t>(image.width) * 3;
  while (job->info.next_scanline < job->info.image_height) {
    // libjpeg takes non-const rows; it only reads them.
    JSAMPROW row = const_cast<JSAMPROW>(image.rgb.data() + job->info.next_scanline * stride);
    jpeg_write_scanlines(&job->info, &row, 1);
  }
  jpeg_finish_compress(&job->info);
  jpeg_destroy_compress(&job->info);
  return true;
}

std::uint16_t big_endian16(std::span<const std::uint8_t> b, std::size_t at) {
  return static_cast<std::uint16_t>(b[at] << 8 | b[at + 1]);
}

}  // namespace

Expected<std::vector<std::uint8_t>> encode_png(const RgbImage& image) {
  if (!well_formed(image)) return unexpected(codec_error("PNG: bad image size"));
  png_image png;
  std::memset(&png, 0, sizeof png);
  png.version = PNG_IMAGE_VERSION;
  png.width = image.width;
  png.height = image.height;
  png.format = PNG_FORMAT_RGB;
  png_alloc_size_t size = 0;
  if (!png_image_write_to_memory(&png, nullptr, &size, 0, image.rgb.data(), 0, nullptr))
    return unexpected(codec_error(std::string("PNG: ") + png.message));
  std::vector<std::uint8_t> out(size);
  if (!png_image_write_to_memory(&png, out.data(), &size, 0, image.rgb.data(), 0, nullptr))
    return unexpected(codec_error(std::string("PNG: ") + png.message));
  out.resize(size);
  return out;
}

Expected<std::vector<std::uint8_t>> encode_jpeg(const RgbImage& image, int quality) {
  if (!well_formed(image)) return unexpected(codec_error("JPEG: bad image size"));
  auto job = std::make_unique<JpegJob>();
  if (!jpeg_compress_rgb(image, std::clamp(quality, 1, 100), job.get()))
    return unexpected(codec_error(std::string("JPEG: ") + job->message));
  std::vector<std::uint8_t> out(job->out, job->out + job->size);
  std::free(job->out);
  return out;
}

Expected<Image> encode_image(const RgbImage& image, std::uint8_t format, int jpeg_quality) {
  Expected<std::vector<std::uint8_t>> data = unexpected(codec_error("unsupported"));
  if (format == image_format::kPng)
    data = encode_png(image);
  else if (format == image_format::kJpeg)
    data = encode_jpeg(image, jpeg_quality);
  else
    return unexpected(make_error(ErrorCode::invalid_argument,
                                 "image format " + std::to_string(format) + " is not produced (7 JPEG, 11 PNG)"));
  if (!data) return unexpected(data.error());
  return Image{format, image.width, image.height, std::move(*data)};
}

std::optional<std::uint8_t> sniff_image_format(std::span<const std::uint8_t> b) {
  static constexpr std::uint8_t kPngMagic[8] = {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A};
  if (b.size() >= 8 && std::memcmp(b.data(), kPngMagic, 8) == 0) return image_format::kPng;
  if (b.size() >= 3 && b[0] == 0xFF && b[1] == 0xD8 && b[2] == 0xFF) return image_format::kJpeg;
  return std::nullopt;
}

std::optional<ImageSize> encoded_image_size(std::span<const std::uint8_t> b) {
  const auto format = sniff_image_format(b);
  if (format == image_format::kPng) {
    // Signature, IHDR length and type, then u32 width and u32 height.
    if (b.size() < 24 || std::memcmp(b.data() + 12, "IHDR", 4) != 0) return std::nullopt;
    if (b[16] != 0 || b[17] != 0 || b[20] != 0 || b[21] != 0) return std::nullopt;  // over 65535
    return ImageSize{big_endian16(b, 18), big_endian16(b, 22)};
  }
  if (format == image_format::kJpeg) {
    // Markers after SOI: FF xx, u16 length (including itself); SOFn holds
    // precision u8, height u16, width u16.
    std::size_t at = 2;
    while (at + 4 <= b.size()) {
      if (b[at] != 0xFF) return std::nullopt;
      const std::uint8_t marker = b[at + 1];
      if (marker == 0xFF) {  // fill byte
        ++at;
        continue;
      }
      const std::size_t length = big_endian16(b, at + 2);
      const bool sof = marker >= 0xC0 && marker <= 0xCF && marker != 0xC4 && marker != 0xC8 && marker != 0xCC;
      if (sof) {
        if (at + 9 > b.size()) return std::nullopt;
        return ImageSize{big_endian16(b, at + 7), big_endian16(b, at + 5)};
      }
      if (marker == 0xD9 || marker == 0xDA || length < 2) return std::nullopt;  // no frame header before the scan
      at += 2 + length;
    }
  }
  return std::nullopt;
}

}  // namespace jaus::components
