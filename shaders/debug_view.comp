#version 450 core
#extension GL_GOOGLE_include_directive : require
// `render --debug-view`: one debug view coloured as the viewer colours it
// (debug_view_colour.glsl), texel for texel, into a linear RGBA32F image of the source's size.
#include "shared.h"
#include "debug_view_colour.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(binding = 0, rgba32f) uniform writeonly image2D colourOut;

void main() {
  ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(texel, debugViewSourceSize()))) return;
  imageStore(colourOut, texel, vec4(debugViewColour(texel), 1.0));
}
