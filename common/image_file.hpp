// Writing images and AOVs with OpenImageIO, atomically (output_file.hpp):
// the data go to a temporary file beside the target, moved into place only
// when complete, so a failure never leaves a partial output file.
#pragma once

#include <cstddef>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include <sol/display.hpp>
#include <sol/texture.hpp>

#include "output_file.hpp"

namespace sol::programs {

/// An image file written band by band, rows from the top, as write_image
/// writes a whole one (same formats, encoding and checks), into `file`'s
/// temporary, left for the caller to commit: a renderer's bands go
/// straight into the encoder (RenderOptions::rows) and the image is never
/// held whole. Throws std::runtime_error naming the file and the reason.
class ImageWriter {
 public:
  /// With `worker`, the rows are encoded on a thread of the writer's own:
  /// write_rows copies them and returns (waiting only while kQueuedBands
  /// bands are already queued), so that a renderer goes on with the next
  /// band meanwhile.
  /// `display`: the exposure and tone curve of 8-bit formats with
  /// `srgb_for_8bit` (their colour channels scaled by Display::scale and
  /// shown through the curve, then sRGB-encoded); float formats take the
  /// values as they are.
  ImageWriter(const OutputFile& file, int width, int height, const std::vector<std::string>& channel_names,
              bool srgb_for_8bit, bool worker = false, const Display& display = {});
  ~ImageWriter();
  ImageWriter(const ImageWriter&) = delete;
  ImageWriter& operator=(const ImageWriter&) = delete;
  /// Rows [first_row, first_row + rows): the next ones, in order, their
  /// channels interleaved (rows × width × channels values). An error of the
  /// worker's is thrown here or by finish().
  void write_rows(int first_row, int rows, std::span<const float> interleaved);
  /// After the last row: finishes the file (the worker's rows first);
  /// returns how many non-finite values were written as 0.
  std::size_t finish();
  /// After finish(): how many pixels of an 8-bit file the display cut at
  /// white (a colour channel where the tone curve exceeds 1: Display::clips).
  std::size_t clipped() const;

  /// The most bands queued for the worker at once.
  static constexpr int kQueuedBands = 2;

 private:
  struct Impl;
  std::unique_ptr<Impl> m_impl;
};

/// Writes a width × height image with the given channels (interleaved floats,
/// row 0 at the top) in the format the extension names (any OpenImageIO
/// writes). Formats with float pixels (EXR, HDR, TIFF, PFM) get the linear
/// values; 8-bit formats (PNG, JPEG, ...) get them sRGB-encoded when
/// `srgb_for_8bit` is set, after `display`'s exposure and tone curve. No NaN or infinity reaches a file: such values
/// (a defect: validation keeps the renderers' arithmetic finite) are written
/// as 0, and their count is returned for the caller to report. Throws
/// std::runtime_error naming the file and the reason on failure.
std::size_t write_image(const std::string& path, int width, int height, const std::vector<std::string>& channel_names,
                 const std::vector<float>& interleaved, bool srgb_for_8bit, const Display& display = {});

/// The same into `file`'s temporary (in the format its target's name
/// names), left for the caller to commit: several files of one run are
/// written first and committed together, so a failure leaves none.
std::size_t write_image(const OutputFile& file, int width, int height, const std::vector<std::string>& channel_names,
                 const std::vector<float>& interleaved, bool srgb_for_8bit, const Display& display = {});

/// Whether OpenImageIO can write files with this name's extension.
bool can_write(const std::string& path);

/// Whether `path` is a regular file holding a whole width × height image
/// (opened and every pixel decoded); where not, `why` says what it is (an
/// empty file, a directory, a truncated image, another size).
bool image_decodes(const std::string& path, int width, int height, std::string* why = nullptr);

/// An image file as an object's texture (sol/texture.hpp): decoded by
/// OpenImageIO, 8- and 16-bit files' sRGB values made linear (float files'
/// taken as linear), grey spread to RGB, alpha dropped, each value cut to
/// [0, 1]. Throws sol::InvalidArgument naming the file and why.
sol::Texture read_texture_file(const std::string& path);

/// Makes read_texture_file the process's texture reader
/// (sol::set_texture_reader), so that scene files' "texture" keys load:
/// every program calls it first.
void install_texture_reader();

}  // namespace sol::programs
