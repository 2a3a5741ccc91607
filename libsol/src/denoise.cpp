#include "sol/denoise.hpp"

#include <algorithm>
#include <string>
#include <thread>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "sol/denoise.h"
#include "sol/error.hpp"
#include "row_pool.hpp"

namespace sol {

void validate_denoise(const RenderResult& image, int eyes, const char* who) {
  const std::string where = std::string(who) + ": ";
  if (eyes != 1 && eyes != 2) throw InvalidArgument(where + "eyes must be 1 or 2, got " + std::to_string(eyes));
  if (image.width < 1 || image.height < 1 || image.width % eyes != 0) {
    throw InvalidArgument(where + "the image's width " + std::to_string(image.width) + " and height " +
                          std::to_string(image.height) + " must be positive, the width a multiple of the eyes");
  }
  const std::size_t n = static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height);
  const struct {
    const char* name;
    std::size_t size, expected;
  } planes[] = {{"rgba", image.rgba.size(), 4 * n},     {"object", image.object.size(), n},
                {"distance", image.distance.size(), n}, {"albedo", image.albedo.size(), 3 * n},
                {"emission", image.emission.size(), 3 * n}, {"normal", image.normal.size(), 3 * n}};
  for (const auto& p : planes) {
    if (p.size != p.expected) {
      throw InvalidArgument(where + "the image's " + p.name + " holds " + std::to_string(p.size) + " values, not " +
                            std::to_string(p.expected) + (p.size == 0 ? " (render with RenderOptions::aovs and guides)" : ""));
    }
  }
  // (The light moment is optional: without it the noise is the neighbours'.)
  if (!image.light_moment.empty() && image.light_moment.size() != n) {
    throw InvalidArgument(where + "the image's light_moment holds " + std::to_string(image.light_moment.size()) +
                          " values, not " + std::to_string(n) + " (or none)");
  }
  if (image.samples < 0) throw InvalidArgument(where + "the image's samples must be 0 or more, got " + std::to_string(image.samples));
}

std::vector<double> own_variances(const RenderResult& image) {
  const std::size_t n = static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height);
  if (image.samples < 2 || image.light_moment.size() != n || image.emission.size() != 3 * n) return {};
  std::vector<double> own(n);
  for (std::size_t k = 0; k < n; ++k) {
    glm::dvec3 light, modulation;
    for (int c = 0; c < 3; ++c) {
      const std::size_t channel = static_cast<std::size_t>(c);
      light[c] = static_cast<double>(image.rgba[4 * k + channel]) - image.emission[3 * k + channel];
      modulation[c] = kernel::sol_denoise_modulation(image.albedo[3 * k + channel], image.object[k]);
    }
    own[k] = kernel::sol_denoise_own_variance(image.light_moment[k], kernel::sol_denoise_luminance(light),
                                              static_cast<double>(image.samples), kernel::sol_denoise_luminance(modulation));
  }
  return own;
}

namespace {

// One pixel's guides, as the filter reads them.
struct Guide {
  double object = 0.0, distance = 0.0, slope = 0.0;
  glm::dvec3 normal{0.0};
};

}  // namespace

void denoise(RenderResult& image, int eyes, unsigned threads) {
  validate_denoise(image, eyes, "sol::denoise");
  const int w = image.width, h = image.height, eye_width = w / eyes;
  const std::size_t n = static_cast<std::size_t>(w) * static_cast<std::size_t>(h);
  if (threads == 0) threads = std::max(1u, std::thread::hardware_concurrency());
  threads = std::min<unsigned>(threads, static_cast<unsigned>(h));
  auto index = [w](int i, int j) { return static_cast<std::size_t>(j) * static_cast<std::size_t>(w) + static_cast<std::size_t>(i); };
  auto same_eye = [eye_width](int i, int other) { return other >= 0 && other / eye_width == i / eye_width; };

  std::vector<Guide> guide(n);
  std::vector<glm::dvec3> modulation(n);
  std::vector<glm::dvec4> current(n), next(n);  // the light (rgb) and its luminance's variance (w)
  for (std::size_t k = 0; k < n; ++k) {
    Guide& g = guide[k];
    g.object = image.object[k];
    g.distance = image.distance[k];
    for (int c = 0; c < 3; ++c) {
      g.normal[c] = image.normal[3 * k + c];
      modulation[k][c] = kernel::sol_denoise_modulation(image.albedo[3 * k + c], g.object);
      current[k][c] = (image.rgba[4 * k + c] - image.emission[3 * k + c]) / modulation[k][c];
    }
  }
  // Each pixel's distance slope and its noise: the mean over its 3 × 3
  // neighbours of the same object of their own variances where the image
  // has them, else the variance of their light (the noise, and what the
  // light itself varies there).
  const std::vector<double> own = own_variances(image);
  detail::for_each_row(h, threads, {}, [&](int j, const std::atomic<bool>&) {
    for (int i = 0; i < w; ++i) {
      const std::size_t k = index(i, j);
      Guide& g = guide[k];
      auto same = [&](int x, int y) {
        return same_eye(i, x) && x < w && y >= 0 && y < h && guide[index(x, y)].object == g.object;
      };
      auto z = [&](int x, int y) { return same(x, y) ? guide[index(x, y)].distance : 0.0; };
      g.slope = std::max(kernel::sol_denoise_slope_along(g.distance, z(i - 1, j), same(i - 1, j), z(i + 1, j), same(i + 1, j)),
                         kernel::sol_denoise_slope_along(g.distance, z(i, j - 1), same(i, j - 1), z(i, j + 1), same(i, j + 1)));
      double sum = 0.0, squares = 0.0, count = 0.0, owns = 0.0;
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
          if (!same(i + dx, j + dy)) continue;
          const std::size_t q = index(i + dx, j + dy);
          const double l = kernel::sol_denoise_luminance(glm::dvec3(current[q]));
          sum += l;
          squares += l * l;
          count += 1.0;
          if (!own.empty()) owns += own[q];
        }
      }
      current[k].w = own.empty() ? std::max(squares / count - (sum / count) * (sum / count), 0.0) : owns / count;
    }
  });
  // The unfiltered light and each pixel's noise, to hold the filtered light to (sol_denoise_clamp).
  const bool clamp = !own.empty() && image.samples >= kernel::kDenoiseClampSamples;
  const std::vector<glm::dvec4> unfiltered = clamp ? current : std::vector<glm::dvec4>{};
  for (int pass = 0; pass < kernel::kDenoisePasses; ++pass) {
    const int step = 1 << pass;
    detail::for_each_row(h, threads, {}, [&](int j, const std::atomic<bool>&) {
      for (int i = 0; i < w; ++i) {
        const std::size_t k = index(i, j);
        const Guide& g = guide[k];
        const double l = kernel::sol_denoise_luminance(glm::dvec3(current[k]));
        glm::dvec3 sum(0.0);
        double weights = 0.0, variance = 0.0;
        for (int dy = -2; dy <= 2; ++dy) {
          for (int dx = -2; dx <= 2; ++dx) {
            const int x = i + dx * step, y = j + dy * step;
            if (!same_eye(i, x) || x >= w || y < 0 || y >= h) continue;
            const std::size_t q = index(x, y);
            const Guide& o = guide[q];
            const double offset = step * std::sqrt(static_cast<double>(dx * dx + dy * dy));
            const double wq = kernel::sol_denoise_tap(dx) * kernel::sol_denoise_tap(dy) *
                              kernel::sol_denoise_weight(g.object, o.object, l,
                                                         kernel::sol_denoise_luminance(glm::dvec3(current[q])), current[k].w,
                                                         g.normal, o.normal, g.distance, o.distance, g.slope, offset);
            sum += wq * glm::dvec3(current[q]);
            weights += wq;
            variance += wq * wq * current[q].w;
          }
        }
        // (The centre's own weight is its tap's, never 0: weights > 0.)
        next[k] = glm::dvec4(sum / weights, variance / (weights * weights));
      }
    });
    std::swap(current, next);
  }
  for (std::size_t k = 0; k < n; ++k) {
    const glm::dvec3 filtered(current[k]);
    const glm::dvec3 light = clamp ? kernel::sol_denoise_clamp(filtered, glm::dvec3(unfiltered[k]), unfiltered[k].w) : filtered;
    for (int c = 0; c < 3; ++c) {
      image.rgba[4 * k + c] = static_cast<float>(light[c] * modulation[k][c] + image.emission[3 * k + c]);
    }
  }
}

}  // namespace sol
