#pragma once
// Indirect light, pass 1: reflective shadow maps. Each light sees the scene through five faces
// of a cube around its centre (the face along its normal and the four sides; the half of a side
// face behind the light sees nothing the light reaches), each face a small G-buffer rendered by
// the G-buffer pass. A compute pass then gives every texel the direct light it receives from
// its own light's VPLs, without visibility (the secondary VPLs get theirs,
// secondary_visibility.h), and stores the diffuse radiance it reflects. The results sit in three
// atlas textures: the five faces side by side, one row of faces per light.

#include <memory>
#include <vector>

#include "gl/handles.h"
#include "gl/program.h"
#include "image/image.h"
#include "render/gbuffer.h"
#include "render/scene_gpu.h"
#include "render/vpls.h"

namespace penumbra {

class ReflectiveShadowMap {
 public:
  // faceSize texels per side of each face.
  ReflectiveShadowMap(int faceSize, int lightCount);

  int faceSize() const { return faceSize_; }
  int lightCount() const { return lightCount_; }
  glm::ivec2 atlasSize() const;
  GBuffer& face(int light, int face) { return *faces_[static_cast<std::size_t>(light * 5 + face)]; }

  gl::Texture positionArea{GL_TEXTURE_2D};  // xyz world position, w surface area of the texel
  gl::Texture normal{GL_TEXTURE_2D};        // xyz unit normal on the light's side, w 1 if valid
  gl::Texture radiance{GL_TEXTURE_2D};      // rgb diffuse radiance the texel reflects

  // The three atlases read back in texel order: row y is the atlas's texel row y, so that light
  // l's faces fill rows l * faceSize to (l + 1) * faceSize - 1, as RsmPass::run lays them out.
  struct Texels {
    Image positionArea;
    Image normal;
    Image radiance;
  };
  Texels read() const;

 private:
  int faceSize_;
  int lightCount_;
  std::vector<std::unique_ptr<GBuffer>> faces_;  // light * 5 + face
};

class RsmPass {
 public:
  struct Inputs {
    const SceneGpu& scene;
    const VplBuffer& vpls;  // the primary VPLs, whose light the maps reflect
  };
  struct Outputs {
    ReflectiveShadowMap& maps;
  };

  RsmPass();
  void run(const Inputs& in, const Outputs& out) const;

 private:
  GBufferPass gbufferPass_;  // without shadow-ray starts, which the maps do not use
  gl::Program flux_;
};

}  // namespace penumbra
