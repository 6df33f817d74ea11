#version 450
// Test kernel: element i of the output buffer becomes 2 * i.

layout(local_size_x = 64) in;

layout(std430, binding = 0) writeonly buffer Output { uint values[]; };

uniform uint valueCount;

void main() {
  uint index = gl_GlobalInvocationID.x;
  if (index < valueCount) values[index] = index * 2u;
}
