// Environment sensor subgroup: 0x0800-0x09FF, 0x2800-0x29FF, 0x4800-0x49FF.
#pragma once

#include "jaus/messages/common.hpp"
#include "jaus/messages/core_messages.hpp"

namespace jaus::msg {

struct CameraIdBody {
  std::uint8_t camera_id = 1;
  bool operator==(const CameraIdBody&) const = default;
  static constexpr auto describe() { return std::make_tuple(wire::field("camera_id", &CameraIdBody::camera_id, Byte{})); }
};

// Set Camera Pose: +-100 % of full scale; mode_indicator bits 0-5 choose rate (1)
// or position (0) for the six axes in order.
inline constexpr auto kCameraPoseMode = wire::bits_of<std::uint8_t>(
    {"x_linear_rate", "y_linear_rate", "z_linear_rate", "x_angular_rate", "y_angular_rate", "z_angular_rate"});

struct CameraPoseCommandBody {
  std::uint8_t camera_id = 1;
  std::uint8_t mode_indicator = 0;
  std::optional<double> x_linear_percent;
  std::optional<double> y_linear_percent;
  std::optional<double> z_linear_percent;
  std::optional<double> x_angular_percent;
  std::optional<double> y_angular_percent;
  std::optional<double> z_angular_percent;
  bool operator==(const CameraPoseCommandBody&) const = default;
  static constexpr auto describe() {
    using B = CameraPoseCommandBody;
    constexpr wire::Scaled<std::int16_t> percent{-100, 100};
    return std::make_tuple(wire::presence_vector<std::uint8_t>(), wire::field("camera_id", &B::camera_id, Byte{}),
                           wire::field("mode_indicator", &B::mode_indicator, kCameraPoseMode),
                           wire::optional(0, "x_linear_percent", &B::x_linear_percent, percent),
                           wire::optional(1, "y_linear_percent", &B::y_linear_percent, percent),
                           wire::optional(2, "z_linear_percent", &B::z_linear_percent, percent),
                           wire::optional(3, "x_angular_percent", &B::x_angular_percent, percent),
                           wire::optional(4, "y_angular_percent", &B::y_angular_percent, percent),
                           wire::optional(5, "z_angular_percent", &B::z_angular_percent, percent));
  }
};

inline constexpr wire::Scaled<std::uint16_t> kFieldOfView{0, kPi};
inline constexpr wire::Scaled<std::uint8_t> kPercentByte{0, 100};

// imagery_control bits: 0 auto focus, 1 auto exposure/iris, 2 image
// stabilisation, 3 white balance, 4 sync flash, 5 red eye, 6 auto shutter,
// 7 auto gain, 8 non-interlaced. audio_control bits: 0 audio, 1 auto gain,
// 2 stereo, 3 directional, 4 front, 5 rear, 6 left, 7 right microphone.
struct CameraCapabilitiesCommandBody {
  std::uint8_t camera_id = 1;
  std::optional<double> horizontal_fov_rad;
  std::optional<double> vertical_fov_rad;
  std::optional<std::uint16_t> horizontal_resolution;
  std::optional<std::uint16_t> vertical_resolution;
  std::optional<double> focus_percent;
  std::optional<double> iris_percent;
  std::optional<double> gain_percent;
  std::optional<std::uint16_t> frame_rate_fps;
  std::optional<std::uint16_t> shutter_inverse_s;  // 500 means 1/500 s
  std::optional<std::uint16_t> imagery_control;
  std::optional<std::uint16_t> audio_control;
  bool operator==(const CameraCapabilitiesCommandBody&) const = default;
  static constexpr auto describe() {
    using B = CameraCapabilitiesCommandBody;
    return std::make_tuple(wire::presence_vector<std::uint16_t>(), wire::field("camera_id", &B::camera_id, Byte{}),
                           wire::optional(0, "horizontal_fov_rad", &B::horizontal_fov_rad, kFieldOfView),
                           wire::optional(1, "vertical_fov_rad", &B::vertical_fov_rad, kFieldOfView),
                           wire::optional(2, "horizontal_resolution", &B::horizontal_resolution, UShort{}),
                           wire::optional(3, "vertical_resolution", &B::vertical_resolution, UShort{}),
                           wire::optional(4, "focus_percent", &B::focus_percent, kPercentByte),
                           wire::optional(5, "iris_percent", &B::iris_percent, kPercentByte),
                           wire::optional(6, "gain_percent", &B::gain_percent, kPercentByte),
                           wire::optional(7, "frame_rate_fps", &B::frame_rate_fps, UShort{}),
                           wire::optional(8, "shutter_inverse_s", &B::shutter_inverse_s, UShort{}),
                           wire::optional(9, "imagery_control", &B::imagery_control, kImageryControl),
                           wire::optional(10, "audio_control", &B::audio_control, kAudioControl));
  }
};

// Audio formats: 1 RAW, 2 PCM, 3 AU, 4 WAV, 5 MID, 6 MP3, 7 MP2, 8 ASF.
// Image formats: 1 MPEG2, 2 MPEG4, 3 MJPEG, 4 NTSC, 5 PAL, 6 TIFF, 7 JPEG,
// 8 GIF, 9 H263, 10 H264, 11 PNG, 12 BMP, 13 RAW, 14 PPM, 15 PGM, 16 PNM.
struct CameraFormatCommandBody {
  std::uint8_t camera_id = 1;
  std::optional<std::uint8_t> audio_format;
  std::optional<std::uint8_t> image_format;
  std::optional<std::uint32_t> format_option;
  bool operator==(const CameraFormatCommandBody&) const = default;
  static constexpr auto describe() {
    using B = CameraFormatCommandBody;
    return std::make_tuple(wire::presence_vector<std::uint8_t>(), wire::field("camera_id", &B::camera_id, Byte{}),
                           wire::optional(0, "audio_format", &B::audio_format, kAudioFormat),
                           wire::optional(1, "image_format", &B::image_format, kImageFormat),
                           wire::optional(2, "format_option", &B::format_option, UInt{}));
  }
};

// A query carrying a presence mask and a camera ID, in that order.
template <std::unsigned_integral T>
struct CameraQueryBody {
  T presence_vector = 0;
  std::uint8_t camera_id = 1;
  bool operator==(const CameraQueryBody&) const = default;
  static constexpr auto describe() {
    return std::make_tuple(wire::field("presence_vector", &CameraQueryBody::presence_vector, wire::Int<T>{}),
                           wire::field("camera_id", &CameraQueryBody::camera_id, Byte{}));
  }
};

struct CameraPoseReportBody {
  std::uint8_t camera_id = 1;
  std::optional<std::string> camera_name;  // up to 15 characters
  std::optional<double> x_origin_m;
  std::optional<double> y_origin_m;
  std::optional<double> z_origin_m;
  std::optional<double> x_axis_direction_cosine_x;
  std::optional<double> x_axis_direction_cosine_y;
  std::optional<double> x_axis_direction_cosine_z;
  std::optional<double> z_axis_direction_cosine_x;
  std::optional<double> z_axis_direction_cosine_y;
  std::optional<double> z_axis_direction_cosine_z;
  bool operator==(const CameraPoseReportBody&) const = default;
  static constexpr auto describe() {
    using B = CameraPoseReportBody;
    constexpr wire::Scaled<std::int16_t> origin{-32.767, 32.767};
    constexpr wire::Scaled<std::int16_t> cosine{-1, 1};
    return std::make_tuple(wire::presence_vector<std::uint16_t>(), wire::field("camera_id", &B::camera_id, Byte{}),
                           wire::optional(0, "camera_name", &B::camera_name, wire::Text<15>{}),
                           wire::optional(1, "x_origin_m", &B::x_origin_m, origin),
                           wire::optional(2, "y_origin_m", &B::y_origin_m, origin),
                           wire::optional(3, "z_origin_m", &B::z_origin_m, origin),
                           wire::optional(4, "x_axis_direction_cosine_x", &B::x_axis_direction_cosine_x, cosine),
                           wire::optional(5, "x_axis_direction_cosine_y", &B::x_axis_direction_cosine_y, cosine),
                           wire::optional(6, "x_axis_direction_cosine_z", &B::x_axis_direction_cosine_z, cosine),
                           wire::optional(7, "z_axis_direction_cosine_x", &B::z_axis_direction_cosine_x, cosine),
                           wire::optional(8, "z_axis_direction_cosine_y", &B::z_axis_direction_cosine_y, cosine),
                           wire::optional(9, "z_axis_direction_cosine_z", &B::z_axis_direction_cosine_z, cosine));
  }
};

struct CameraCountBody {
  std::uint8_t camera_count = 1;
  bool operator==(const CameraCountBody&) const = default;
  static constexpr auto describe() {
    return std::make_tuple(wire::field("camera_count", &CameraCountBody::camera_count, Byte{}));
  }
};

// Report Relative Object Position. The openjaus dialect appends a u16 object
// ID that Part 3 does not define; it is read and written only in that dialect.
struct RelativeObjectPositionBody {
  TimeStamp time_stamp;
  std::optional<double> range_m;
  std::optional<double> range_error_m;
  std::optional<double> bearing_rad;
  std::optional<double> bearing_error_rad;
  std::optional<double> elevation_rad;
  std::optional<double> elevation_error_rad;
  std::optional<std::uint8_t> confidence;  // 0 low .. 255 highest
  std::optional<std::uint16_t> object_id;  // openjaus dialect only
  bool operator==(const RelativeObjectPositionBody&) const = default;
  static constexpr auto describe() {
    using B = RelativeObjectPositionBody;
    constexpr wire::Scaled<std::uint32_t> angle_error{0, kPi};
    return std::make_tuple(wire::presence_vector<std::uint8_t>(),
                           wire::field("time_stamp", &B::time_stamp, wire::Time{}),
                           wire::optional(0, "range_m", &B::range_m, wire::Scaled<std::int32_t>{-10'000, 10'000}),
                           wire::optional(1, "range_error_m", &B::range_error_m, wire::Scaled<std::uint32_t>{0, 1000}),
                           wire::optional(2, "bearing_rad", &B::bearing_rad, kAngleInt),
                           wire::optional(3, "bearing_error_rad", &B::bearing_error_rad, angle_error),
                           wire::optional(4, "elevation_rad", &B::elevation_rad, kAngleInt),
                           wire::optional(5, "elevation_error_rad", &B::elevation_error_rad, angle_error),
                           wire::optional(6, "confidence", &B::confidence, Byte{}),
                           wire::dialect_field(Dialect::openjaus, "object_id", &B::object_id, UShort{}));
  }
};

struct CameraCapabilitiesReportBody {
  std::uint8_t camera_id = 1;
  std::optional<std::string> description;  // up to 50 characters
  std::optional<double> max_horizontal_fov_rad;
  std::optional<double> min_horizontal_fov_rad;
  std::optional<double> max_vertical_fov_rad;
  std::optional<double> min_vertical_fov_rad;
  std::optional<std::uint16_t> max_horizontal_resolution;
  std::optional<std::uint16_t> min_horizontal_resolution;
  std::optional<std::uint16_t> max_vertical_resolution;
  std::optional<std::uint16_t> min_vertical_resolution;
  std::optional<std::uint16_t> min_frame_rate_fps;
  std::optional<std::uint16_t> max_frame_rate_fps;
  std::optional<std::uint16_t> min_shutter_inverse_s;
  std::optional<std::uint16_t> max_shutter_inverse_s;
  std::optional<std::uint16_t> imagery_control;  // bits as in Set Camera Capabilities ("available")
  std::optional<std::uint16_t> audio_control;
  bool operator==(const CameraCapabilitiesReportBody&) const = default;
  static constexpr auto describe() {
    using B = CameraCapabilitiesReportBody;
    return std::make_tuple(wire::presence_vector<std::uint16_t>(), wire::field("camera_id", &B::camera_id, Byte{}),
                           wire::optional(0, "description", &B::description, wire::Text<50>{}),
                           wire::optional(1, "max_horizontal_fov_rad", &B::max_horizontal_fov_rad, kFieldOfView),
                           wire::optional(2, "min_horizontal_fov_rad", &B::min_horizontal_fov_rad, kFieldOfView),
                           wire::optional(3, "max_vertical_fov_rad", &B::max_vertical_fov_rad, kFieldOfView),
                           wire::optional(4, "min_vertical_fov_rad", &B::min_vertical_fov_rad, kFieldOfView),
                           wire::optional(5, "max_horizontal_resolution", &B::max_horizontal_resolution, UShort{}),
                           wire::optional(6, "min_horizontal_resolution", &B::min_horizontal_resolution, UShort{}),
                           wire::optional(7, "max_vertical_resolution", &B::max_vertical_resolution, UShort{}),
                           wire::optional(8, "min_vertical_resolution", &B::min_vertical_resolution, UShort{}),
                           wire::optional(9, "min_frame_rate_fps", &B::min_frame_rate_fps, UShort{}),
                           wire::optional(10, "max_frame_rate_fps", &B::max_frame_rate_fps, UShort{}),
                           wire::optional(11, "min_shutter_inverse_s", &B::min_shutter_inverse_s, UShort{}),
                           wire::optional(12, "max_shutter_inverse_s", &B::max_shutter_inverse_s, UShort{}),
                           wire::optional(13, "imagery_control", &B::imagery_control, kImageryControl),
                           wire::optional(14, "audio_control", &B::audio_control, kAudioControl));
  }
};

struct CameraFormatReportBody {
  std::uint8_t camera_id = 1;
  std::optional<std::uint8_t> audio_format_1;
  std::optional<std::uint8_t> audio_format_2;
  std::optional<std::uint8_t> image_format_1;
  std::optional<std::uint8_t> image_format_2;
  std::optional<std::uint8_t> image_format_3;
  std::optional<std::uint8_t> image_format_4;
  std::optional<std::uint32_t> format_option;
  bool operator==(const CameraFormatReportBody&) const = default;
  static constexpr auto describe() {
    using B = CameraFormatReportBody;
    return std::make_tuple(wire::presence_vector<std::uint8_t>(), wire::field("camera_id", &B::camera_id, Byte{}),
                           wire::optional(0, "audio_format_1", &B::audio_format_1, kAudioFormat),
                           wire::optional(1, "audio_format_2", &B::audio_format_2, kAudioFormat),
                           wire::optional(2, "image_format_1", &B::image_format_1, kImageFormat),
                           wire::optional(3, "image_format_2", &B::image_format_2, kImageFormat),
                           wire::optional(4, "image_format_3", &B::image_format_3, kImageFormat),
                           wire::optional(5, "image_format_4", &B::image_format_4, kImageFormat),
                           wire::optional(6, "format_option", &B::format_option, UInt{}));
  }
};

// Report Image: one frame. Part 3 leaves the data undefined ("the JTA and
// best commercial practices dictate the content"); this is the layout the
// common RA 3.3 peer sends and reads: the camera ID, the image format code of
// Set Camera Format Options (7 JPEG, 11 PNG, ...), then the encoded image (a
// whole PNG or JPEG file), to the end of the message. A frame over one
// packet travels as a large data set.
struct ImageBody {
  std::uint8_t camera_id = 1;
  std::uint8_t image_format = 0;
  std::vector<std::uint8_t> data;
  bool operator==(const ImageBody&) const = default;
  static constexpr auto describe() {
    return std::make_tuple(wire::field("camera_id", &ImageBody::camera_id, Byte{}),
                           wire::field("image_format", &ImageBody::image_format, kImageFormat),
                           wire::field("data", &ImageBody::data, wire::Bytes<>{}));
  }
};

using SetCameraPose = Message<0x0801, "Set Camera Pose", CameraPoseCommandBody>;
using SelectCamera = Message<0x0802, "Select Camera", CameraIdBody>;
using SetCameraCapabilities = Message<0x0805, "Set Camera Capabilities", CameraCapabilitiesCommandBody>;
using SetCameraFormatOptions = Message<0x0806, "Set Camera Format Options", CameraFormatCommandBody>;

using QueryCameraPose = Message<0x2800, "Query Camera Pose", CameraQueryBody<std::uint16_t>>;
using QueryCameraCount = Message<0x2801, "Query Camera Count", Empty>;
using QueryRelativeObjectPosition =
    Message<0x2802, "Query Relative Object Position", PresenceQueryBody<std::uint8_t>>;
using QuerySelectedCamera = Message<0x2804, "Query Selected Camera", Empty>;
using QueryCameraCapabilities = Message<0x2805, "Query Camera Capabilities", CameraQueryBody<std::uint16_t>>;
using QueryCameraFormatOptions = Message<0x2806, "Query Camera Format Options", CameraQueryBody<std::uint8_t>>;
using QueryImage = Message<0x2807, "Query Image", Empty>;

using ReportCameraPose = Message<0x4800, "Report Camera Pose", CameraPoseReportBody>;
using ReportCameraCount = Message<0x4801, "Report Camera Count", CameraCountBody>;
using ReportRelativeObjectPosition =
    Message<0x4802, "Report Relative Object Position", RelativeObjectPositionBody>;
using ReportSelectedCamera = Message<0x4804, "Report Selected Camera", CameraIdBody>;
using ReportCameraCapabilities = Message<0x4805, "Report Camera Capabilities", CameraCapabilitiesReportBody>;
using ReportCameraFormatOptions = Message<0x4806, "Report Camera Format Options", CameraFormatReportBody>;
using ReportImage = Message<0x4807, "Report Image", ImageBody>;

using EnvironmentMessages =
    TypeList<SetCameraPose, SelectCamera, SetCameraCapabilities, SetCameraFormatOptions, QueryCameraPose,
             QueryCameraCount, QueryRelativeObjectPosition, QuerySelectedCamera, QueryCameraCapabilities,
             QueryCameraFormatOptions, QueryImage, ReportCameraPose, ReportCameraCount, ReportRelativeObjectPosition,
             ReportSelectedCamera, ReportCameraCapabilities, ReportCameraFormatOptions, ReportImage>;

}  // namespace jaus::msg
