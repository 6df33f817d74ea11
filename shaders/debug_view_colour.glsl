// The colours of every debug view (render/debug_view_registry.h): how one texel of a renderer
// texture becomes a linear colour, as displayKind says (kDisplay* in shared.h). The one colouring
// of the views, for the viewer (display.frag) and for `render --debug-view` (debug_view.comp).
// The includer includes shared.h first.

layout(binding = 0) uniform sampler2D floatSource;
layout(binding = 1) uniform usampler2D unsignedSource;
layout(binding = 2) uniform sampler1D colourMapTable;

uniform int displayKind;
uniform bool sourceIsUnsigned;
uniform float exposureScale;  // kDisplayRadiance: 2^exposure
uniform int channel;          // kDisplayScalar, and kDisplayCategories from a float texture
uniform vec2 scalarRange;     // kDisplayScalar: the values at the two ends of the colour map
uniform int maskChannel;      // kDisplayScalar: black where this channel equals maskValue
uniform float maskValue;      //   (-1: no mask)
uniform vec3 palette[kDisplayPaletteSize];  // kDisplayLevels, kDisplayCategories

vec3 paletteColour(int index) {
  return palette[clamp(index, 0, kDisplayPaletteSize - 1)];
}

ivec2 debugViewSourceSize() {
  return sourceIsUnsigned ? textureSize(unsignedSource, 0) : textureSize(floatSource, 0);
}

// The colour of source texel `texel` (GL order: row 0 at the bottom).
vec3 debugViewColour(ivec2 texel) {
  if (sourceIsUnsigned) {
    uint value = texelFetch(unsignedSource, texel, 0).r;
    return paletteColour(int(min(value, uint(kDisplayPaletteSize - 1))));
  }
  vec4 value = texelFetch(floatSource, texel, 0);
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
