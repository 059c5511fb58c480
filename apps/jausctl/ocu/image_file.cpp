#include "image_file.hpp"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "jaus/messages/environment_messages.hpp"

namespace jausctl::ocu {

jaus::Expected<std::size_t> save_report_image(const jaus::ocu::Received& report, const std::string& path) {
  if (report.header.command_code != jaus::msg::ReportImage::code)
    return jaus::unexpected(jaus::make_error(jaus::ErrorCode::invalid_argument,
                                             "--save-image needs Report Image (0x4807) reports"));
  jaus::msg::ReportImage image;
  if (auto decoded = jaus::wire::decode_payload_into(report.payload, image, jaus::wire::Dialect::ra, jaus::kHeaderSize);
      !decoded)
    return jaus::unexpected(jaus::make_error(jaus::ErrorCode::malformed, "Report Image from " +
                                                                             report.header.source.to_string() +
                                                                             " does not decode: " + decoded.error().message()));
  const std::string temporary = path + ".part";
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(image.data.data()), static_cast<std::streamsize>(image.data.size()));
    out.close();
    if (!out)
      return jaus::unexpected(
          jaus::make_error(jaus::ErrorCode::io, "cannot write " + temporary + ": " + std::strerror(errno)));
  }
  std::error_code ec;
  std::filesystem::rename(temporary, path, ec);
  if (ec) return jaus::unexpected(jaus::make_error(jaus::ErrorCode::io, "cannot write " + path + ": " + ec.message()));
  return image.data.size();
}

jaus::ocu::Json with_saved_image(jaus::ocu::Json report, std::size_t bytes, const std::string& path) {
  if (report.contains("fields") && report["fields"].contains("data"))
    report["fields"]["data"] = jaus::ocu::Json{{"bytes", bytes}, {"saved_to", path}};
  return report;
}

}  // namespace jausctl::ocu
