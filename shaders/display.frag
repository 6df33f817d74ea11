#version 450 core
#extension GL_GOOGLE_include_directive : require
// The viewer's picture: one debug view (debug_view_colour.glsl) stretched over the viewport
// (nearest texel), and written sRGB-encoded as the 8-bit outputs of `penumbra render` store
// their pixels.
#include "shared.h"
#include "debug_view_colour.glsl"

uniform ivec2 viewportSize;

layout(location = 0) out vec4 outColour;

vec3 linearToSrgb(vec3 linear) {
  vec3 low = 12.92 * linear;
  vec3 high = 1.055 * pow(linear, vec3(1.0 / 2.4)) - 0.055;
  return mix(high, low, lessThanEqual(linear, vec3(0.0031308)));
}

void main() {
  ivec2 sourceSize = debugViewSourceSize();
  vec2 scale = vec2(sourceSize) / vec2(viewportSize);
  vec3 colour = debugViewColour(min(ivec2(gl_FragCoord.xy * scale), sourceSize - 1));
  // NaN shows as black, as in the 8-bit outputs.
  colour = mix(colour, vec3(0.0), isnan(colour));
  outColour = vec4(linearToSrgb(clamp(colour, 0.0, 1.0)), 1.0);
}
