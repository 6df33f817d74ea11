#include "render/gl_state.h"

#include <algorithm>
#include <cstddef>

namespace penumbra {
namespace {

struct Capability {
  GLenum name;
  GLboolean initial;
};
// The switches that change what the renderer's draws and copies produce, or that it sets.
constexpr Capability kCapabilities[] = {
    {GL_DEPTH_TEST, GL_FALSE},
    {GL_CULL_FACE, GL_FALSE},
    {GL_BLEND, GL_FALSE},
    {GL_SCISSOR_TEST, GL_FALSE},
    {GL_STENCIL_TEST, GL_FALSE},
    {GL_RASTERIZER_DISCARD, GL_FALSE},
    {GL_POLYGON_OFFSET_FILL, GL_FALSE},
    {GL_POLYGON_SMOOTH, GL_FALSE},
    {GL_COLOR_LOGIC_OP, GL_FALSE},
    {GL_DEPTH_CLAMP, GL_FALSE},
    {GL_FRAMEBUFFER_SRGB, GL_FALSE},
    {GL_SAMPLE_ALPHA_TO_COVERAGE, GL_FALSE},
    {GL_SAMPLE_COVERAGE, GL_FALSE},
    {GL_SAMPLE_MASK, GL_FALSE},
    {GL_MULTISAMPLE, GL_TRUE},
    {GL_PRIMITIVE_RESTART, GL_FALSE},
    {GL_PRIMITIVE_RESTART_FIXED_INDEX, GL_FALSE},
    {GL_CLIP_DISTANCE0, GL_FALSE},
    {GL_CLIP_DISTANCE1, GL_FALSE},
    {GL_CLIP_DISTANCE2, GL_FALSE},
    {GL_CLIP_DISTANCE3, GL_FALSE},
    {GL_CLIP_DISTANCE4, GL_FALSE},
    {GL_CLIP_DISTANCE5, GL_FALSE},
    {GL_CLIP_DISTANCE6, GL_FALSE},
    {GL_CLIP_DISTANCE7, GL_FALSE},
};
constexpr std::array<GLenum, 8> kBufferTargets{GL_ARRAY_BUFFER,         GL_DISPATCH_INDIRECT_BUFFER,
                                               GL_DRAW_INDIRECT_BUFFER, GL_PIXEL_PACK_BUFFER,
                                               GL_PIXEL_UNPACK_BUFFER,  GL_SHADER_STORAGE_BUFFER,
                                               GL_UNIFORM_BUFFER,       GL_ATOMIC_COUNTER_BUFFER};
constexpr std::array<GLenum, 8> kBufferBindingQueries{
    GL_ARRAY_BUFFER_BINDING,         GL_DISPATCH_INDIRECT_BUFFER_BINDING,
    GL_DRAW_INDIRECT_BUFFER_BINDING, GL_PIXEL_PACK_BUFFER_BINDING,
    GL_PIXEL_UNPACK_BUFFER_BINDING,  GL_SHADER_STORAGE_BUFFER_BINDING,
    GL_UNIFORM_BUFFER_BINDING,       GL_ATOMIC_COUNTER_BUFFER_BINDING};
constexpr std::array<GLenum, 5> kTextureTargets{GL_TEXTURE_2D, GL_TEXTURE_2D_ARRAY, GL_TEXTURE_3D,
                                                GL_TEXTURE_CUBE_MAP, GL_TEXTURE_BUFFER};
constexpr std::array<GLenum, 5> kTextureBindingQueries{
    GL_TEXTURE_BINDING_2D, GL_TEXTURE_BINDING_2D_ARRAY, GL_TEXTURE_BINDING_3D,
    GL_TEXTURE_BINDING_CUBE_MAP, GL_TEXTURE_BINDING_BUFFER};

GLint integer(GLenum name) {
  GLint value = 0;
  glGetIntegerv(name, &value);
  return value;
}

GLint integerAt(GLenum name, GLuint index) {
  GLint value = 0;
  glGetIntegeri_v(name, index, &value);
  return value;
}

// The binding points of an indexed target that are captured: the first kCapturedBindingPoints
// of those the implementation has.
GLuint capturedCount(GLenum limit) {
  return std::min(static_cast<GLuint>(integer(limit)), kCapturedBindingPoints);
}

std::vector<GlState::BufferRange> captureRanges(GLenum limit, GLenum binding, GLenum start,
                                                GLenum size) {
  std::vector<GlState::BufferRange> ranges(capturedCount(limit));
  for (GLuint index = 0; index < ranges.size(); ++index) {
    GlState::BufferRange& range = ranges[index];
    range.buffer = integerAt(binding, index);
    glGetInteger64i_v(start, index, &range.start);
    glGetInteger64i_v(size, index, &range.size);
  }
  return ranges;
}

// A size of 0 is how GL reports a whole-buffer binding (glBindBufferBase).
void restoreRanges(GLenum target, const std::vector<GlState::BufferRange>& ranges) {
  for (GLuint index = 0; index < ranges.size(); ++index) {
    const GlState::BufferRange& range = ranges[index];
    const auto buffer = static_cast<GLuint>(range.buffer);
    if (buffer == 0 || range.size == 0)
      glBindBufferBase(target, index, buffer);
    else
      glBindBufferRange(target, index, buffer, static_cast<GLintptr>(range.start),
                        static_cast<GLsizeiptr>(range.size));
  }
}

}  // namespace

GlState GlState::capture() {
  GlState state;
  state.drawFramebuffer = integer(GL_DRAW_FRAMEBUFFER_BINDING);
  state.readFramebuffer = integer(GL_READ_FRAMEBUFFER_BINDING);
  glGetIntegerv(GL_VIEWPORT, state.viewport.data());
  glGetIntegerv(GL_SCISSOR_BOX, state.scissorBox.data());
  for (const Capability& capability : kCapabilities)
    state.capabilities.push_back(glIsEnabled(capability.name));
  state.depthFunc = integer(GL_DEPTH_FUNC);
  glGetBooleanv(GL_DEPTH_WRITEMASK, &state.depthMask);
  glGetBooleanv(GL_COLOR_WRITEMASK, state.colorMask.data());
  // Core profiles have one mode for both faces; the query may still answer two values.
  GLint polygonModes[2] = {GL_FILL, GL_FILL};
  glGetIntegerv(GL_POLYGON_MODE, polygonModes);
  state.polygonMode = polygonModes[0];
  state.clipOrigin = integer(GL_CLIP_ORIGIN);
  state.clipDepthMode = integer(GL_CLIP_DEPTH_MODE);
  state.program = integer(GL_CURRENT_PROGRAM);
  state.vertexArray = integer(GL_VERTEX_ARRAY_BINDING);
  for (std::size_t i = 0; i < kBufferTargets.size(); ++i)
    state.buffers[i] = integer(kBufferBindingQueries[i]);
  state.storageBuffers =
      captureRanges(GL_MAX_SHADER_STORAGE_BUFFER_BINDINGS, GL_SHADER_STORAGE_BUFFER_BINDING,
                    GL_SHADER_STORAGE_BUFFER_START, GL_SHADER_STORAGE_BUFFER_SIZE);
  state.uniformBuffers = captureRanges(GL_MAX_UNIFORM_BUFFER_BINDINGS, GL_UNIFORM_BUFFER_BINDING,
                                       GL_UNIFORM_BUFFER_START, GL_UNIFORM_BUFFER_SIZE);
  state.atomicCounterBuffers =
      captureRanges(GL_MAX_ATOMIC_COUNTER_BUFFER_BINDINGS, GL_ATOMIC_COUNTER_BUFFER_BINDING,
                    GL_ATOMIC_COUNTER_BUFFER_START, GL_ATOMIC_COUNTER_BUFFER_SIZE);

  state.activeTexture = integer(GL_ACTIVE_TEXTURE);
  state.textureUnits.resize(capturedCount(GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS));
  for (GLuint unit = 0; unit < state.textureUnits.size(); ++unit) {
    TextureUnit& captured = state.textureUnits[unit];
    glActiveTexture(GL_TEXTURE0 + unit);
    for (std::size_t i = 0; i < kTextureTargets.size(); ++i)
      captured.textures[i] = integer(kTextureBindingQueries[i]);
    captured.sampler = integer(GL_SAMPLER_BINDING);
  }
  glActiveTexture(static_cast<GLenum>(state.activeTexture));

  state.imageUnits.resize(capturedCount(GL_MAX_IMAGE_UNITS));
  for (GLuint unit = 0; unit < state.imageUnits.size(); ++unit) {
    ImageUnit& image = state.imageUnits[unit];
    image.texture = integerAt(GL_IMAGE_BINDING_NAME, unit);
    image.level = integerAt(GL_IMAGE_BINDING_LEVEL, unit);
    glGetBooleani_v(GL_IMAGE_BINDING_LAYERED, unit, &image.layered);
    image.layer = integerAt(GL_IMAGE_BINDING_LAYER, unit);
    image.access = integerAt(GL_IMAGE_BINDING_ACCESS, unit);
    image.format = integerAt(GL_IMAGE_BINDING_FORMAT, unit);
  }
  state.packAlignment = integer(GL_PACK_ALIGNMENT);
  state.unpackAlignment = integer(GL_UNPACK_ALIGNMENT);
  return state;
}

GlState GlState::initial(const GlState& captured) {
  GlState state;
  state.viewport = captured.viewport;
  state.scissorBox = captured.scissorBox;
  for (const Capability& capability : kCapabilities)
    state.capabilities.push_back(capability.initial);
  state.storageBuffers.resize(captured.storageBuffers.size());
  state.uniformBuffers.resize(captured.uniformBuffers.size());
  state.atomicCounterBuffers.resize(captured.atomicCounterBuffers.size());
  state.textureUnits.resize(captured.textureUnits.size());
  state.imageUnits.resize(captured.imageUnits.size());
  return state;
}

void GlState::restore() const {
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, static_cast<GLuint>(drawFramebuffer));
  glBindFramebuffer(GL_READ_FRAMEBUFFER, static_cast<GLuint>(readFramebuffer));
  glViewport(viewport[0], viewport[1], viewport[2], viewport[3]);
  glScissor(scissorBox[0], scissorBox[1], scissorBox[2], scissorBox[3]);
  for (std::size_t i = 0; i < capabilities.size(); ++i) {
    if (capabilities[i] == GL_TRUE)
      glEnable(kCapabilities[i].name);
    else
      glDisable(kCapabilities[i].name);
  }
  glDepthFunc(static_cast<GLenum>(depthFunc));
  glDepthMask(depthMask);
  glColorMask(colorMask[0], colorMask[1], colorMask[2], colorMask[3]);
  glPolygonMode(GL_FRONT_AND_BACK, static_cast<GLenum>(polygonMode));
  glClipControl(static_cast<GLenum>(clipOrigin), static_cast<GLenum>(clipDepthMode));
  // A program deleted while current stays current, and GL_CURRENT_PROGRAM names it, until
  // another is used; once the renderer has used its own, that name is gone and cannot be given
  // back (GL_INVALID_VALUE). The host had deleted it, so it gets no program, as after any use.
  const auto hostProgram = static_cast<GLuint>(program);
  glUseProgram(hostProgram != 0 && glIsProgram(hostProgram) == GL_TRUE ? hostProgram : 0);
  glBindVertexArray(static_cast<GLuint>(vertexArray));
  // The indexed bindings also set their target's generic binding, so they go first.
  restoreRanges(GL_SHADER_STORAGE_BUFFER, storageBuffers);
  restoreRanges(GL_UNIFORM_BUFFER, uniformBuffers);
  restoreRanges(GL_ATOMIC_COUNTER_BUFFER, atomicCounterBuffers);
  for (std::size_t i = 0; i < kBufferTargets.size(); ++i)
    glBindBuffer(kBufferTargets[i], static_cast<GLuint>(buffers[i]));

  for (GLuint unit = 0; unit < textureUnits.size(); ++unit) {
    glActiveTexture(GL_TEXTURE0 + unit);
    for (std::size_t i = 0; i < kTextureTargets.size(); ++i)
      glBindTexture(kTextureTargets[i], static_cast<GLuint>(textureUnits[unit].textures[i]));
    glBindSampler(unit, static_cast<GLuint>(textureUnits[unit].sampler));
  }
  glActiveTexture(static_cast<GLenum>(activeTexture));

  for (GLuint unit = 0; unit < imageUnits.size(); ++unit) {
    const ImageUnit& image = imageUnits[unit];
    glBindImageTexture(unit, static_cast<GLuint>(image.texture), image.level, image.layered,
                       image.layer, static_cast<GLenum>(image.access),
                       static_cast<GLenum>(image.format));
  }
  glPixelStorei(GL_PACK_ALIGNMENT, packAlignment);
  glPixelStorei(GL_UNPACK_ALIGNMENT, unpackAlignment);
}

}  // namespace penumbra
