#include "image_file.hpp"

#include <algorithm>
#include <condition_variable>
#include <deque>
#include <exception>
#include <mutex>
#include <thread>
#include <cmath>
#include <filesystem>
#include <stdexcept>
#include <string_view>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <sol/error.hpp>

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

bool image_decodes(const std::string& path, int width, int height, std::string* why) {
  auto fail = [&](const std::string& reason) {
    if (why) *why = reason;
    return false;
  };
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) return fail("not a regular file");
  if (std::filesystem::file_size(path, ec) == 0 || ec) return fail("empty");
  // (Made and opened in two steps: ImageInput::open keeps a failed open's
  // message in a global that the sanitizers count as a leak; the reader's
  // own message goes with it.)
  auto in = OIIO::ImageInput::create(path);
  OIIO::ImageSpec opened;
  if (!in || !in->open(path, opened)) {
    if (in) (void)in->geterror();
    return fail("not an image this program reads");
  }
  const OIIO::ImageSpec& spec = in->spec();
  if (spec.width != width || spec.height != height) {
    return fail(std::to_string(spec.width) + " x " + std::to_string(spec.height) + ", not " + std::to_string(width) +
                " x " + std::to_string(height));
  }
  std::vector<float> pixels(static_cast<std::size_t>(spec.width) * spec.height * spec.nchannels);
  if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, pixels.data())) {
    (void)in->geterror();
    return fail("it does not decode");
  }
  return true;
}

sol::Texture read_texture_file(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    throw sol::InvalidArgument(path + ": cannot open the texture (no such file, or not a regular file)");
  }
  // (Made and opened in two steps, as image_decodes.) The colour as the
  // file holds it, not multiplied by its alpha (which a texture ignores).
  auto in = OIIO::ImageInput::create(path);
  OIIO::ImageSpec opened, config;
  config.attribute("oiio:UnassociatedAlpha", 1);
  if (!in || !in->open(path, opened, config)) {
    const std::string error = in ? in->geterror() : OIIO::geterror();
    throw sol::InvalidArgument(path + ": not an image this program reads" + (error.empty() ? "" : " (" + error + ")"));
  }
  const OIIO::ImageSpec& spec = in->spec();
  if (spec.width < 1 || spec.height < 1 || spec.width > sol::Texture::kMaxTextureSize ||
      spec.height > sol::Texture::kMaxTextureSize || spec.nchannels < 1) {
    throw sol::InvalidArgument(path + ": a texture of " + std::to_string(spec.width) + " x " + std::to_string(spec.height) +
                               " texels (from 1 to " + std::to_string(sol::Texture::kMaxTextureSize) + " each way)");
  }
  const std::size_t texels = static_cast<std::size_t>(spec.width) * static_cast<std::size_t>(spec.height);
  std::vector<float> pixels(texels * static_cast<std::size_t>(spec.nchannels));
  if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, pixels.data())) {
    throw sol::InvalidArgument(path + ": the texture does not decode (" + in->geterror() + ")");
  }
  // 8- and 16-bit files hold sRGB-encoded values (PNG, JPEG, unless they say
  // otherwise); float files linear ones (EXR, HDR).
  const std::string space = spec.get_string_attribute("oiio:ColorSpace");
  const bool encoded = space.empty() ? !spec.format.is_floating_point()
                                     : (space == "sRGB" || space.find("srgb") != std::string::npos);
  // An albedo: linear, in [0, 1] (a float file's brighter texels cut at 1).
  auto linear = [&](float v) {
    if (!std::isfinite(v) || v <= 0.0f) return 0.0f;
    if (v >= 1.0f) return 1.0f;
    return !encoded ? v : v <= 0.04045f ? v / 12.92f : std::pow((v + 0.055f) / 1.055f, 2.4f);
  };
  sol::Texture t;
  t.width = spec.width;
  t.height = spec.height;
  t.rgb.resize(3 * texels);
  const auto n = static_cast<std::size_t>(spec.nchannels);
  for (std::size_t k = 0; k < texels; ++k) {
    for (std::size_t c = 0; c < 3; ++c) t.rgb[3 * k + c] = linear(pixels[n * k + std::min(c, n < 3 ? 0 : c)]);
  }
  return t;
}

void install_texture_reader() { sol::set_texture_reader(read_texture_file); }

struct ImageWriter::Impl {
  explicit Impl(const OutputFile& f) : file(f) {}
  const OutputFile& file;
  std::string path;  // the target's name, for messages
  int width = 0, height = 0, given = 0, channels = 0;
  bool drop_alpha = false, as_float = false, srgb = false;
  int tone = kernel::kToneClamp;  // the display's curve (sol/tone.h) ...
  double scale = 1.0;             // ... and 2^exposure
  std::size_t clipped = 0;        // pixels whose colour the display cut
  // The encoded bytes and their proxy before the writer: it may write
  // into them as it goes (an unfinished file closes when destroyed).
  std::vector<unsigned char> encoded;
  std::unique_ptr<OIIO::Filesystem::IOVecOutput> memory;
  std::unique_ptr<OIIO::ImageOutput> out;
  OIIO::ImageSpec spec;
  bool in_memory = false;
  int next_row = 0;
  std::size_t non_finite = 0;
  std::vector<float> band;  // one band's values as the file takes them

  // The worker: bands (first row, rows, values) waiting to be encoded.
  struct Queued {
    int first, rows;
    std::vector<float> values;
  };
  std::thread worker;
  std::mutex mutex;
  std::condition_variable changed;
  std::deque<Queued> queue;
  bool closing = false;
  std::exception_ptr error;  // the worker's

  [[noreturn]] void fail(const std::string& reason) const {
    throw std::runtime_error(path + ": cannot write: " + reason);
  }
  void encode(int first_row, int rows, std::span<const float> interleaved);
  void work();
  // Stops the worker (after the queued bands) and rethrows its error.
  void join();
};

void ImageWriter::Impl::work() {
  for (;;) {
    Queued q;
    {
      std::unique_lock lock(mutex);
      changed.wait(lock, [&] { return !queue.empty() || closing; });
      if (queue.empty()) return;
      q = std::move(queue.front());
    }
    try {
      if (!error) encode(q.first, q.rows, q.values);
    } catch (...) {
      std::lock_guard lock(mutex);
      error = std::current_exception();
    }
    {
      std::lock_guard lock(mutex);
      queue.pop_front();
    }
    changed.notify_all();
  }
}

void ImageWriter::Impl::join() {
  if (worker.joinable()) {
    {
      std::lock_guard lock(mutex);
      closing = true;
    }
    changed.notify_all();
    worker.join();
  }
  if (error) std::rethrow_exception(error);
}

ImageWriter::ImageWriter(const OutputFile& file, int width, int height, const std::vector<std::string>& channel_names,
                         bool srgb_for_8bit, bool worker, const Display& display)
    : m_impl(std::make_unique<Impl>(file)) {
  Impl& m = *m_impl;
  m.path = file.target();
  m.width = width;
  m.height = height;
  m.given = static_cast<int>(channel_names.size());
  m.srgb = srgb_for_8bit;
  m.tone = static_cast<int>(display.tone);
  m.scale = display.scale();
  // The writer is chosen from the target's name; it writes the temporary.
  m.out = OIIO::ImageOutput::create(m.path);
  if (!m.out) throw std::runtime_error(m.path + ": no image format for this file name (" + OIIO::geterror() + ")");
  // RGBA into a format without alpha (Radiance .hdr, .ppm: "can only
  // support 3-channel images", after the whole render): RGB alone. The
  // renders' alpha is 1 everywhere; nothing is lost.
  m.drop_alpha = m.given == 4 && channel_names[3] == "A" && !m.out->supports("alpha");
  m.channels = m.drop_alpha ? 3 : m.given;
  m.as_float = float_format(m.path);
  m.spec = OIIO::ImageSpec(width, height, m.channels, m.as_float ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::UINT8);
  m.spec.channelnames.assign(channel_names.begin(), channel_names.begin() + m.channels);
  if (m.channels == 4 && channel_names[3] == "A") m.spec.alpha_channel = 3;
  // Encoded in memory where the writer can (its own file writes are not all
  // checked: a full disk left PNG files empty and said nothing), then
  // written with every write checked; otherwise written by the writer and
  // read back whole before the file may replace its target.
  m.memory = std::make_unique<OIIO::Filesystem::IOVecOutput>(m.encoded);
  m.in_memory = m.out->supports("ioproxy") && m.out->set_ioproxy(m.memory.get());
  if (!m.out->open(m.in_memory ? m.path : file.path(), m.spec)) m.fail(m.out->geterror());
  if (worker) m.worker = std::thread([&m] { m.work(); });
}

ImageWriter::~ImageWriter() {
  try {
    m_impl->join();  // (an unfinished file: its temporary goes with its OutputFile)
  } catch (...) {
  }
}

void ImageWriter::write_rows(int first_row, int rows, std::span<const float> interleaved) {
  Impl& m = *m_impl;
  const auto row_in = static_cast<std::size_t>(m.width) * static_cast<std::size_t>(m.given);
  if (first_row != m.next_row || rows < 0 || first_row + rows > m.height ||
      interleaved.size() != row_in * static_cast<std::size_t>(rows)) {
    throw std::runtime_error(m.path + ": internal error: rows " + std::to_string(first_row) + " + " +
                             std::to_string(rows) + " do not follow row " + std::to_string(m.next_row) +
                             " or do not match the image");
  }
  m.next_row += rows;
  if (!m.worker.joinable()) {
    m.encode(first_row, rows, interleaved);
    return;
  }
  std::unique_lock lock(m.mutex);
  m.changed.wait(lock, [&] { return m.queue.size() < static_cast<std::size_t>(kQueuedBands) || m.error; });
  if (m.error) std::rethrow_exception(m.error);
  m.queue.push_back({first_row, rows, std::vector<float>(interleaved.begin(), interleaved.end())});
  lock.unlock();
  m.changed.notify_all();
}

void ImageWriter::Impl::encode(int first_row, int rows, std::span<const float> interleaved) {
  Impl& m = *this;
  const auto row_in = static_cast<std::size_t>(m.width) * static_cast<std::size_t>(m.given);
  // In bands of kBandRows rows: alpha dropped where the format has none,
  // non-finite values written as 0 (and counted), 8-bit formats through the
  // display's exposure and curve (the pixels it cuts counted), sRGB-encoded.
  constexpr int kBandRows = 64;
  const auto row_out = static_cast<std::size_t>(m.width) * static_cast<std::size_t>(m.channels);
  for (int y = 0; y < rows; y += kBandRows) {
    const int n = std::min(kBandRows, rows - y);
    const float* in = interleaved.data() + static_cast<std::size_t>(y) * row_in;
    const std::size_t values = row_out * static_cast<std::size_t>(n);
    m.band.resize(values);
    const auto stride = static_cast<std::size_t>(m.channels);
    bool cut = false;  // the current pixel's
    for (std::size_t i = 0, j = 0; i < values; ++j) {
      if (m.drop_alpha && j % 4 == 3) continue;
      float v = in[j];
      if (!std::isfinite(v)) {
        v = 0.0f;
        ++m.non_finite;
      }
      const std::size_t channel = i % stride;
      if (!m.as_float && m.srgb && channel < 3) {
        const double scaled = static_cast<double>(v) * m.scale;
        cut = (channel > 0 && cut) || kernel::sol_tone_curve(m.tone, scaled) > 1.0;
        v = programs::srgb_encode(static_cast<float>(kernel::sol_tone(m.tone, scaled)));
        if (channel == std::min<std::size_t>(stride, 3) - 1 && cut) ++m.clipped;
      }
      m.band[i++] = v;
    }
    if (!m.out->write_scanlines(first_row + y, first_row + y + n, 0, OIIO::TypeDesc::FLOAT, m.band.data())) {
      m.fail(m.out->geterror());
    }
  }
}

std::size_t ImageWriter::finish() {
  Impl& m = *m_impl;
  m.join();
  if (m.next_row != m.height) {
    throw std::runtime_error(m.path + ": internal error: " + std::to_string(m.next_row) + " of " +
                             std::to_string(m.height) + " rows written");
  }
  if (!m.out->close()) m.fail(m.out->geterror());
  if (m.in_memory) {
    m.file.write(std::string_view(reinterpret_cast<const char*>(m.encoded.data()), m.encoded.size()));
  } else {
    check_readable(m.file.path(), m.path, m.spec);
  }
  return m.non_finite;
}

std::size_t ImageWriter::clipped() const { return m_impl->clipped; }

std::size_t write_image(const OutputFile& file, int width, int height, const std::vector<std::string>& channel_names,
                 const std::vector<float>& interleaved, bool srgb_for_8bit, const Display& display) {
  if (interleaved.size() != static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * channel_names.size()) {
    throw std::runtime_error(file.target() + ": internal error: pixel data size does not match the image");
  }
  ImageWriter writer(file, width, height, channel_names, srgb_for_8bit, false, display);
  writer.write_rows(0, height, interleaved);
  return writer.finish();
}

std::size_t write_image(const std::string& path, int width, int height, const std::vector<std::string>& channel_names,
                 const std::vector<float>& interleaved, bool srgb_for_8bit, const Display& display) {
  OutputFile file(path);
  const std::size_t non_finite = write_image(file, width, height, channel_names, interleaved, srgb_for_8bit, display);
  file.commit();
  return non_finite;
}

}  // namespace sol::programs
