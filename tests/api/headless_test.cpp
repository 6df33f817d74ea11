// The facade on its own: this suite sees only include/penumbra/ (it links Penumbra's facade and
// nothing internal), makes its own headless context and renders in it, as a program without a
// window does.

#include <penumbra/penumbra.h>

#include <algorithm>
#include <utility>

#include <gtest/gtest.h>

namespace {

TEST(HeadlessLibrary, RendersInItsOwnContext) {
  penumbra::api::HeadlessContext context;
  EXPECT_FALSE(penumbra::api::currentGlRenderer().empty());
  // Moved, the context stays current: the renderer below works in it.
  penumbra::api::HeadlessContext kept = std::move(context);
  auto scene = penumbra::api::Scene::load(PENUMBRA_SOURCE_DIR "/scenes/shadow_box.scene");
  penumbra::api::Renderer renderer(scene, 32, 24);
  penumbra::api::Settings settings;
  settings.vplsPerLight = 4;
  renderer.render(0, settings);
  const penumbra::api::Image image = renderer.readImage();
  EXPECT_EQ(image.width, 32);
  EXPECT_EQ(image.height, 24);
  // The floor under the light is lit: some pixel is above black.
  EXPECT_GT(*std::max_element(image.rgba.begin(), image.rgba.end()), 0.0f);
}

}  // namespace
