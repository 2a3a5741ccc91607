// Writing images and AOVs with OpenImageIO, atomically (output_file.hpp):
// the data go to a temporary file beside the target, moved into place only
// when complete, so a failure never leaves a partial output file.
#pragma once

#include <string>
#include <vector>

#include "output_file.hpp"

namespace sol::programs {

/// Writes a width × height image with the given channels (interleaved floats,
/// row 0 at the top) in the format the extension names (any OpenImageIO
/// writes). Formats with float pixels (EXR, HDR, TIFF, PFM) get the linear
/// values; 8-bit formats (PNG, JPEG, ...) get them sRGB-encoded when
/// `srgb_for_8bit` is set. No NaN or infinity reaches a file: such values
/// (a defect: validation keeps the renderers' arithmetic finite) are written
/// as 0, and their count is returned for the caller to report. Throws
/// std::runtime_error naming the file and the reason on failure.
std::size_t write_image(const std::string& path, int width, int height, const std::vector<std::string>& channel_names,
                 const std::vector<float>& interleaved, bool srgb_for_8bit);

/// The same into `file`'s temporary (in the format its target's name
/// names), left for the caller to commit: several files of one run are
/// written first and committed together, so a failure leaves none.
std::size_t write_image(const OutputFile& file, int width, int height, const std::vector<std::string>& channel_names,
                 const std::vector<float>& interleaved, bool srgb_for_8bit);

/// Whether OpenImageIO can write files with this name's extension.
bool can_write(const std::string& path);

}  // namespace sol::programs
