#pragma once
// Pass 1: the G-buffer from the camera. Surfaces write position and linear depth, normal and
// pixel kind, albedo, specular colour and exponent, their ambient term, and where their shadow
// rays start (the lift and the face normal); light quads write their emission (black from behind).
// Background pixels stay zero (kind kPixelBackground). A batch whose box lies wholly outside one
// plane of the view is not drawn (Camera::maySeeBox). The reflective shadow maps draw the scene's
// simplified triangles (Triangles::simplifiedForMaps).

#include "gl/handles.h"
#include "gl/program.h"
#include "render/scene_gpu.h"

namespace penumbra {

struct GBuffer {
  explicit GBuffer(glm::ivec2 size);
  static constexpr int kColourTargets = 7;  // the textures below but depth, in draw-buffer order

  glm::ivec2 size;
  gl::Texture positionDepth{GL_TEXTURE_2D};  // xyz world position, w distance to the eye
  gl::Texture normalKind{GL_TEXTURE_2D};     // xyz normal facing the eye, w pixel kind
  gl::Texture albedo{GL_TEXTURE_2D};         // rgb diffuse albedo (dif * texture)
  gl::Texture specular{GL_TEXTURE_2D};       // rgb k_s, w Phong exponent
  gl::Texture emission{GL_TEXTURE_2D};       // rgb emission (lights) or ambient (surfaces)
  // Where shadow rays start (docs/shadows.md): xyz the shadow-terminator lift, from the position
  // to the point lifted onto the surface the smooth normals describe (zero on flat triangles).
  gl::Texture shadowLift{GL_TEXTURE_2D};
  // xyz the triangle's unit normal facing the eye, w its mesh's index plus one (0 on lights), so
  // that the visibility pass can tell where two surfaces touch (visibility_select.comp)
  gl::Texture faceNormal{GL_TEXTURE_2D};
  gl::Texture depth{GL_TEXTURE_2D};
  gl::Framebuffer framebuffer;
};

class GBufferPass {
 public:
  struct Inputs {
    const SceneGpu& scene;
    const Camera& camera;
  };
  struct Outputs {
    GBuffer& gbuffer;
  };

  // Whether the surfaces' pixels hold where their shadow rays start.
  enum class ShadowRayStarts {
    written,  // the lift and the face normal with its mesh: the camera's G-buffer
    // Left zero: the reflective shadow map's faces, which only place and colour secondary VPLs,
    // and the camera's G-buffer in frames without shadows.
    // The starts need the triangle's corners, read by gl_PrimitiveID, and with them llvmpipe drew
    // the dragon's five faces in 310 to 330 ms a frame against 185 to 215 ms without
    // (docs/indirect.md).
    skipped,
  };

  // Which of the scene's triangles are drawn.
  enum class Triangles {
    full,  // the scene's own
    // The reflective shadow maps' (FrameGeometry::mapTriangles): big meshes simplified to about
    // a texel's size, without which the dragon's took 84 ms of the maps' 107 at 64x64 texels a
    // face. Only with the starts skipped, which read the full triangles by their index.
    simplifiedForMaps,
  };

  // Throws std::invalid_argument for simplified triangles with the starts written.
  explicit GBufferPass(ShadowRayStarts starts = ShadowRayStarts::written,
                       Triangles triangles = Triangles::full);
  void run(const Inputs& in, const Outputs& out) const;

 private:
  ShadowRayStarts starts_;
  Triangles triangles_;
  gl::Program surfaces_;
  gl::Program lights_;
};

}  // namespace penumbra
