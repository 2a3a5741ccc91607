#include "image_file.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <stdexcept>

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

}  // namespace

bool can_write(const std::string& path) {
  auto out = OIIO::ImageOutput::create(path);
  return out != nullptr;
}

std::size_t write_image(const OutputFile& file, int width, int height, const std::vector<std::string>& channel_names,
                 const std::vector<float>& interleaved, bool srgb_for_8bit) {
  const std::string& path = file.target();
  const int channels = static_cast<int>(channel_names.size());
  if (interleaved.size() != static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * channels) {
    throw std::runtime_error(path + ": internal error: pixel data size does not match the image");
  }
  // The writer is chosen from the target's name; it writes the temporary.
  auto out = OIIO::ImageOutput::create(path);
  if (!out) throw std::runtime_error(path + ": no image format for this file name (" + OIIO::geterror() + ")");
  const bool as_float = float_format(path);
  OIIO::ImageSpec spec(width, height, channels, as_float ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::UINT8);
  spec.channelnames = channel_names;
  if (channels == 4 && channel_names[3] == "A") spec.alpha_channel = 3;
  std::vector<float> data = interleaved;
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
  if (!out->open(file.path(), spec)) throw std::runtime_error(path + ": cannot write: " + out->geterror());
  const bool written = out->write_image(OIIO::TypeDesc::FLOAT, data.data());
  const std::string reason = written ? std::string() : out->geterror();
  const bool closed = out->close();
  if (!written || !closed) throw std::runtime_error(path + ": cannot write: " + (reason.empty() ? out->geterror() : reason));
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
