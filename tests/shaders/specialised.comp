#version 450
// A test of specialisation constants folded into SPIR-V (sol::vk::specialize_spirv):
// each pixel (x, y) gets ((x + OFFSET) * SCALE, y, SQUARE ? squared(...) : 0, 1).
layout(local_size_x = 8, local_size_y = 8) in;
layout(constant_id = 0) const bool SQUARE = false;
layout(constant_id = 1) const int OFFSET = 0;
layout(constant_id = 2) const float SCALE = 1.0;
const int DOUBLED = 2 * OFFSET;  // a constant expression of a constant (OpSpecConstantOp)
layout(set = 0, binding = 0, rgba32f) uniform writeonly image2D result;

// Called only where SQUARE: folded away otherwise, though its guard also
// reads a value known only at run time (as the kernel's `HAS_X && type ==
// code`: glslang writes an OpLogicalAnd, which only constant propagation
// folds).
float squared(float v) { return v * v + float(DOUBLED); }

void main() {
  const ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  const float v = float(p.x + OFFSET) * SCALE;
  float w = 0.0;
  if (SQUARE && p.y >= 0) w = squared(v);
  imageStore(result, p, vec4(v, float(p.y), w, 1.0));
}
