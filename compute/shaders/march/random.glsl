// Random numbers of paths and of glossy reflections (path_radiance and
// radiance in libsol/src/render.cpp draw the same from the same seed).
#ifndef SOL_MARCH_RANDOM_GLSL
#define SOL_MARCH_RANDOM_GLSL

// ---- The paths' random numbers: splitmix64 (as sol's PathRandom) from the
// seed, the pixel (its index in its eye's image) and the sample, on 64-bit
// integers held as (low, high) 32-bit halves, so that the kernel draws the
// CPU's numbers without the shaderInt64 feature.

uvec2 u64_add(uvec2 a, uvec2 b) {
  uint carry;
  const uint low = uaddCarry(a.x, b.x, carry);
  return uvec2(low, a.y + b.y + carry);
}

// The low 64 bits of a b.
uvec2 u64_mul(uvec2 a, uvec2 b) {
  uint high, low;
  umulExtended(a.x, b.x, high, low);
  return uvec2(low, high + a.x * b.y + a.y * b.x);
}

// a >> s for s in [1, 31].
uvec2 u64_shr(uvec2 a, int s) { return uvec2((a.x >> uint(s)) | (a.y << uint(32 - s)), a.y >> uint(s)); }

const uvec2 kGolden = uvec2(0x7F4A7C15u, 0x9E3779B9u);  // 0x9E3779B97F4A7C15
const uvec2 kSampleMix = uvec2(0xD192ED03u, 0xD1B54A32u);  // 0xD1B54A32D192ED03

uvec2 path_random_start(uvec2 seed, uint pixel, uint sample_index) {
  return seed ^ u64_mul(kGolden, uvec2(pixel + 1u, 0u)) ^ u64_mul(kSampleMix, uvec2(sample_index + 1u, 0u));
}

// Uniform in [0, 1): the top 24 bits of the CPU's 53 (its double, rounded down to a float).
float path_uniform(inout uvec2 state) {
  state = u64_add(state, kGolden);
  uvec2 z = state;
  z = u64_mul(z ^ u64_shr(z, 30), uvec2(0x1CE4E5B9u, 0xBF58476Du));
  z = u64_mul(z ^ u64_shr(z, 27), uvec2(0x133111EBu, 0x94D049BBu));
  z = z ^ u64_shr(z, 31);
  return float(z.y >> 8u) * (1.0 / 16777216.0);
}

#endif  // SOL_MARCH_RANDOM_GLSL
