#version 450
// The display of a linear image (sol::vk::DisplayPass): every pixel's colour
// scaled by the exposure's 2^stops and shown through the tone curve
// (sol/tone.h), alpha kept; written to a float image whose values a blit
// into an sRGB swapchain image encodes as solrender's 8-bit files do.
#extension GL_GOOGLE_include_directive : require

#include "sol/tone.h"

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;

layout(set = 0, binding = 0, rgba32f) uniform readonly image2D linear_image;
layout(set = 0, binding = 1, rgba32f) uniform writeonly image2D shown_image;

layout(push_constant) uniform Push {
  ivec2 size;   // the pixels to show: [0, size.x) x [0, size.y)
  float scale;  // 2^exposure
  int tone;     // the curve's code
} push;

void main() {
  const ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(pixel, push.size))) return;
  const vec4 c = imageLoad(linear_image, pixel);
  imageStore(shown_image, pixel,
             vec4(sol_tone(push.tone, c.r * push.scale), sol_tone(push.tone, c.g * push.scale),
                  sol_tone(push.tone, c.b * push.scale), c.a));
}
