// Image textures on objects, their mapping written once for the CPU
// renderer (double) and the kernels (float): an object's pattern
// coordinates (u, v) (sol/patterns.h, each kind's own) place one copy of
// the image over `cells` = (cu, cv) pattern cells, its centre at (0, 0),
// repeated in both directions; the colour there is the bilinear mean of
// the four nearest texels (their centres at ((i + 1/2) / W, 1 − (j + 1/2) /
// H) of the unit square, row 0 at the image's top, v upwards), wrapping at
// the image's edges. A ball's longitude and latitude span 8 and 4 cells:
// cells (8, 4) wrap an equirectangular image once around it. Valid C++
// (namespace sol::kernel, double) and GLSL (float), as sol/patterns.h.
#ifndef SOL_TEXTURE_H
#define SOL_TEXTURE_H

#include "sol/kernel_constants.h"

#ifdef __cplusplus
#include <cmath>
#include <glm/vec2.hpp>
#include <glm/vec4.hpp>
namespace sol::kernel {
#define SOL_TEXTURE_FUNCTION inline
#define SOL_TEXTURE_VEC2 glm::dvec2
#define SOL_TEXTURE_IVEC4 glm::ivec4
#define SOL_TEXTURE_OUT(type) type&
#define sol_texture_floor(x) std::floor(x)
#else
#define SOL_TEXTURE_FUNCTION
#define SOL_TEXTURE_VEC2 vec2
#define SOL_TEXTURE_IVEC4 ivec4
#define SOL_TEXTURE_OUT(type) out type
#define sol_texture_floor(x) floor(x)
#endif

// The four texels around pattern coordinates `uv` of an image of `width`
// × `height` texels spread over `cells`: their columns i0, i1 and rows j0,
// j1 in `texels` (x, z and y, w) and the weights of i1 and j1 in `along`
// (bilinear: (1 − a.x)(1 − a.y) for (i0, j0), ...).
SOL_TEXTURE_FUNCTION void sol_texture_taps(SOL_TEXTURE_VEC2 uv, SOL_TEXTURE_VEC2 cells, int width, int height,
                                           SOL_TEXTURE_OUT(SOL_TEXTURE_IVEC4) texels, SOL_TEXTURE_OUT(SOL_TEXTURE_VEC2) along) {
  // The point in the unit square: s rightwards, t upwards, (1/2, 1/2) at uv = 0.
  const SOL_REAL s = uv.x / cells.x + 0.5, t = uv.y / cells.y + 0.5;
  const SOL_REAL x = (s - sol_texture_floor(s)) * SOL_REAL(width) - 0.5;
  const SOL_REAL y = (1.0 - (t - sol_texture_floor(t))) * SOL_REAL(height) - 0.5;
  const SOL_REAL x0 = sol_texture_floor(x), y0 = sol_texture_floor(y);
  along = SOL_TEXTURE_VEC2(x - x0, y - y0);
  int i0 = int(x0), j0 = int(y0);
  // (x in [-1/2, W - 1/2): i0 from -1 to W - 1; wrapped into [0, W).)
  if (i0 < 0) i0 += width;
  if (j0 < 0) j0 += height;
  if (i0 >= width) i0 -= width;
  if (j0 >= height) j0 -= height;
  const int i1 = i0 + 1 >= width ? 0 : i0 + 1, j1 = j0 + 1 >= height ? 0 : j0 + 1;
  texels = SOL_TEXTURE_IVEC4(i0, j0, i1, j1);
}

#undef SOL_TEXTURE_FUNCTION
#undef SOL_TEXTURE_VEC2
#undef SOL_TEXTURE_IVEC4
#undef SOL_TEXTURE_OUT
#undef sol_texture_floor
#ifdef __cplusplus
}  // namespace sol::kernel
#endif

#endif  // SOL_TEXTURE_H
