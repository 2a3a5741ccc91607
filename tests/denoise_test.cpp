// The denoiser on the host (sol::denoise, sol/denoise.h) on images whose
// truth is known: synthetic images built here (a flat surface of known
// light and albedo, with noise of known spread), whose denoised colour is
// compared with the truth, and the filter's invariants (a constant image
// stays as it is, no pixel takes from another object or the other eye).
// Also the CPU renderer's guides against the scene's definitions and
// against the colour where the colour is the albedo or the emission alone. The kernel's filter and AOVs are compared with these in
// kernel_denoise_test.cpp.
#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <sol/denoise.h>
#include <sol/denoise.hpp>
#include <sol/sol.hpp>

#include "support/guides.hpp"

namespace {

// A w × h image of a plane seen face on: object 1, normal (0, 0, 1),
// distance 2 everywhere, albedo `albedo(i, j)`, no emission, colour
// albedo × light + Gaussian noise of standard deviation `sigma` (seeded).
template <class Albedo>
sol::RenderResult flat_image(int w, int h, double light, double sigma, Albedo albedo, unsigned seed = 1) {
  sol::RenderResult r;
  r.width = w;
  r.height = h;
  const std::size_t n = static_cast<std::size_t>(w) * h;
  r.rgba.resize(4 * n);
  r.object.assign(n, 1.0f);
  r.distance.assign(n, 2.0f);
  r.albedo.resize(3 * n);
  r.emission.assign(3 * n, 0.0f);
  r.normal.resize(3 * n);
  std::mt19937 random(seed);
  std::normal_distribution<double> noise(0.0, sigma);
  for (int j = 0; j < h; ++j) {
    for (int i = 0; i < w; ++i) {
      const std::size_t k = static_cast<std::size_t>(j) * w + i;
      const double a = albedo(i, j);
      for (int c = 0; c < 3; ++c) {
        r.albedo[3 * k + c] = static_cast<float>(a);
        r.rgba[4 * k + c] = static_cast<float>(a * light + noise(random));
        r.normal[3 * k + c] = c == 2 ? 1.0f : 0.0f;
      }
      r.rgba[4 * k + 3] = 1.0f;
    }
  }
  return r;
}

// The RMS difference of the red channel from a * light over the pixels.
template <class Albedo>
double rms_error(const sol::RenderResult& r, double light, Albedo albedo) {
  double squares = 0.0;
  for (int j = 0; j < r.height; ++j) {
    for (int i = 0; i < r.width; ++i) {
      const double d = r.rgba[4 * (static_cast<std::size_t>(j) * r.width + i)] - albedo(i, j) * light;
      squares += d * d;
    }
  }
  return std::sqrt(squares / (r.width * r.height));
}

TEST(Denoise, AConstantImageStaysAsItIs) {
  // Every weight is normalised: a constant colour is its own weighted mean.
  const auto grey = [](int, int) { return 0.5; };
  sol::RenderResult r = flat_image(40, 30, 0.8, 0.0, grey);
  sol::denoise(r);
  for (std::size_t k = 0; k < r.rgba.size(); ++k) EXPECT_NEAR(r.rgba[k], k % 4 == 3 ? 1.0 : 0.4, 1e-6) << k;
}

TEST(Denoise, NoiseOnAFlatSurfaceFallsBelowAQuarter) {
  // White noise of σ = 0.1 on a constant 0.5: the passes' kernel (33
  // pixels wide, its luminance weight letting most of them in) must take
  // the noise down at least fourfold, what 16 times the samples would.
  const auto grey = [](int, int) { return 0.5; };
  sol::RenderResult r = flat_image(64, 48, 1.0, 0.1, grey);
  const double before = rms_error(r, 1.0, grey);
  sol::denoise(r);
  const double after = rms_error(r, 1.0, grey);
  EXPECT_NEAR(before, 0.1, 0.005);
  EXPECT_LT(after, before / 4.0) << before << " -> " << after;
}

TEST(Denoise, AnAlbedoCheckerKeepsItsEdges) {
  // A checker of albedo 0.2 and 0.8 (squares of 8 pixels) under a light of
  // 1 with noise: the colour is divided by the albedo before filtering
  // and multiplied by it after, so every pixel, the squares' edges
  // included, comes back near its own albedo, and the noise falls as on a
  // flat surface.
  const auto checker = [](int i, int j) { return ((i / 8) + (j / 8)) % 2 == 0 ? 0.2 : 0.8; };
  sol::RenderResult r = flat_image(64, 48, 1.0, 0.05, checker, 7);
  const double before = rms_error(r, 1.0, checker);
  sol::denoise(r);
  EXPECT_LT(rms_error(r, 1.0, checker), before / 3.0);
  double worst = 0.0;
  for (int j = 0; j < r.height; ++j) {
    for (int i = 0; i < r.width; ++i) {
      worst = std::max(worst, std::abs(r.rgba[4 * (static_cast<std::size_t>(j) * r.width + i)] - checker(i, j)));
    }
  }
  // Blurred edges would put pixels near 0.5, 0.3 from either albedo; the
  // raw noise reaches about 4 σ = 0.2 at the worst of 3072 pixels.
  EXPECT_LT(worst, 0.12);
}

TEST(Denoise, NoPixelTakesFromAnotherObjectOrTheOtherEye) {
  // Left half object 1 at colour 0.2, right half object 2 at 0.9, both
  // noisy; then the same as two eyes of one object. Every output pixel is
  // a weighted mean of its own half's inputs: within their range.
  for (const bool eyes : {false, true}) {
    const auto half = [](int i, int) { return i < 32 ? 0.2 : 0.9; };
    sol::RenderResult r = flat_image(64, 32, 1.0, 0.05, half, 3);
    if (!eyes) {
      for (int j = 0; j < r.height; ++j) {
        for (int i = 32; i < 64; ++i) r.object[static_cast<std::size_t>(j) * 64 + i] = 2.0f;
      }
    }
    double low[2] = {1e9, 1e9}, high[2] = {-1e9, -1e9};
    for (int j = 0; j < r.height; ++j) {
      for (int i = 0; i < 64; ++i) {
        const double v = r.rgba[4 * (static_cast<std::size_t>(j) * 64 + i)] / half(i, j);  // (the light: divided by the albedo)
        low[i / 32] = std::min(low[i / 32], v);
        high[i / 32] = std::max(high[i / 32], v);
      }
    }
    // With one object and two eyes the light (1 on both halves) would
    // mix; the eyes' rule lets nothing through.
    sol::denoise(r, eyes ? 2 : 1);
    for (int j = 0; j < r.height; ++j) {
      for (int i = 0; i < 64; ++i) {
        const double v = r.rgba[4 * (static_cast<std::size_t>(j) * 64 + i)] / half(i, j);
        EXPECT_GE(v, low[i / 32] - 1e-6) << i << ", " << j << (eyes ? " eyes" : " objects");
        EXPECT_LE(v, high[i / 32] + 1e-6) << i << ", " << j << (eyes ? " eyes" : " objects");
      }
    }
  }
}

TEST(Denoise, TheEmissionIsTakenOutAndTheAlbedoDividedPixelByPixel) {
  // Pixels whose samples straddle edges have guides that are blends: here
  // every pixel has its own albedo in [0.2, 0.8] and emission in [0, 3]
  // (as the samples' means are), the colour emission + albedo × light
  // under a light of 1, with noise of σ = 0.05. The light the filter sees,
  // (colour − emission) / albedo, is flat: the noise must fall at least
  // threefold though no two neighbours share a colour. (Without taking
  // the emission out the light would vary by up to 15 from pixel to
  // pixel and the luminance weight let nothing in: the error stays.)
  std::mt19937 random(11);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  sol::RenderResult r = flat_image(64, 48, 1.0, 0.0, [](int, int) { return 0.5; });
  std::normal_distribution<double> noise(0.0, 0.05);
  std::vector<double> truth(r.rgba.size(), 1.0);
  for (std::size_t k = 0; k < r.object.size(); ++k) {
    for (int c = 0; c < 3; ++c) {
      const double a = 0.2 + 0.6 * unit(random), e = 3.0 * unit(random);
      r.albedo[3 * k + c] = static_cast<float>(a);
      r.emission[3 * k + c] = static_cast<float>(e);
      truth[4 * k + c] = e + a;
      r.rgba[4 * k + c] = static_cast<float>(e + a + noise(random));
    }
  }
  const auto error = [&](const sol::RenderResult& image) {
    double squares = 0.0;
    for (std::size_t k = 0; k < truth.size(); ++k) {
      if (k % 4 != 3) squares += std::pow(image.rgba[k] - truth[k], 2.0);
    }
    return std::sqrt(squares / (3.0 * static_cast<double>(r.object.size())));
  };
  const double before = error(r);
  sol::denoise(r);
  EXPECT_NEAR(before, 0.05, 0.003);
  EXPECT_LT(error(r), before / 3.0) << before << " -> " << error(r);
}

TEST(Denoise, AnImageWithoutItsAovsIsRefusedByName) {
  const auto grey = [](int, int) { return 0.5; };
  sol::RenderResult r = flat_image(8, 8, 1.0, 0.0, grey);
  r.albedo.clear();
  try {
    sol::denoise(r);
    FAIL() << "no albedo accepted";
  } catch (const sol::InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("albedo"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("RenderOptions::aovs"), std::string::npos) << e.what();
  }
  sol::RenderResult odd = flat_image(9, 8, 1.0, 0.0, grey);
  EXPECT_THROW(sol::denoise(odd, 2), sol::InvalidArgument);  // two eyes of an odd width
  EXPECT_THROW(sol::denoise(odd, 3), sol::InvalidArgument);
}

TEST(Denoise, ALightMomentOfTheWrongSizeOrNegativeSamplesAreRefusedByName) {
  // (An image without a light moment is filtered with the neighbours' noise;
  // one with a moment of another size, or a negative count, is an error.)
  const auto grey = [](int, int) { return 0.5; };
  const sol::RenderResult good = flat_image(8, 8, 1.0, 0.05, grey);
  sol::RenderResult short_moment = good, negative = good;
  short_moment.light_moment.assign(63, 0.25f);
  short_moment.samples = 4;
  negative.samples = -1;
  const sol::RenderResult before = short_moment;
  for (auto [image, field] : {std::pair{&short_moment, "light_moment"}, std::pair{&negative, "samples"}}) {
    try {
      sol::denoise(*image);
      ADD_FAILURE() << field << " accepted";
    } catch (const sol::InvalidArgument& e) {
      EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
    }
  }
  EXPECT_EQ(short_moment.rgba, before.rgba);  // (refused before any pixel changed)
}

TEST(Denoise, TheCpuRenderersAlbedoAndNormalAreTheHitsOwn) {
  // The sandwich's two planes z = ±1 (the lower one's "circles" pattern):
  // each pixel's albedo is its object's colour times the pattern's factor
  // at the hit point's pattern coordinates (the world x, y for a plane),
  // its normal (0, 0, ∓1) facing the ray (the upper plane's is -z).
  sol::Scene scene = sol::preset_scene("sandwich");
  sol::RenderOptions options;
  options.width = 32;
  options.height = 24;
  options.guides = true;
  const sol::RenderResult r = sol::render_cpu(scene, options);
  int hits = 0;
  for (std::size_t k = 0; k < r.object.size(); ++k) {
    const int object = static_cast<int>(r.object[k]);
    if (object == 0) {
      for (int c = 0; c < 3; ++c) EXPECT_EQ(r.albedo[3 * k + c], 0.0f);
      continue;
    }
    ++hits;
    const sol::SceneObject& o = scene.objects[static_cast<std::size_t>(object - 1)];
    const double factor = sol::pattern_factor(o.pattern, r.px[k], r.py[k]);
    const double z = r.pz[k];
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(r.albedo[3 * k + c], o.color[c] * factor, 1e-6) << k;
    EXPECT_NEAR(r.normal[3 * k + 2], z > 0.0 ? -1.0 : 1.0, 1e-9) << k;
  }
  EXPECT_GT(hits, 500);
}


TEST(Denoise, TheCpuRenderersGuidesAreTheSamplesMeans) {
  sol::CpuRenderer cpu;
  sol::test::expect_guides_are_the_samples_means(cpu, 1e-6);
}

TEST(Denoise, TheCpuRenderersLightMomentIsTheSamplesMeanSquare) {
  // (The moment summed in double and stored in float: 1e-6 relative.)
  sol::CpuRenderer cpu;
  sol::test::expect_light_moment_is_the_samples_mean_square(cpu, 1e-6);
}

// A w × h plane seen face on (object 1, albedo 0.5, distance 2) whose
// pixel k's colour is the mean of `samples` samples of Gaussian noise of
// spread 0.2 about truth(k), with its light moment (the mean of the
// samples' squared luminances: grey, so the luminance is the channel) and
// the count.
template <class Truth>
sol::RenderResult sampled_image(int w, int h, int samples, unsigned seed, Truth truth) {
  const auto grey = [](int, int) { return 0.5; };
  sol::RenderResult r = flat_image(w, h, 1.0, 0.0, grey);
  std::mt19937 random(seed);
  std::normal_distribution<double> noise(0.0, 0.2);
  r.light_moment.resize(r.object.size());
  r.samples = samples;
  for (std::size_t k = 0; k < r.object.size(); ++k) {
    const double mean = truth(k);
    double sum = 0.0, squares = 0.0;
    for (int s = 0; s < samples; ++s) {
      const double v = mean + noise(random);
      sum += v;
      squares += v * v;
    }
    for (int c = 0; c < 3; ++c) r.rgba[4 * k + c] = static_cast<float>(sum / samples);
    r.light_moment[k] = static_cast<float>(squares / samples);
  }
  return r;
}

// 32 × 16 pixels whose light is 1 left of column 16 and 0.6 right of it (a
// shadow's edge: the same object and normal on both sides).
sol::RenderResult shadow_edge(int samples, unsigned seed) {
  return sampled_image(32, 16, samples, seed, [](std::size_t k) { return 0.5 * (k % 32 < 16 ? 1.0 : 0.6); });
}

TEST(Denoise, APixelsOwnNoiseIsTheSampleVarianceOfItsMean) {
  // sol::own_variances against the two-pass sample variance of each
  // pixel's samples over samples − 1, of the mean (over the count), of
  // the light (over the albedo 0.5 squared): the same 64 samples drawn again.
  const sol::RenderResult r = shadow_edge(64, 7);
  const std::vector<double> own = sol::own_variances(r);
  ASSERT_EQ(own.size(), r.object.size());
  std::mt19937 random(7);
  std::normal_distribution<double> noise(0.0, 0.2);
  double mean_own = 0.0;
  for (std::size_t k = 0; k < own.size(); ++k) {
    const double truth = 0.5 * (k % 32 < 16 ? 1.0 : 0.6);
    std::vector<double> v(64);
    for (double& x : v) x = truth + noise(random);
    double mean = 0.0, spread = 0.0;
    for (const double x : v) mean += x / 64.0;
    for (const double x : v) spread += (x - mean) * (x - mean) / 63.0;
    // (The moment in float: its 6e-8 relative of about 0.3 against a variance of 0.04.)
    EXPECT_NEAR(own[k], spread / 64.0 / 0.25, 2e-6) << k;
    mean_own += own[k] / static_cast<double>(own.size());
  }
  // 0.2² / 64 / 0.25 of the light, on average.
  EXPECT_NEAR(mean_own, 0.04 / 64.0 / 0.25, 0.1 * 0.04 / 64.0 / 0.25);
  // One sample has no variance of its own; nor has an image without a moment.
  sol::RenderResult one = shadow_edge(1, 7), none = r;
  none.light_moment.clear();
  EXPECT_TRUE(sol::own_variances(one).empty());
  EXPECT_TRUE(sol::own_variances(none).empty());
}

TEST(Denoise, FromSixteenSamplesNoPixelMovesFurtherThanItsNoise) {
  // A flat plane of light 1 (albedo 0.5) whose samples spread 0.2 about
  // it, with scattered pixels 4 to 8 standard deviations of their mean
  // brighter (each pixel's mean and moment from its own 16 samples).
  // Filtered, every pixel's light stays within 3 of its own standard
  // deviations (its neighbours' own variances' mean, as the filter's
  // noise) of its unfiltered light; with the same image taken as 15
  // samples (no hold) the filter pulls some spikes further.
  const int w = 24, h = 24, samples = 16;
  std::mt19937 random(11);
  std::uniform_real_distribution<double> spike(4.0, 8.0);
  std::vector<double> spikes(static_cast<std::size_t>(w * h), 0.0);
  for (std::size_t k = 3; k < spikes.size(); k += 7) spikes[k] = spike(random) * 0.2 / std::sqrt(samples);
  const sol::RenderResult r = sampled_image(w, h, samples, 12, [&](std::size_t k) { return 0.5 + spikes[k]; });
  const auto furthest = [&](int as_samples) {
    sol::RenderResult image = r;
    image.samples = as_samples;
    const std::vector<double> own = sol::own_variances(image);
    sol::denoise(image);
    double worst = 0.0;  // the largest move in the pixel's own standard deviations
    for (int j = 0; j < h; ++j) {
      for (int i = 0; i < w; ++i) {
        double sum = 0.0, count = 0.0;
        for (int y = std::max(0, j - 1); y <= std::min(h - 1, j + 1); ++y) {
          for (int x = std::max(0, i - 1); x <= std::min(w - 1, i + 1); ++x) {
            sum += own[static_cast<std::size_t>(y * w + x)];
            count += 1.0;
          }
        }
        const std::size_t k = static_cast<std::size_t>(j * w + i);
        const double move = std::abs(image.rgba[4 * k] - r.rgba[4 * k]) / 0.5;  // (in light: over the albedo)
        worst = std::max(worst, move / std::sqrt(sum / count));
      }
    }
    return worst;
  };
  EXPECT_LE(furthest(samples), sol::kernel::kDenoiseClampSigmas + 1e-4);
  EXPECT_GT(furthest(samples - 1), sol::kernel::kDenoiseClampSigmas + 0.5);
}

TEST(Denoise, AColouredFireflyIsHeldByItsLuminancesNoise) {
  // Fireflies: on the grey plane of light 1 (16 samples a pixel, each of
  // grey noise 0.1), every 7th pixel has one sample with 3 more red. Its
  // noise is the luminance's, a fifth of the red excess's: held channel
  // by channel to 3 of those deviations the red kept most of its excess
  // (a red dot); held in luminance, the filter takes out most of it, as it
  // does where it is free (8 samples, no hold).
  const int w = 24, h = 24;
  const auto fireflies = [&](int samples) {
    const auto grey = [](int, int) { return 0.5; };
    sol::RenderResult r = flat_image(w, h, 1.0, 0.0, grey);
    std::mt19937 random(5);
    std::normal_distribution<double> noise(0.0, 0.1);
    r.light_moment.resize(r.object.size());
    r.samples = samples;
    for (std::size_t k = 0; k < r.object.size(); ++k) {
      glm::dvec3 sum(0.0);
      double squares = 0.0;
      for (int s = 0; s < samples; ++s) {
        glm::dvec3 v(0.5 + noise(random));
        if (k % 7 == 3 && s == 0) v.r += 3.0;
        sum += v;
        squares += std::pow(sol::kernel::sol_denoise_luminance(v), 2.0);
      }
      for (int c = 0; c < 3; ++c) r.rgba[4 * k + c] = static_cast<float>(sum[c] / samples);
      r.light_moment[k] = static_cast<float>(squares / samples);
    }
    return r;
  };
  // The fireflies' red above the plane's 0.5, filtered, over raw (3 / samples).
  const auto kept = [&](int samples) {
    sol::RenderResult r = fireflies(samples);
    sol::denoise(r);
    double excess = 0.0;
    int count = 0;
    for (std::size_t k = 3; k < r.object.size(); k += 7, ++count) excess += r.rgba[4 * k] - 0.5;
    return excess / count / (3.0 / samples);
  };
  // Measured: 0.13 at 8 samples, 0.14 at 16 (channel by channel: 0.53).
  EXPECT_LT(kept(8), 0.3);
  EXPECT_LT(kept(16), 0.3);
}

TEST(Denoise, AShadowsEdgeStaysSharpWithThePixelsOwnNoise) {
  // At 64 samples a pixel the mean's noise (0.025) is far below the
  // edge's step (0.2 of colour): the pixel's own noise makes the step an
  // edge, where the neighbours' spread (the step itself, about 0.1 of
  // light beside it) took it for noise and blurred it. Errors against the
  // truth on the two columns either side of the edge, and over the flat
  // rest (where either estimate of the noise filters).
  sol::RenderResult own = shadow_edge(64, 3), spatial = own;
  spatial.light_moment.clear();
  const sol::RenderResult raw = own;
  sol::denoise(own);
  sol::denoise(spatial);
  const auto error = [](const sol::RenderResult& r, bool edge) {
    double squares = 0.0;
    int count = 0;
    for (std::size_t k = 0; k < r.object.size(); ++k) {
      const std::size_t i = k % 32;
      if ((i >= 14 && i < 18) != edge) continue;
      const double d = r.rgba[4 * k] - 0.5 * (i < 16 ? 1.0 : 0.6);
      squares += d * d;
      ++count;
    }
    return std::sqrt(squares / count);
  };
  // Measured: edge raw 0.028, own 0.0040, spatial 0.025 (the step's
  // blur); flat raw 0.026, own and spatial 0.0018.
  EXPECT_LT(error(own, true), 0.25 * error(raw, true));
  EXPECT_LT(error(own, true), 0.25 * error(spatial, true));
  EXPECT_LT(error(own, false), 0.25 * error(raw, false));
}

}  // namespace
