#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "scene/scene_desc.h"
#include "scene/transform.h"
#include "test_files.h"

namespace penumbra {
namespace {

// Matrices are composed in float from values of order 1: a few float roundings (about 1e-7
// each) stay far below this.
constexpr float kFloatTolerance = 1e-5f;

void expectNear(glm::vec3 actual, glm::vec3 expected) {
  EXPECT_NEAR(actual.x, expected.x, kFloatTolerance);
  EXPECT_NEAR(actual.y, expected.y, kFloatTolerance);
  EXPECT_NEAR(actual.z, expected.z, kFloatTolerance);
}

void expectNear(const glm::mat4& actual, const glm::mat4& expected) {
  for (int column = 0; column < 4; ++column)
    for (int row = 0; row < 4; ++row)
      EXPECT_NEAR(actual[column][row], expected[column][row], kFloatTolerance)
          << "column " << column << " row " << row;
}

glm::vec3 apply(const glm::mat4& matrix, glm::vec3 point) {
  return glm::vec3(matrix * glm::vec4(point, 1.0f));
}

// Every test gets a directory with a model and a texture the scenes can name.
class Parser : public ::testing::Test {
 protected:
  void SetUp() override {
    directory_ = test::scratchDirectory();
    sceneFile_ = directory_ / "test.scene";
    test::writeFile(directory_, "cube.obj", "");
    test::writeFile(directory_, "wood.png", "");
  }

  SceneDesc parse(std::string_view text) const { return parseScene(text, sceneFile_); }

  // Parses `text` expecting the error `message` at line:column.
  void expectError(std::string_view text, int line, int column, const std::string& message) const {
    try {
      parse(text);
      ADD_FAILURE() << "no error; expected: " << message;
    } catch (const SceneError& error) {
      EXPECT_EQ(error.message(), message);
      EXPECT_EQ(error.where().file, sceneFile_.string());
      EXPECT_EQ(error.where().line, line);
      EXPECT_EQ(error.where().column, column);
      EXPECT_EQ(std::string(error.what()), sceneFile_.string() + ":" + std::to_string(line) + ":" +
                                               std::to_string(column) + ": error: " + message);
    }
  }

  std::string at(int line, int column) const {
    return sceneFile_.string() + ":" + std::to_string(line) + ":" + std::to_string(column);
  }

  std::filesystem::path directory_;
  std::filesystem::path sceneFile_;
};

const char* const kLight =
    "area_light tv\n"
    "  pos1 0 0 0\n"
    "  pos2 1 0 0\n"
    "  pos3 1 1 0\n"
    "  pos4 0 1 0\n"
    "  mat glow\n"
    "end\n"
    "material glow\n"
    "end\n";

TEST_F(Parser, MaterialDefaults) {
  const SceneDesc scene = parse("\nmaterial plain\nend\n");
  ASSERT_EQ(scene.materials.size(), 1u);
  const MaterialDesc& material = scene.materials[0];
  EXPECT_EQ(material.name, "plain");
  EXPECT_EQ(material.ambient, glm::vec3(0));
  EXPECT_EQ(material.diffuse, glm::vec3(0.8f));
  EXPECT_EQ(material.specular, glm::vec3(0));
  EXPECT_EQ(material.shininess, 1.0f);
  EXPECT_FALSE(material.texture.has_value());
  EXPECT_FALSE(material.emission.has_value());
  EXPECT_EQ(material.where.str(), at(2, 1));
  EXPECT_EQ(scene.file, sceneFile_);
  EXPECT_FALSE(scene.camera.has_value());
}

TEST_F(Parser, MaterialKeys) {
  const SceneDesc scene = parse(
      "material red\n"
      "  amb 0.1 0.2 0.3\n"
      "  dif 1 0 0.5\n"
      "  spec 0.25 0.5 1\n"
      "  shin 50\n"
      "  tex wood.png\n"
      "  emit 4 5 6\n"
      "end\n");
  const MaterialDesc* material = scene.findMaterial("red");
  ASSERT_NE(material, nullptr);
  EXPECT_EQ(material->ambient, glm::vec3(0.1f, 0.2f, 0.3f));
  EXPECT_EQ(material->diffuse, glm::vec3(1, 0, 0.5f));
  EXPECT_EQ(material->specular, glm::vec3(0.25f, 0.5f, 1));
  EXPECT_EQ(material->shininess, 50.0f);
  EXPECT_EQ(material->texture, directory_ / "wood.png");
  EXPECT_EQ(material->emission, glm::vec3(4, 5, 6));
  EXPECT_EQ(scene.findMaterial("blue"), nullptr);
}

TEST_F(Parser, TextureMinusOneMeansNone) {
  const SceneDesc scene = parse("material a\n  tex wood.png\n  tex -1\nend\n");
  EXPECT_FALSE(scene.materials[0].texture.has_value());
}

TEST_F(Parser, LightKeys) {
  const SceneDesc scene = parse(
      "area_light tv\n"
      "  pos1 -1 0 -2\n"
      "  pos2 1 0 -2\n"
      "  pos3 1 1.2 -2\n"
      "  pos4 -1 1.2 -2\n"
      "  at 0 0.6 0\n"
      "  mat screen\n"
      "end\n"
      "material screen\n"
      "end\n");
  ASSERT_EQ(scene.lights.size(), 1u);
  const AreaLightDesc& light = scene.lights[0];
  EXPECT_EQ(light.name, "tv");
  EXPECT_EQ(light.corners[0], glm::vec3(-1, 0, -2));
  EXPECT_EQ(light.corners[1], glm::vec3(1, 0, -2));
  EXPECT_EQ(light.corners[2], glm::vec3(1, 1.2f, -2));
  EXPECT_EQ(light.corners[3], glm::vec3(-1, 1.2f, -2));
  EXPECT_EQ(light.emittingSidePoint, glm::vec3(0, 0.6f, 0));
  EXPECT_EQ(light.material, "screen");
  EXPECT_EQ(light.where.str(), at(1, 1));
  EXPECT_EQ(light.materialWhere.str(), at(7, 7));
}

TEST_F(Parser, LightWithoutAtHasNoEmittingSidePoint) {
  EXPECT_FALSE(parse(kLight).lights[0].emittingSidePoint.has_value());
}

TEST_F(Parser, CameraDefaults) {
  const SceneDesc scene = parse("camera cam\n  pos 0 1 4\n  at 0 0.5 0\nend\n");
  ASSERT_TRUE(scene.camera.has_value());
  const CameraDesc& camera = *scene.camera;
  EXPECT_EQ(camera.name, "cam");
  EXPECT_EQ(camera.position, glm::vec3(0, 1, 4));
  EXPECT_EQ(camera.target, glm::vec3(0, 0.5f, 0));
  EXPECT_EQ(camera.up, glm::vec3(0, 1, 0));
  EXPECT_EQ(camera.fovyDegrees, 45.0f);
  EXPECT_EQ(camera.nearPlane, 0.1f);
  EXPECT_EQ(camera.farPlane, 1000.0f);
  EXPECT_EQ(camera.screenSize, glm::ivec2(1024, 1024));
  EXPECT_EQ(camera.where.str(), at(1, 1));
}

TEST_F(Parser, CameraKeys) {
  const SceneDesc scene = parse(
      "camera cam\n"
      "  pos 0 1 4\n"
      "  at 0 0.5 0\n"
      "  up 1 0 0\n"
      "  fovy 60\n"
      "  near 0.5\n"
      "  far 50\n"
      "  screen_size 640 480\n"
      "end\n");
  const CameraDesc& camera = *scene.camera;
  EXPECT_EQ(camera.up, glm::vec3(1, 0, 0));
  EXPECT_EQ(camera.fovyDegrees, 60.0f);
  EXPECT_EQ(camera.nearPlane, 0.5f);
  EXPECT_EQ(camera.farPlane, 50.0f);
  EXPECT_EQ(camera.screenSize, glm::ivec2(640, 480));
}

TEST_F(Parser, ObjectDefaults) {
  const SceneDesc scene = parse("object cube.obj\nend\n");
  ASSERT_EQ(scene.objects.size(), 1u);
  const ObjectDesc& object = scene.objects[0];
  EXPECT_EQ(object.model, directory_ / "cube.obj");
  EXPECT_EQ(object.staticTransform, glm::mat4(1.0f));
  EXPECT_TRUE(object.animations.empty());
  EXPECT_FALSE(object.material.has_value());
  EXPECT_EQ(object.normals, NormalsMode::File);
  EXPECT_EQ(object.where.str(), at(1, 1));
}

TEST_F(Parser, ObjectNormalsAndMaterial) {
  const SceneDesc scene = parse(
      "object cube.obj\n  normals flat\n  mat red\nend\n"
      "object cube.obj\n  normals smooth\nend\n"
      "object cube.obj\n  normals file\nend\n"
      "material red\nend\n");
  ASSERT_EQ(scene.objects.size(), 3u);
  EXPECT_EQ(scene.objects[0].normals, NormalsMode::Flat);
  EXPECT_EQ(scene.objects[0].material, "red");
  EXPECT_EQ(scene.objects[0].materialWhere.str(), at(3, 7));
  EXPECT_EQ(scene.objects[1].normals, NormalsMode::Smooth);
  EXPECT_EQ(scene.objects[2].normals, NormalsMode::File);
}

TEST_F(Parser, StaticTransformsComposeLikeTheOpenGlMatrixStack) {
  // translate then rotate: M = T * R, so the point is rotated first, then translated.
  const glm::mat4 translateThenRotate =
      parse("object cube.obj\n  translate 1 0 0\n  rotate 90 0 0 1\nend\n")
          .objects[0]
          .staticTransform;
  // Columns of T(1,0,0) * Rz(90): x -> y, y -> -x, then the offset (1,0,0).
  const glm::mat4 expectedTR(glm::vec4(0, 1, 0, 0), glm::vec4(-1, 0, 0, 0), glm::vec4(0, 0, 1, 0),
                             glm::vec4(1, 0, 0, 1));
  expectNear(translateThenRotate, expectedTR);
  expectNear(apply(translateThenRotate, {1, 0, 0}), {1, 1, 0});

  const glm::mat4 rotateThenTranslate =
      parse("object cube.obj\n  rotate 90 0 0 1\n  translate 1 0 0\nend\n")
          .objects[0]
          .staticTransform;
  // Rz(90) * T(1,0,0): the offset is rotated too and becomes (0,1,0).
  const glm::mat4 expectedRT(glm::vec4(0, 1, 0, 0), glm::vec4(-1, 0, 0, 0), glm::vec4(0, 0, 1, 0),
                             glm::vec4(0, 1, 0, 1));
  expectNear(rotateThenTranslate, expectedRT);
  expectNear(apply(rotateThenTranslate, {1, 0, 0}), {0, 2, 0});
}

TEST_F(Parser, ScaleTakesOneOrThreeFactors) {
  const SceneDesc scene =
      parse("object cube.obj\n  scale 2\nend\nobject cube.obj\n  scale 1 2 3\nend\n");
  EXPECT_EQ(scene.objects[0].staticTransform, glm::scale(glm::mat4(1.0f), glm::vec3(2)));
  expectNear(apply(scene.objects[0].staticTransform, {1, 1, 1}), {2, 2, 2});
  expectNear(apply(scene.objects[1].staticTransform, {1, 1, 1}), {1, 2, 3});
}

TEST_F(Parser, ScaleAfterTranslateScalesTheModelOnly) {
  // As in the spec's example: the cube is scaled about its own origin, then moved.
  const ObjectDesc object =
      parse("object cube.obj\n  translate 0 0.5 0\n  scale 0.5\nend\n").objects[0];
  expectNear(apply(object.staticTransform, {1, 1, 1}), {0.5f, 1.0f, 0.5f});
}

TEST_F(Parser, AnimationsFollowTheStaticTransform) {
  const ObjectDesc object = parse(
                                "object cube.obj\n"
                                "  translate 0 1 0\n"
                                "  anim rotate 0 1 0 0.5\n"
                                "  anim translate 2 0 0 0.25\n"
                                "end\n")
                                .objects[0];
  ASSERT_EQ(object.animations.size(), 2u);
  EXPECT_EQ(object.animations[0].kind, Animation::Kind::Rotate);
  EXPECT_EQ(object.animations[0].axis, glm::vec3(0, 1, 0));
  EXPECT_EQ(object.animations[0].step, 0.5f);
  EXPECT_EQ(object.animations[1].kind, Animation::Kind::Translate);
  EXPECT_EQ(object.animations[1].axis, glm::vec3(2, 0, 0));
  EXPECT_EQ(object.animations[1].step, 0.25f);

  // The origin is first moved by 2 sin(0.25 f) along x, spun by 0.5 f about y, then lifted.
  const auto expected = [](int frame) {
    const double offset = 2.0 * std::sin(0.25 * frame);
    const double angle = 0.5 * frame;
    return glm::vec3(static_cast<float>(offset * std::cos(angle)), 1.0f,
                     static_cast<float>(-offset * std::sin(angle)));
  };
  for (const int frame : {0, 1, 100})
    expectNear(apply(worldFromObject(object, frame), {0, 0, 0}), expected(frame));
}

TEST_F(Parser, MaterialsMayBeReferencedBeforeTheirDefinition) {
  const SceneDesc scene =
      parse(std::string("object cube.obj\n  mat red\nend\n") + kLight + "material red\nend\n");
  EXPECT_EQ(scene.objects[0].material, "red");
  EXPECT_EQ(scene.lights[0].material, "glow");
  EXPECT_EQ(scene.materials.size(), 2u);
}

TEST_F(Parser, QuotedPathsMayContainSpaces) {
  test::writeFile(directory_, "my models/big cube.obj", "");
  test::writeFile(directory_, "my textures/oak wood.png", "");
  const SceneDesc scene = parse(
      "object \"my models/big cube.obj\"\nend\n"
      "material m\n  tex \"my textures/oak wood.png\"  # comment\nend\n");
  EXPECT_EQ(scene.objects[0].model, directory_ / "my models/big cube.obj");
  EXPECT_EQ(scene.materials[0].texture, directory_ / "my textures/oak wood.png");
}

TEST_F(Parser, AbsolutePathsAreKept) {
  const std::filesystem::path model = directory_ / "cube.obj";
  const SceneDesc scene = parseScene("object \"" + model.string() + "\"\nend\n",
                                     std::filesystem::path("elsewhere/test.scene"));
  EXPECT_EQ(scene.objects[0].model, model);
}

TEST_F(Parser, LastValueWinsForRepeatedKeys) {
  const SceneDesc scene = parse(
      "material m\n  dif 0.1 0.1 0.1\n  shin 3\n  dif 0.2 0.3 0.4\nend\n"
      "camera c\n  pos 1 1 1\n  at 0 0 0\n  pos 0 0 5\n  fovy 30\n  fovy 70\nend\n"
      "object cube.obj\n  mat m\n  normals flat\n  mat other\n  normals smooth\nend\n"
      "material other\nend\n");
  EXPECT_EQ(scene.materials[0].diffuse, glm::vec3(0.2f, 0.3f, 0.4f));
  EXPECT_EQ(scene.materials[0].shininess, 3.0f);
  EXPECT_EQ(scene.camera->position, glm::vec3(0, 0, 5));
  EXPECT_EQ(scene.camera->fovyDegrees, 70.0f);
  EXPECT_EQ(scene.objects[0].material, "other");
  EXPECT_EQ(scene.objects[0].normals, NormalsMode::Smooth);
}

TEST_F(Parser, RepeatedTransformsAccumulate) {
  const ObjectDesc object =
      parse("object cube.obj\n  translate 1 0 0\n  translate 0 2 0\nend\n").objects[0];
  expectNear(apply(object.staticTransform, {0, 0, 0}), {1, 2, 0});
}

TEST_F(Parser, ReadsTheSpecExampleFromAFile) {
  test::writeFile(directory_, "clip.mp4", "");
  const std::filesystem::path file = test::writeFile(directory_, "example.scene", R"(
# A red-tinted TV screen lighting a spinning cube.
material screen
  emit 4 4 4
  tex clip.mp4
end

material red
  amb 0 0 0
  dif 1.0 0.0 0.0
  spec 1.0 1.0 1.0
  shin 50.0
  tex -1
end

area_light tv
  pos1 -1 0 -2
  pos2  1 0 -2
  pos3  1 1.2 -2
  pos4 -1 1.2 -2
  at 0 0.6 0
  mat screen
end

camera cam1
  pos 0.0 1.0 4.0
  up 0.0 1.0 0.0
  at 0.0 0.5 0.0
  fovy 45.0
  near 0.1
  far 50.0
  screen_size 1024 1024
end

object cube.obj
  translate 0 0.5 0
  scale 0.5
  anim rotate 0 1 0 0.02
  mat red
end
)");
  const SceneDesc scene = parseSceneFile(file);
  EXPECT_EQ(scene.file, file);
  EXPECT_EQ(scene.materials.size(), 2u);
  EXPECT_EQ(scene.lights.size(), 1u);
  EXPECT_EQ(scene.objects.size(), 1u);
  EXPECT_EQ(scene.camera->farPlane, 50.0f);
  EXPECT_EQ(scene.findMaterial("screen")->texture, directory_ / "clip.mp4");
  EXPECT_EQ(scene.objects[0].animations.size(), 1u);
}

TEST_F(Parser, MissingSceneFileIsAnErrorWithoutALine) {
  const std::filesystem::path file = directory_ / "absent.scene";
  try {
    parseSceneFile(file);
    ADD_FAILURE() << "no error";
  } catch (const SceneError& error) {
    EXPECT_EQ(std::string(error.what()), file.string() + ": error: scene file not found");
  }
}

TEST_F(Parser, EmptySceneIsValid) {
  const SceneDesc scene = parse("# nothing here\n\n");
  EXPECT_TRUE(scene.materials.empty());
  EXPECT_TRUE(scene.objects.empty());
}

// One test per kind of error, each checking the message and where it points.

TEST_F(Parser, ErrorUnknownKeyInABlock) {
  expectError("material m\n  dif 1 1 1\n  diffuse 1 1 1\nend\n", 3, 3,
              "unknown keyword 'diffuse' in a material block, expected one of: amb, dif, spec, "
              "shin, tex, emit, emit_tex, two_sided, end");
  expectError("object cube.obj\n  pos 1 1 1\nend\n", 2, 3,
              "unknown keyword 'pos' in an object block, expected one of: translate, rotate, "
              "scale, anim, mat, normals, end");
}

TEST_F(Parser, ErrorUnknownBlock) {
  expectError(
      "\n  light l\nend\n", 2, 3,
      "unknown keyword 'light', expected a block: material, area_light, camera, object, scene");
}

TEST_F(Parser, ErrorTooFewNumbers) {
  expectError("material m\n  dif 1 1\nend\n", 2, 3, "expected 3 numbers after 'dif', found 2");
  expectError("object cube.obj\n  rotate 90 0 1\nend\n", 2, 3,
              "expected 4 numbers after 'rotate', found 3");
  expectError("object cube.obj\n  anim translate 1 0 0\nend\n", 2, 3,
              "expected 4 numbers after 'anim translate', found 3");
  expectError("camera c\n  fovy\nend\n", 2, 3, "expected 1 number after 'fovy', found 0");
}

TEST_F(Parser, ErrorTooManyNumbersPointsAtTheFirstExtra) {
  expectError("material m\n  emit 1 1 1 1\nend\n", 2, 14,
              "expected 3 numbers after 'emit', found 4");
  expectError("camera c\n  screen_size 1 2 3\nend\n", 2, 19,
              "expected 2 numbers after 'screen_size', found 3");
}

TEST_F(Parser, ErrorScaleWithTwoNumbers) {
  expectError("object cube.obj\n  scale 1 2\nend\n", 2, 3,
              "expected 1 or 3 numbers after 'scale', found 2");
}

TEST_F(Parser, ErrorNan) {
  expectError("material m\n  dif 1 nan 1\nend\n", 2, 9, "expected a finite number, found 'nan'");
}

TEST_F(Parser, ErrorInf) {
  expectError("object cube.obj\n  translate 0 0 inf\nend\n", 2, 17,
              "expected a finite number, found 'inf'");
  expectError("object cube.obj\n  translate 0 0 1e999\nend\n", 2, 17,
              "expected a finite number, found '1e999'");
}

TEST_F(Parser, ErrorQuotesAtMostAFewDozenCharactersOfAToken) {
  const std::string digits(5'000'000, '9');
  expectError(
      "object cube.obj\n  translate 0 0 " + digits + "\nend\n", 2, 17,
      "expected a finite number, found '" + digits.substr(0, 40) + "...' (5000000 characters)");
  const std::string word(100, 'x');
  expectError("material m\n  " + word + " 1\nend\n", 2, 3,
              "unknown keyword '" + word.substr(0, 40) +
                  "...' (100 characters) in a material block, expected one of: amb, dif, spec, "
                  "shin, tex, emit, emit_tex, two_sided, end");
}

TEST_F(Parser, ErrorDuplicateName) {
  expectError("material m\nend\n\nmaterial m\nend\n", 4, 10,
              "duplicate material name 'm', first defined at " + at(1, 1));
  expectError(std::string(kLight) + kLight, 10, 12,
              "duplicate area_light name 'tv', first defined at " + at(1, 1));
}

TEST_F(Parser, SameNameForAMaterialAndALightIsAllowed) {
  EXPECT_NO_THROW(parse(std::string(kLight) + "material tv\nend\n"));
}

TEST_F(Parser, ErrorUndefinedMaterial) {
  expectError("object cube.obj\n  mat red\nend\nmaterial blue\nend\n", 2, 7,
              "undefined material 'red': no material block has this name");
  expectError(
      "area_light l\n  pos1 0 0 0\n  pos2 1 0 0\n  pos3 1 1 0\n  pos4 0 1 0\n  mat   glow\nend\n",
      6, 9, "undefined material 'glow': no material block has this name");
}

TEST_F(Parser, ErrorSecondCamera) {
  const std::string camera = "camera a\n  pos 0 0 1\n  at 0 0 0\nend\n";
  expectError(camera + "camera b\n  pos 0 0 1\n  at 0 0 0\nend\n", 5, 1,
              "a second camera 'b': only one camera is allowed, 'a' is defined at " + at(1, 1));
}

TEST_F(Parser, ErrorDegenerateLight) {
  expectError(
      "material g\nend\n  area_light flat\n  pos1 0 0 0\n  pos2 1 0 0\n  pos3 2 0 0\n"
      "  pos4 3 0 0\n  mat g\nend\n",
      3, 3, "area_light 'flat': zero area: the corners do not span a surface");
}

TEST_F(Parser, ErrorNonPlanarLight) {
  // The longer diagonal, pos1-pos3, is sqrt(2.0001) = 1.41425: the limit is 1e-4 of it.
  expectError(
      "area_light bent\n  pos1 0 0 0\n  pos2 1 0 0\n  pos3 1 1 0.01\n  pos4 0 1 0\n  mat g\nend\n",
      1, 1,
      "area_light 'bent': corners not coplanar: pos3 is 0.01 from the plane of pos1, pos2 and "
      "pos4 (at most 0.000141425, 1e-4 of the diagonal, is allowed)");
}

TEST_F(Parser, ErrorNonConvexLight) {
  expectError(
      "area_light bow\n  pos1 0 0 0\n  pos2 1 0 0\n  pos3 0 1 0\n  pos4 1 1 0\n  mat g\nend\n", 1,
      1,
      "area_light 'bow': non-convex corner order: the outline turns the other way at pos3 (list "
      "the corners in order around a convex quad)");
}

TEST_F(Parser, ErrorMissingModelFile) {
  expectError("object  missing.obj\nend\n", 1, 9,
              "model file 'missing.obj' not found (looked for '" +
                  (directory_ / "missing.obj").string() + "')");
}

TEST_F(Parser, ErrorDirectoryForAFile) {
  std::filesystem::create_directory(directory_ / "models");
  expectError(
      "object models\nend\n", 1, 8,
      "model file 'models' is a directory (looked at '" + (directory_ / "models").string() + "')");
  expectError("material m\n  tex models\nend\n", 2, 7,
              "texture file 'models' is a directory (looked at '" +
                  (directory_ / "models").string() + "')");
}

TEST_F(Parser, ErrorMissingTexture) {
  expectError("material m\n  tex \"no such.png\"\nend\n", 2, 7,
              "texture file 'no such.png' not found (looked for '" +
                  (directory_ / "no such.png").string() + "')");
}

TEST_F(Parser, OverriddenMissingTextureIsNotAnError) {
  EXPECT_NO_THROW(parse("material m\n  tex missing.png\n  tex wood.png\nend\n"));
}

TEST_F(Parser, ErrorUnclosedBlock) {
  expectError("material a\nend\n\n  material b\n  dif 1 1 1\n", 4, 3,
              "material 'b' is not closed: expected 'end' before the end of the file");
  expectError("material a\n  dif 1 1 1\nobject cube.obj\nend\n", 3, 1,
              "expected 'end' to close material 'a' (opened at " + at(1, 1) + ") before 'object'");
}

TEST_F(Parser, ErrorEndWithoutBlock) {
  expectError("material a\nend\nend\n", 3, 1, "'end' without an open block");
  expectError("material a\nend x\n", 2, 5, "unexpected 'x' after 'end'");
}

TEST_F(Parser, ErrorMissingRequiredKeys) {
  expectError("material g\nend\narea_light l\n  pos1 0 0 0\n  pos2 1 0 0\n  pos4 0 1 0\nend\n", 3,
              1, "area_light 'l' is missing required keys 'pos3', 'mat'");
  expectError("camera c\n  pos 0 0 1\nend\n", 1, 1, "camera 'c' is missing required key 'at'");
}

TEST_F(Parser, ErrorMissingBlockArgument) {
  expectError("material\nend\n", 1, 1, "expected 1 name after 'material', found 0");
  expectError("object cube.obj cube.obj\nend\n", 1, 17,
              "expected 1 model path after 'object', found 2");
}

TEST_F(Parser, ErrorValuesOutOfRange) {
  expectError("material m\n  dif 1 1.5 1\nend\n", 2, 9,
              "'dif' values must be in [0, 1], found '1.5'");
  expectError("material m\n  spec -0.1 0 0\nend\n", 2, 8,
              "'spec' values must be in [0, 1], found '-0.1'");
  expectError("material m\n  shin -1\nend\n", 2, 8, "'shin' must be >= 0, found '-1'");
  expectError("material m\n  emit 1 1 -2\nend\n", 2, 12, "'emit' values must be >= 0, found '-2'");
  expectError("camera c\n  pos 0 0 1\n  at 0 0 0\n  fovy 180\nend\n", 4, 8,
              "'fovy' must be in (0, 180) degrees, found '180'");
  expectError("camera c\n  pos 0 0 1\n  at 0 0 0\n  near 0\nend\n", 4, 8,
              "'near' must be > 0, found '0'");
  expectError("camera c\n  pos 0 0 1\n  at 0 0 0\n  far 0.5\n  near 2\nend\n", 4, 7,
              "'near' (2) must be less than 'far' (0.5)");
  expectError("camera c\n  pos 0 0 1\n  at 0 0 0\n  near 2000\nend\n", 4, 8,
              "'near' (2000) must be less than 'far' (1000)");
  // Values are checked once the block's syntax is (the required keys included).
  expectError("camera c\n  pos 0 0 1\n  at 0 0 0\n  screen_size 640 0\nend\n", 4, 19,
              "expected a positive integer, found '0'");
  expectError("camera c\n  screen_size 640.5 480\nend\n", 2, 15,
              "expected a positive integer, found '640.5'");
}

TEST_F(Parser, ErrorDegenerateCamera) {
  expectError("camera c\n  pos 1 2 3\n  at 1 2 3\nend\n", 1, 1,
              "camera 'c': 'pos' and 'at' are the same point");
  expectError("camera c\n  pos 0 5 0\n  at 0 0 0\nend\n", 1, 1,
              "camera 'c': 'up' is zero or parallel to the viewing direction");
  expectError("camera c\n  pos 0 0 1\n  at 0 0 0\n  up 0 0 0\nend\n", 4, 6,
              "camera 'c': 'up' is zero or parallel to the viewing direction");
  // Parallel up to float rounding: the cross product of (0.3, 0.7, 1.1) and (3, 7, 11) in float
  // is about 5e-7, not zero.
  expectError("camera c\n  pos 0 0 0\n  at 0.3 0.7 1.1\n  up 3 7 11\nend\n", 4, 6,
              "camera 'c': 'up' is zero or parallel to the viewing direction");
  EXPECT_NO_THROW(parse("camera c\n  pos 0 0 0\n  at 0 0 -1\n  up 0 0.01 1\nend\n"));
}

TEST_F(Parser, ErrorBadTransformArguments) {
  expectError("object cube.obj\n  rotate 90 0 0 0\nend\n", 2, 13,
              "the rotation axis must not be zero");
  expectError("object cube.obj\n  anim rotate 0 0 0 1\nend\n", 2, 15,
              "the rotation axis must not be zero");
  expectError("object cube.obj\n  scale 1 0 1\nend\n", 2, 11,
              "'scale' factors must not be zero, found '0'");
  expectError("object cube.obj\n  anim\nend\n", 2, 3,
              "expected 'rotate' or 'translate' after 'anim'");
  expectError("object cube.obj\n  anim spin 0 1 0 1\nend\n", 2, 8,
              "unknown animation 'spin', expected one of: rotate, translate");
  expectError("object cube.obj\n  normals faceted\nend\n", 2, 11,
              "unknown normals mode 'faceted', expected one of: file, smooth, flat");
}

}  // namespace
}  // namespace penumbra
