#version 450 core
#extension GL_GOOGLE_include_directive : require
// VPLs of one light: VPL (i,j) sits at the centre of cell (i,j) of the light's (u,v) grid and
// carries E times the exact mean of the emission texture over its cell (each texel weighted by
// its overlap), the same as makeVpls() in src/scene/area_light.cpp.
#include "shared.h"
#include "quad_light.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = kLightBinding) readonly buffer Lights { GpuLight lights[]; };
layout(std430, binding = kVplBinding) writeonly buffer Vpls { GpuVpl vpls[]; };

uniform int lightIndex;
// Uploaded bottom row first, so texel row y covers v in [y/h, (y+1)/h].
layout(binding = 0) uniform sampler2D emissionTexture;

vec3 cellMean(vec2 uvMin, vec2 uvMax) {
  vec2 size = vec2(textureSize(emissionTexture, 0));
  vec2 texMin = uvMin * size;
  vec2 texMax = uvMax * size;
  ivec2 first = ivec2(floor(texMin));
  ivec2 last = min(ivec2(ceil(texMax)) - 1, ivec2(size) - 1);
  vec3 sum = vec3(0.0);
  for (int y = first.y; y <= last.y; ++y) {
    float overlapY = min(float(y + 1), texMax.y) - max(float(y), texMin.y);
    for (int x = first.x; x <= last.x; ++x) {
      float overlapX = min(float(x + 1), texMax.x) - max(float(x), texMin.x);
      sum += texelFetch(emissionTexture, ivec2(x, y), 0).rgb * (overlapX * overlapY);
    }
  }
  return sum / ((texMax.x - texMin.x) * (texMax.y - texMin.y));
}

void main() {
  GpuLight light = lights[lightIndex];
  int cellsPerSide = light.vplInfo.y;
  int cell = int(gl_GlobalInvocationID.x);
  if (cell >= cellsPerSide * cellsPerSide) return;
  ivec2 cellXY = ivec2(cell % cellsPerSide, cell / cellsPerSide);
  vec2 uvMin = vec2(cellXY) / float(cellsPerSide);
  vec2 uvMax = vec2(cellXY + 1) / float(cellsPerSide);
  vec3 radiance = light.emission.rgb;
  if (light.vplInfo.z != 0) radiance *= cellMean(uvMin, uvMax);
  vec3 position = quadPointAt(light.corners[0].xyz, light.corners[1].xyz, light.corners[2].xyz,
                              light.corners[3].xyz, 0.5 * (uvMin + uvMax));
  float area = light.normalArea.w / float(cellsPerSide * cellsPerSide);
  GpuVpl vpl;
  vpl.positionArea = vec4(position, area);
  vpl.normal = vec4(light.normalArea.xyz, 0.0);
  vpl.radiance = vec4(radiance, 0.0);
  vpls[light.vplInfo.x + cell] = vpl;
}
