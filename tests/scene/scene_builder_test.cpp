// Scenes built in memory: every check of the parser that is about values (not syntax) has its
// counterpart here, failing with the same message. The syntax errors (unknown keys, value counts,
// unclosed blocks, missing required keys) have none: a struct has every field.

#include <cmath>
#include <functional>
#include <limits>
#include <ostream>

#include <gtest/gtest.h>

#include "scene/scene.h"
#include "scene/scene_builder.h"
#include "test_files.h"

namespace penumbra {
namespace {

struct Counterpart {
  std::string name;
  std::string sceneText;  // `DIR` stands for the scratch directory
  std::function<void(SceneBuilder&, const std::filesystem::path& directory)> build;
};

// Test names and failure messages show the case's name, not its bytes.
void PrintTo(const Counterpart& counterpart, std::ostream* out) {
  *out << counterpart.name;
}

std::string withDirectory(std::string text, const std::filesystem::path& directory) {
  for (std::size_t at = text.find("DIR"); at != std::string::npos; at = text.find("DIR", at))
    text.replace(at, 3, directory.string());
  return text;
}

std::string errorOf(const std::function<void()>& action) {
  try {
    action();
  } catch (const SceneError& error) {
    return error.message();
  }
  return "(no error)";
}

MaterialDesc material(const std::string& name) {
  MaterialDesc result;
  result.name = name;
  return result;
}

AreaLightDesc light(const std::string& name, std::array<glm::vec3, 4> corners) {
  AreaLightDesc result;
  result.name = name;
  result.corners = corners;
  result.material = "glow";
  return result;
}

constexpr std::array<glm::vec3, 4> kUnitSquare = {glm::vec3(0, 0, 0), glm::vec3(1, 0, 0),
                                                  glm::vec3(1, 1, 0), glm::vec3(0, 1, 0)};

CameraDesc camera(const std::string& name) {
  CameraDesc result;
  result.name = name;
  result.position = {0, 0, 1};
  return result;
}

ObjectDesc object(const std::filesystem::path& model) {
  ObjectDesc result;
  result.model = model;
  return result;
}

const float kNaN = std::numeric_limits<float>::quiet_NaN();

// The parser locates errors in the file; the API at the description's `where`. The locations
// that messages quote (first definitions) are given the parser's, so that the texts compare.
SourceLocation at(int line, int column) {
  return {"test.scene", line, column};
}

std::vector<Counterpart> counterparts() {
  const std::string camera1 = "camera c\n  pos 0 0 1\n  at 0 0 0\n";
  const std::string light1 =
      "material glow\nend\narea_light tv\n  pos1 0 0 0\n  pos2 1 0 0\n"
      "  pos3 1 1 0\n  pos4 0 1 0\n  mat glow\nend\n";
  const auto cameraWith = [](const std::function<void(CameraDesc&)>& change) {
    return [change](SceneBuilder& builder, const std::filesystem::path&) {
      CameraDesc desc = camera("c");
      change(desc);
      builder.setCamera(desc);
    };
  };
  const auto materialWith = [](const std::function<void(MaterialDesc&)>& change) {
    return [change](SceneBuilder& builder, const std::filesystem::path&) {
      MaterialDesc desc = material("m");
      change(desc);
      builder.addMaterial(desc);
    };
  };
  const auto objectWith = [](const std::function<void(ObjectDesc&)>& change) {
    return [change](SceneBuilder& builder, const std::filesystem::path& directory) {
      ObjectDesc desc = object(directory / "cube.obj");
      change(desc);
      builder.addObject(desc);
    };
  };
  return {
      {"NotFinite", "material m\n  dif nan 0 0\nend\n", materialWith([](MaterialDesc& m) {
         m.diffuse = {kNaN, 0, 0};
       })},
      {"DiffuseOutOfRange", "material m\n  dif 1 1.5 1\nend\n", materialWith([](MaterialDesc& m) {
         m.diffuse = {1, 1.5f, 1};
       })},
      {"SpecularOutOfRange", "material m\n  spec -0.5 0 0\nend\n",
       materialWith([](MaterialDesc& m) {
         m.specular = {-0.5f, 0, 0};
       })},
      {"NegativeShininess", "material m\n  shin -1\nend\n",
       materialWith([](MaterialDesc& m) { m.shininess = -1; })},
      {"NegativeEmission", "material m\n  emit 1 1 -2\nend\n",
       materialWith([](MaterialDesc& m) { m.emission = glm::vec3(1, 1, -2); })},
      {"MissingTexture", "material m\n  tex \"DIR/missing.png\"\nend\n",
       [](SceneBuilder& builder, const std::filesystem::path& directory) {
         MaterialDesc desc = material("m");
         desc.texture = directory / "missing.png";
         builder.addMaterial(desc);
       }},
      {"DuplicateMaterial", "material m\nend\nmaterial m\nend\n",
       [](SceneBuilder& builder, const std::filesystem::path&) {
         MaterialDesc first = material("m");
         first.where = at(1, 1);
         builder.addMaterial(first);
         builder.addMaterial(material("m"));
       }},
      {"DuplicateLight",
       light1 + "area_light tv\n  pos1 0 0 0\n  pos2 1 0 0\n  pos3 1 1 0\n"
                "  pos4 0 1 0\n  mat glow\nend\n",
       [](SceneBuilder& builder, const std::filesystem::path&) {
         builder.addMaterial(material("glow"));
         AreaLightDesc first = light("tv", kUnitSquare);
         first.where = at(3, 1);
         builder.addLight(first);
         builder.addLight(light("tv", kUnitSquare));
       }},
      {"DegenerateLight",
       "area_light flat\n  pos1 0 0 0\n  pos2 1 0 0\n  pos3 2 0 0\n  pos4 3 0 0\n  mat glow\n"
       "end\n",
       [](SceneBuilder& builder, const std::filesystem::path&) {
         builder.addLight(light("flat", {glm::vec3(0, 0, 0), glm::vec3(1, 0, 0), glm::vec3(2, 0, 0),
                                         glm::vec3(3, 0, 0)}));
       }},
      {"UndefinedLightMaterial",
       "area_light tv\n  pos1 0 0 0\n  pos2 1 0 0\n  pos3 1 1 0\n  pos4 0 1 0\n  mat glow\nend\n",
       [](SceneBuilder& builder, const std::filesystem::path&) {
         builder.addLight(light("tv", kUnitSquare));
         builder.finish();
       }},
      {"UndefinedObjectMaterial", "object \"DIR/cube.obj\"\n  mat red\nend\n",
       [](SceneBuilder& builder, const std::filesystem::path& directory) {
         ObjectDesc desc = object(directory / "cube.obj");
         desc.material = "red";
         builder.addObject(desc);
         builder.finish();
       }},
      {"SecondCamera", camera1 + "end\n" + camera1 + "end\n",
       [](SceneBuilder& builder, const std::filesystem::path&) {
         CameraDesc first = camera("c");
         first.where = at(1, 1);
         builder.setCamera(first);
         builder.setCamera(camera("c"));
       }},
      {"FieldOfViewOutOfRange", camera1 + "  fovy 180\nend\n",
       cameraWith([](CameraDesc& c) { c.fovyDegrees = 180; })},
      {"NearNotPositive", camera1 + "  near 0\nend\n",
       cameraWith([](CameraDesc& c) { c.nearPlane = 0; })},
      {"FarNotPositive", camera1 + "  far -1\nend\n",
       cameraWith([](CameraDesc& c) { c.farPlane = -1; })},
      {"NearNotBelowFar", camera1 + "  near 2\n  far 0.5\nend\n", cameraWith([](CameraDesc& c) {
         c.nearPlane = 2;
         c.farPlane = 0.5f;
       })},
      {"ScreenSizeNotPositive", camera1 + "  screen_size 640 0\nend\n",
       cameraWith([](CameraDesc& c) {
         c.screenSize = {640, 0};
       })},
      {"PositionIsTarget", "camera c\n  pos 1 2 3\n  at 1 2 3\nend\n",
       cameraWith([](CameraDesc& c) {
         c.position = c.target = {1, 2, 3};
       })},
      {"UpAlongTheView", "camera c\n  pos 0 5 0\n  at 0 0 0\nend\n", cameraWith([](CameraDesc& c) {
         c.position = {0, 5, 0};
       })},
      {"UpNearlyAlongTheView", "camera c\n  pos 0 5 0\n  at 0 0 0\n  up 0 1 0.00001\nend\n",
       cameraWith([](CameraDesc& c) {
         c.position = {0, 5, 0};
         c.up = {0, 1, 0.00001f};
       })},
      {"LongNameQuotedShort",
       "material " + std::string(100, 'm') + "\nend\nmaterial " + std::string(100, 'm') + "\nend\n",
       [](SceneBuilder& builder, const std::filesystem::path&) {
         MaterialDesc first = material(std::string(100, 'm'));
         first.where = at(1, 1);
         builder.addMaterial(first);
         builder.addMaterial(material(std::string(100, 'm')));
       }},
      {"ModelIsADirectory", "object \"DIR\"\nend\n",
       [](SceneBuilder& builder, const std::filesystem::path& directory) {
         builder.addObject(object(directory));
       }},
      {"MissingModel", "object \"DIR/missing.obj\"\nend\n",
       [](SceneBuilder& builder, const std::filesystem::path& directory) {
         builder.addObject(object(directory / "missing.obj"));
       }},
      {"ZeroRotationAxis", "object \"DIR/cube.obj\"\n  rotate 90 0 0 0\nend\n",
       objectWith([](ObjectDesc& o) {
         o.transform.push_back({TransformStep::Kind::Rotate, glm::vec3(0), 90});
       })},
      {"ZeroScaleFactor", "object \"DIR/cube.obj\"\n  scale 1 0 1\nend\n",
       objectWith([](ObjectDesc& o) {
         o.transform.push_back({TransformStep::Kind::Scale, glm::vec3(1, 0, 1)});
       })},
      {"ZeroAnimationAxis", "object \"DIR/cube.obj\"\n  anim rotate 0 0 0 1\nend\n",
       objectWith([](ObjectDesc& o) {
         o.animations.push_back({Animation::Kind::Rotate, glm::vec3(0), 1});
       })},
  };
}

class SceneBuilderCounterpart : public ::testing::TestWithParam<Counterpart> {};

TEST_P(SceneBuilderCounterpart, FailsWithTheParsersMessage) {
  const std::filesystem::path directory = test::scratchDirectory();
  test::writeFile(directory, "cube.obj", "");
  const Counterpart& counterpart = GetParam();
  const std::string text = withDirectory(counterpart.sceneText, directory);
  const std::string parsed = errorOf([&] { parseScene(text, "test.scene"); });
  const std::string built = errorOf([&] {
    SceneBuilder builder;
    counterpart.build(builder, directory);
  });
  EXPECT_NE(parsed, "(no error)");
  EXPECT_EQ(built, parsed);
}

INSTANTIATE_TEST_SUITE_P(EveryValueError, SceneBuilderCounterpart,
                         ::testing::ValuesIn(counterparts()),
                         [](const auto& param) { return param.param.name; });

TEST(SceneBuilder, ErrorsOfCallsAreLocatedAtTheOrigin) {
  SceneBuilder builder("my scene");
  MaterialDesc desc = material("m");
  desc.diffuse = glm::vec3(2);
  try {
    builder.addMaterial(desc);
    ADD_FAILURE() << "no error";
  } catch (const SceneError& error) {
    EXPECT_EQ(std::string(error.what()),
              "my scene: error: 'dif' values must be in [0, 1], found '2'");
  }
}

TEST(SceneBuilder, BuildsTheDescriptionTheParserReads) {
  const std::filesystem::path directory = test::scratchDirectory();
  const std::filesystem::path cube = test::writeFile(directory, "cube.obj", "");
  const SceneDesc parsed = parseScene(
      "material m\n  dif 0.5 0.25 1\n  shin 8\nend\n"
      "object \"" +
          cube.string() +
          "\"\n  translate 1 2 3\n  rotate 30 0 1 0\n  scale 2\n"
          "  mat m\nend\n",
      "test.scene");
  SceneBuilder builder;
  MaterialDesc m = material("m");
  m.diffuse = {0.5f, 0.25f, 1};
  m.shininess = 8;
  builder.addMaterial(m);
  ObjectDesc desc = object(cube);
  desc.transform = {{TransformStep::Kind::Translate, {1, 2, 3}},
                    {TransformStep::Kind::Rotate, {0, 1, 0}, 30},
                    {TransformStep::Kind::Scale, glm::vec3(2)}};
  desc.material = "m";
  builder.addObject(desc);
  const SceneDesc built = builder.finish();
  ASSERT_EQ(built.materials.size(), 1u);
  EXPECT_EQ(built.materials[0].diffuse, parsed.materials[0].diffuse);
  EXPECT_EQ(built.materials[0].shininess, parsed.materials[0].shininess);
  ASSERT_EQ(built.objects.size(), 1u);
  // The same steps composed in the same order: the same floats.
  EXPECT_EQ(built.objects[0].staticTransform, parsed.objects[0].staticTransform);
  EXPECT_EQ(built.objects[0].material, parsed.objects[0].material);
}

MeshArrays triangle() {
  MeshArrays mesh;
  mesh.name = "tri";
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  mesh.triangles = {{0, 1, 2}};
  return mesh;
}

std::string meshError(const MeshArrays& mesh) {
  return errorOf([&] { makeMeshModel(mesh, NormalsMode::File, {"in-memory scene", 0, 0}); });
}

TEST(MeshArrays, ComputesMissingNormalsAndUvs) {
  const std::shared_ptr<const Model> model =
      makeMeshModel(triangle(), NormalsMode::File, {"in-memory scene", 0, 0});
  ASSERT_EQ(model->meshes.size(), 1u);
  const Mesh& mesh = model->meshes[0];
  EXPECT_EQ(mesh.normals, std::vector<glm::vec3>(3, glm::vec3(0, 0, 1)));
  EXPECT_EQ(mesh.uvs, std::vector<glm::vec2>(3, glm::vec2(0)));
  EXPECT_EQ(mesh.material, -1);
}

TEST(MeshArrays, ErrorNoTriangles) {
  MeshArrays mesh = triangle();
  mesh.triangles.clear();
  EXPECT_EQ(meshError(mesh), "mesh 'tri': has no triangles");
}

TEST(MeshArrays, ErrorNormalCount) {
  MeshArrays mesh = triangle();
  mesh.normals = {{0, 0, 1}};
  EXPECT_EQ(meshError(mesh),
            "mesh 'tri': 1 normals for 3 positions; give one per position or none");
}

TEST(MeshArrays, ErrorUvCount) {
  MeshArrays mesh = triangle();
  mesh.uvs = {{0, 0}, {1, 0}};
  EXPECT_EQ(meshError(mesh), "mesh 'tri': 2 uvs for 3 positions; give one per position or none");
}

TEST(MeshArrays, ErrorIndexOutOfRange) {
  MeshArrays mesh = triangle();
  mesh.triangles = {{0, 1, 3}};
  EXPECT_EQ(meshError(mesh), "mesh 'tri': triangle 0 uses vertex 3, but there are 3 positions");
}

// The element and the vertex are named, in the words of a model file's error (model_test.cpp).
TEST(MeshArrays, ErrorPositionNotFinite) {
  MeshArrays mesh = triangle();
  mesh.positions[1].y = std::numeric_limits<float>::infinity();
  EXPECT_EQ(meshError(mesh),
            "mesh 'tri': vertex 1 has the non-finite position (1, inf, 0); "
            "positions must be finite numbers");
}

TEST(MeshArrays, ErrorNormalNotFinite) {
  MeshArrays mesh = triangle();
  mesh.normals = std::vector<glm::vec3>(3, glm::vec3(0, 0, 1));
  mesh.normals[2].x = kNaN;
  EXPECT_EQ(meshError(mesh),
            "mesh 'tri': vertex 2 has the non-finite normal (nan, 0, 1); "
            "normals must be finite numbers");
}

TEST(MeshArrays, ErrorUvNotFinite) {
  MeshArrays mesh = triangle();
  mesh.uvs = std::vector<glm::vec2>(3, glm::vec2(0.5f));
  mesh.uvs[0].y = -std::numeric_limits<float>::infinity();
  EXPECT_EQ(meshError(mesh),
            "mesh 'tri': vertex 0 has the non-finite texture coordinate "
            "(0.5, -inf); texture coordinates must be finite numbers");
}

TEST(SceneBuilder, ErrorEmptyTextureImage) {
  MaterialDesc desc = material("m");
  desc.textureImage = std::make_shared<Image>();
  EXPECT_EQ(errorOf([&] { SceneBuilder().addMaterial(desc); }),
            "material 'm': the texture image has no pixels or the wrong number");
}

TEST(SceneBuilder, InMemoryMeshAndTextureLoad) {
  SceneBuilder builder;
  MaterialDesc desc = material("m");
  desc.textureImage = std::make_shared<Image>(2, 1, glm::vec4(0.5f));
  builder.addMaterial(desc);
  ObjectDesc mesh;
  mesh.mesh = makeMeshModel(triangle(), NormalsMode::File, builder.origin());
  mesh.material = "m";
  builder.addObject(mesh);
  builder.addObject(mesh);
  const Scene scene = loadScene(builder.finish());
  ASSERT_EQ(scene.objects.size(), 2u);
  // One material and one texture, shared by both objects.
  ASSERT_EQ(scene.materials.size(), 1u);
  ASSERT_EQ(scene.textures.size(), 1u);
  EXPECT_EQ(scene.textures[0]->size(), glm::ivec2(2, 1));
  EXPECT_EQ(scene.objects[1].model.meshes[0].positions, triangle().positions);
}

// The builder fills MaterialDesc::textureWhere: a texture that fails to load is reported at the
// material of a scene built in memory, which has no `tex` token to point at.
TEST(SceneBuilder, TextureErrorsOfCallsAreAtTheMaterial) {
  const std::filesystem::path directory = test::scratchDirectory();
  SceneBuilder builder("my scene");
  MaterialDesc desc = material("m");
  desc.texture = test::writeFile(directory, "broken.png", "not a PNG");
  desc.where = {"my scene", 7, 1};
  builder.addMaterial(desc);
  ObjectDesc mesh;
  mesh.mesh = makeMeshModel(triangle(), NormalsMode::File, builder.origin());
  mesh.material = "m";
  builder.addObject(mesh);
  const SceneDesc scene = builder.finish();
  try {
    loadScene(scene);
    ADD_FAILURE() << "the scene loaded";
  } catch (const SceneError& error) {
    EXPECT_EQ(error.where().line, 7) << error.what();
    EXPECT_EQ(error.where().column, 1) << error.what();
    EXPECT_NE(error.message().find("broken.png"), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace penumbra
