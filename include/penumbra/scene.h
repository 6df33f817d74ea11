#pragma once
// A scene ready to render: its models, textures and videos loaded.

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace penumbra {
struct Scene;
}

namespace penumbra::api {

class Scene {
 public:
  // Parses a scene file (docs/scene-format.md) and loads what it names, relative to the file.
  // Throws Error (BadInput) with file:line:col.
  static Scene load(const std::filesystem::path& file);

  Scene(Scene&&) noexcept;
  Scene& operator=(Scene&&) noexcept;
  ~Scene();

  // The camera's image size in the scene (`camera ... size`).
  int width() const;
  int height() const;
  // Things the loader fixed up, e.g. "no camera: made one framing the scene".
  const std::vector<std::string>& warnings() const;

 private:
  friend class Renderer;
  explicit Scene(std::unique_ptr<penumbra::Scene> scene);
  std::unique_ptr<penumbra::Scene> scene_;
};

}  // namespace penumbra::api
