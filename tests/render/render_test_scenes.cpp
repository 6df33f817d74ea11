#include "render/render_test_scenes.h"

#include <cmath>
#include <numbers>

#include "test_files.h"

namespace penumbra::test {

Scene loadSceneText(const std::filesystem::path& directory, const std::string& text,
                    const std::string& name) {
  return loadScene(parseSceneFile(writeFile(directory, name, text)));
}

Image cellCuttingPicture() {
  Image picture(5, 3);
  for (int y = 0; y < picture.height; ++y)
    for (int x = 0; x < picture.width; ++x)
      picture.at(x, y) =
          glm::vec4(0.2f + 0.2f * static_cast<float>(x), 1.0f - 0.3f * static_cast<float>(y),
                    static_cast<float>((x + y) % 2), 1.0f);
  return picture;
}

int leaveOutEdgeOnPixels(const Image& gpu, const Image& reference, std::vector<bool>& compared) {
  int edgeOnPixels = 0;
  for (std::size_t i = 0; i < compared.size(); ++i) {
    const glm::vec3 difference = glm::abs(glm::vec3(gpu.pixels[i] - reference.pixels[i]));
    const glm::vec3 scale = glm::abs(glm::vec3(reference.pixels[i])) + 0.01f;
    if (compared[i] && glm::any(glm::greaterThan(difference, 0.01f * scale))) {
      compared[i] = false;
      ++edgeOnPixels;
    }
  }
  return edgeOnPixels;
}

double cornerFormFactor(double a, double b, double h) {
  const double x = a / h;
  const double y = b / h;
  const double rootX = std::sqrt(1.0 + x * x);
  const double rootY = std::sqrt(1.0 + y * y);
  return (x / rootX * std::atan(y / rootX) + y / rootY * std::atan(x / rootY)) /
         (2.0 * std::numbers::pi);
}

}  // namespace penumbra::test
