#version 450
// The smallest useful kernel, for testing the Vulkan host library: every pixel
// (x, y) of the image gets (x, y, push.value, 1). The grid of invocations is
// rounded up to whole 8×8 groups, so invocations outside the image must not
// write: the bounds check is part of what the test checks.

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;

layout(set = 0, binding = 0, rgba32f) uniform writeonly image2D target;

layout(push_constant) uniform Push {
  float value;
} push;

void main() {
  const ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(pixel, imageSize(target)))) return;
  imageStore(target, pixel, vec4(vec2(pixel), push.value, 1.0));
}
