#version 450
// Test kernel: copies a uniform of each type the setters of gl/uniforms.h take into the output
// buffer. `notRead` is declared and never read, so the GLSL compiler removes it.

layout(local_size_x = 1) in;

layout(std430, binding = 0) writeonly buffer Output { float values[16]; };

uniform int anInt;
uniform uint anUnsigned;
uniform float aFloat;
uniform vec2 aVec2;
uniform ivec2 anIvec2;
uniform uvec2 aUvec2;
uniform vec3 aVec3;
uniform vec4 aVec4;
uniform float notRead;

void main() {
  values[0] = float(anInt);
  values[1] = float(anUnsigned);
  values[2] = aFloat;
  values[3] = aVec2.x;
  values[4] = aVec2.y;
  values[5] = float(anIvec2.x);
  values[6] = float(anIvec2.y);
  values[7] = float(aUvec2.x);
  values[8] = float(aUvec2.y);
  values[9] = aVec3.x;
  values[10] = aVec3.y;
  values[11] = aVec3.z;
  values[12] = aVec4.x;
  values[13] = aVec4.y;
  values[14] = aVec4.z;
  values[15] = aVec4.w;
}
