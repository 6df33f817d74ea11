#version 450 core
#extension GL_GOOGLE_include_directive : require
// The viewer's picture: one texture of the renderer stretched over the viewport (nearest
// texel), shown as displayKind says (kDisplay* in shared.h), and written sRGB-encoded as the
// 8-bit outputs of `penumbra render` store their pixels.
#include "shared.h"

layout(binding = 0) uniform sampler2D floatSource;
layout(binding = 1) uniform usampler2D unsignedSource;
layout(binding = 2) uniform sampler1D colourMapTable;

uniform int displayKind;
uniform bool sourceIsUnsigned;
uniform ivec2 viewportSize;
uniform float exposureScale;  // kDisplayRadiance: 2^exposure
uniform int channel;          // kDisplayScalar, and kDisplayCategories from a float texture
uniform vec2 scalarRange;     // kDisplayScalar: the values at the two ends of the colour map
uniform int maskChannel;      // kDisplayScalar: black where this channel equals maskValue
uniform float maskValue;      //   (-1: no mask)
uniform vec3 palette[kDisplayPaletteSize];  // kDisplayLevels, kDisplayCategories

layout(location = 0) out vec4 outColour;

vec3 linearToSrgb(vec3 linear) {
  vec3 low = 12.92 * linear;
  vec3 high = 1.055 * pow(linear, vec3(1.0 / 2.4)) - 0.055;
  return mix(high, low, lessThanEqual(linear, vec3(0.0031308)));
}

ivec2 sourceTexel(ivec2 sourceSize) {
  vec2 scale = vec2(sourceSize) / vec2(viewportSize);
  return min(ivec2(gl_FragCoord.xy * scale), sourceSize - 1);
}

vec3 paletteColour(int index) {
  return palette[clamp(index, 0, kDisplayPaletteSize - 1)];
}

vec3 displayedColour() {
  if (sourceIsUnsigned) {
    uint value = texelFetch(unsignedSource, sourceTexel(textureSize(unsignedSource, 0)), 0).r;
    return paletteColour(int(min(value, uint(kDisplayPaletteSize - 1))));
  }
  vec4 value = texelFetch(floatSource, sourceTexel(textureSize(floatSource, 0)), 0);
  if (displayKind == kDisplayRadiance) return value.rgb * exposureScale;
  if (displayKind == kDisplayColour) return value.rgb;
  if (displayKind == kDisplayNormal) {
    return value.w == 0.0 ? vec3(0.0) : 0.5 * value.xyz + 0.5;
  }
  if (displayKind == kDisplayScalar) {
    if (maskChannel >= 0 && value[maskChannel] == maskValue) return vec3(0.0);
    float t = (value[channel] - scalarRange.x) / max(scalarRange.y - scalarRange.x, 1e-30);
    // Texel centres hold the ends of the colour map: t = 0 and 1 sample the first and last.
    float tableSize = float(textureSize(colourMapTable, 0));
    return texture(colourMapTable, (clamp(t, 0.0, 1.0) * (tableSize - 1.0) + 0.5) / tableSize).rgb;
  }
  if (displayKind == kDisplayLevels) {
    // w = 1 + the level the value came from, negative for unlit texels, 0 where nothing was lit.
    int source = int(round(abs(value.w))) - 1;
    if (source < 0) return vec3(0.0);
    return value.w < 0.0 ? 0.3 * paletteColour(source) : paletteColour(source);
  }
  return paletteColour(int(round(value[channel])));
}

void main() {
  vec3 colour = displayedColour();
  // NaN shows as black, as in the 8-bit outputs.
  colour = mix(colour, vec3(0.0), isnan(colour));
  outColour = vec4(linearToSrgb(clamp(colour, 0.0, 1.0)), 1.0);
}
