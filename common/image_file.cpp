#include "image_file.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <stdexcept>
#include <string_view>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include "srgb.hpp"

namespace sol::programs {
namespace {

std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

bool float_format(const std::string& path) {
  const std::string ext = lower_extension(path);
  return ext == ".exr" || ext == ".hdr" || ext == ".tif" || ext == ".tiff" || ext == ".pfm";
}

// The file just written at `temporary` reads back whole as `spec` says
// (its writer's own writes were not checked); throws naming `target`.
void check_readable(const std::string& temporary, const std::string& target, const OIIO::ImageSpec& spec) {
  auto in = OIIO::ImageInput::open(temporary);
  if (!in) throw std::runtime_error(target + ": cannot write: the written file does not read back (" + OIIO::geterror() + ")");
  const OIIO::ImageSpec& got = in->spec();
  std::vector<float> pixels(static_cast<std::size_t>(got.width) * static_cast<std::size_t>(got.height) *
                            static_cast<std::size_t>(std::max(got.nchannels, 1)));
  const bool whole = got.width == spec.width && got.height == spec.height && got.nchannels == spec.nchannels &&
                     in->read_image(0, 0, 0, got.nchannels, OIIO::TypeDesc::FLOAT, pixels.data());
  const std::string reason = whole ? std::string() : in->geterror();
  in->close();
  if (!whole) throw std::runtime_error(target + ": cannot write: the written file is incomplete" + (reason.empty() ? "" : " (" + reason + ")"));
}

}  // namespace

bool can_write(const std::string& path) {
  auto out = OIIO::ImageOutput::create(path);
  return out != nullptr;
}

std::size_t write_image(const OutputFile& file, int width, int height, const std::vector<std::string>& channel_names,
                 const std::vector<float>& interleaved, bool srgb_for_8bit) {
  const std::string& path = file.target();
  const int given = static_cast<int>(channel_names.size());
  if (interleaved.size() != static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * given) {
    throw std::runtime_error(path + ": internal error: pixel data size does not match the image");
  }
  // The writer is chosen from the target's name; it writes the temporary.
  auto out = OIIO::ImageOutput::create(path);
  if (!out) throw std::runtime_error(path + ": no image format for this file name (" + OIIO::geterror() + ")");
  // RGBA into a format without alpha (Radiance .hdr, .ppm: "can only
  // support 3-channel images", after the whole render): RGB alone. The
  // renders' alpha is 1 everywhere; nothing is lost.
  const bool drop_alpha = given == 4 && channel_names[3] == "A" && !out->supports("alpha");
  const int channels = drop_alpha ? 3 : given;
  std::vector<float> data;
  if (drop_alpha) {
    data.reserve(interleaved.size() / 4 * 3);
    for (std::size_t i = 0; i < interleaved.size(); ++i) {
      if (i % 4 != 3) data.push_back(interleaved[i]);
    }
  } else {
    data = interleaved;
  }
  const bool as_float = float_format(path);
  OIIO::ImageSpec spec(width, height, channels, as_float ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::UINT8);
  spec.channelnames.assign(channel_names.begin(), channel_names.begin() + channels);
  if (channels == 4 && channel_names[3] == "A") spec.alpha_channel = 3;
  std::size_t non_finite = 0;
  for (float& v : data) {
    if (!std::isfinite(v)) {
      v = 0.0f;
      ++non_finite;
    }
  }
  if (!as_float && srgb_for_8bit) {
    for (std::size_t i = 0; i < data.size(); ++i) {
      if (static_cast<int>(i % static_cast<std::size_t>(channels)) < 3) data[i] = programs::srgb_encode(data[i]);
    }
  }
  // Encoded in memory where the writer can (its own file writes are not all
  // checked: a full disk left PNG files empty and said nothing), then
  // written with every write checked; otherwise written by the writer and
  // read back whole before the file may replace its target.
  std::vector<unsigned char> encoded;
  OIIO::Filesystem::IOVecOutput memory(encoded);
  const bool in_memory = out->supports("ioproxy") && out->set_ioproxy(&memory);
  if (!out->open(in_memory ? path : file.path(), spec)) throw std::runtime_error(path + ": cannot write: " + out->geterror());
  const bool written = out->write_image(OIIO::TypeDesc::FLOAT, data.data());
  const std::string reason = written ? std::string() : out->geterror();
  const bool closed = out->close();
  if (!written || !closed) throw std::runtime_error(path + ": cannot write: " + (reason.empty() ? out->geterror() : reason));
  if (in_memory) {
    file.write(std::string_view(reinterpret_cast<const char*>(encoded.data()), encoded.size()));
  } else {
    check_readable(file.path(), path, spec);
  }
  return non_finite;
}

std::size_t write_image(const std::string& path, int width, int height, const std::vector<std::string>& channel_names,
                 const std::vector<float>& interleaved, bool srgb_for_8bit) {
  OutputFile file(path);
  const std::size_t non_finite = write_image(file, width, height, channel_names, interleaved, srgb_for_8bit);
  file.commit();
  return non_finite;
}

}  // namespace sol::programs
