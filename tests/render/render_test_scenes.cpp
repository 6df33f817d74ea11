#include "render/render_test_scenes.h"

#include <cmath>
#include <numbers>

#include "test_files.h"

namespace penumbra::test {

Scene loadSceneText(const std::filesystem::path& directory, const std::string& text,
                    const std::string& name) {
  return loadScene(parseSceneFile(writeFile(directory, name, text)));
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
