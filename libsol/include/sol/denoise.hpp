// Denoising a rendered image: an edge-avoiding à-trous filter guided by the
// image's AOVs (sol/denoise.h has its weights; docs/lighting.md,
// "Denoising", the method and what it gains):
//
//   sol::RenderOptions options;                  // aovs true (the default)
//   sol::RenderResult image = renderer.render(camera, options);
//   renderer.denoise(image);                     // on the renderer's device
//   sol::denoise(image);                         // or on the host, in double
//
// The colour is replaced; the AOVs are kept. Either way the same filter:
// the kernel's (sol::vk::MarchRenderer::denoise) computes it in float.
#pragma once

#include <vector>

#include "sol/renderer.hpp"

namespace sol {

/// The checks of an image to denoise: its colour and the AOVs the filter
/// reads (object, distance, albedo, emission, normal; the light moment
/// where there is one) of its size, `samples` not negative, and `eyes` (1 or
/// 2, side by side) dividing its width; InvalidArgument naming `who` and
/// the field otherwise (an image rendered without RenderOptions::aovs has
/// none).
void validate_denoise(const RenderResult& image, int eyes, const char* who);

/// Each pixel's own noise from its samples (sol_denoise_own_variance of
/// sol/denoise.h): empty where the image has no light moment or fewer than
/// 2 samples, whose noise the filter takes from the neighbours' light.
std::vector<double> own_variances(const RenderResult& image);

/// Replaces `image`'s colour by the filter's, on the host in double, rows
/// on `threads` threads (0: all). Pixels of one eye never take from the
/// other's. Alpha is kept.
void denoise(RenderResult& image, int eyes = 1, unsigned threads = 0);

}  // namespace sol
