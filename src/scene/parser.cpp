// The scene parser: tokens to a SceneDesc. The parser checks the syntax; each block it reads goes
// to a SceneBuilder, which checks the values, with the tokens as the places its errors point at.
// The whole file is checked before anything is returned, so no partial scene escapes.

#include <array>
#include <charconv>
#include <fstream>
#include <span>
#include <sstream>

#include "scene/gltf_import.h"
#include "scene/scene_builder.h"
#include "scene/scene_desc.h"
#include "scene/tokenizer.h"

namespace penumbra {

std::string SourceLocation::str() const {
  // Problems with the file as a whole (it cannot be read) have no line.
  if (line <= 0)
    return file;
  return file + ":" + std::to_string(line) + ":" + std::to_string(column);
}

SceneError::SceneError(const SourceLocation& where, const std::string& message)
    : std::runtime_error(where.str() + ": error: " + message), where_(where), message_(message) {}

const MaterialDesc* SceneDesc::findMaterial(const std::string& name) const {
  for (const MaterialDesc& material : materials)
    if (material.name == name)
      return &material;
  return nullptr;
}

namespace {

using Keys = std::span<const std::string_view>;

constexpr std::array<std::string_view, 5> kBlockKinds{"material", "area_light", "camera", "object",
                                                      "scene"};
constexpr std::array<std::string_view, 9> kMaterialKeys{
    "amb", "dif", "spec", "shin", "tex", "emit", "emit_tex", "two_sided", "end"};
constexpr std::array<std::string_view, 7> kLightKeys{"pos1", "pos2", "pos3", "pos4",
                                                     "at",   "mat",  "end"};
constexpr std::array<std::string_view, 8> kCameraKeys{"pos",  "at",  "up",          "fovy",
                                                      "near", "far", "screen_size", "end"};
constexpr std::array<std::string_view, 7> kObjectKeys{"translate", "rotate",  "scale", "anim",
                                                      "mat",       "normals", "end"};
constexpr std::array<std::string_view, 1> kSceneKeys{"end"};
constexpr std::array<std::string_view, 2> kAnimationKinds{"rotate", "translate"};
constexpr std::array<std::string_view, 3> kNormalsModes{"file", "smooth", "flat"};
constexpr std::array<std::string_view, 2> kSwitchValues{"on", "off"};

std::string listOf(Keys keys) {
  std::string text;
  for (const std::string_view key : keys) {
    if (!text.empty())
      text += ", ";
    text += key;
  }
  return text;
}

bool contains(Keys keys, std::string_view word) {
  for (const std::string_view key : keys)
    if (key == word)
      return true;
  return false;
}

std::string plural(std::size_t count, std::string_view noun) {
  return std::to_string(count) + " " + std::string(noun) + (count == 1 ? "" : "s");
}

[[noreturn]] void fail(const SourceLocation& where, const std::string& message) {
  throw SceneError(where, message);
}

// Checks that `statement` (the tokens before firstValue) is followed by exactly `count` values.
// Too few points at the statement's first token, too many at the first extra value.
void expectValueCount(const TokenLine& line, std::size_t firstValue, std::size_t count,
                      std::string_view statement, std::string_view noun) {
  const std::size_t found = line.tokens.size() - firstValue;
  if (found == count)
    return;
  const SourceLocation& where =
      found < count ? line.tokens.front().where : line.tokens[firstValue + count].where;
  fail(where, "expected " + plural(count, noun) + " after " + quoteToken(statement) + ", found " +
                  std::to_string(found));
}

const std::string& keyOf(const TokenLine& line) {
  return line.tokens.front().text;
}

float readFloat(const TokenLine& line) {
  expectValueCount(line, 1, 1, keyOf(line), "number");
  return parseNumber(line.tokens[1]);
}

glm::vec3 readVec3(const TokenLine& line, std::size_t firstValue = 1) {
  return {parseNumber(line.tokens[firstValue]), parseNumber(line.tokens[firstValue + 1]),
          parseNumber(line.tokens[firstValue + 2])};
}

glm::vec3 readVec3Key(const TokenLine& line) {
  expectValueCount(line, 1, 3, keyOf(line), "number");
  return readVec3(line);
}

const Token& readWord(const TokenLine& line, std::string_view noun) {
  expectValueCount(line, 1, 1, keyOf(line), noun);
  return line.tokens[1];
}

// An integer; whether it is positive is the builder's check.
int readInteger(const Token& token) {
  int value = 0;
  const std::string& text = token.text;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size())
    fail(token.where, expectedPositiveInteger(text));
  return value;
}

// `block` names the block with its article, e.g. "an object block".
[[noreturn]] void failUnknownKey(const TokenLine& line, std::string_view block, Keys keys) {
  const Token& key = line.tokens.front();
  fail(key.where, "unknown keyword " + quoteToken(key.text) + " in " + std::string(block) +
                      ", expected one of: " + listOf(keys));
}

void requireKeys(const std::vector<std::string_view>& missing, std::string_view block,
                 const std::string& name, const SourceLocation& where) {
  if (missing.empty())
    return;
  std::string names;
  for (const std::string_view key : missing)
    names += (names.empty() ? "" : ", ") + quoteToken(key);
  fail(where, std::string(block) + " " + quoteToken(name) + " is missing required key" +
                  (missing.size() == 1 ? " " : "s ") + names);
}

// The tokens of one block, where the builder's errors point.
class BlockTokens final : public ValueSites {
 public:
  BlockTokens(const TokenLine& header, std::span<const TokenLine> body)
      : header_(header), body_(body) {}

  std::optional<ValueSite> find(std::string_view key, std::size_t index,
                                std::size_t occurrence) const override {
    const TokenLine* line = key.empty() ? &header_ : nullptr;
    std::size_t seen = 0;
    for (std::size_t at = 0; !key.empty() && at < body_.size(); ++at) {
      if (keyOf(body_[at]) != key)
        continue;
      if (occurrence == kLast || seen == occurrence)
        line = &body_[at];
      if (seen++ == occurrence)
        break;
    }
    if (line == nullptr || index >= line->tokens.size())
      return std::nullopt;
    return ValueSite{line->tokens[index].where, line->tokens[index].text};
  }

 private:
  const TokenLine& header_;
  std::span<const TokenLine> body_;
};

class SceneParser {
 public:
  SceneParser(std::string_view text, const std::filesystem::path& file)
      : lines_(tokenize(text, file.string())), directory_(file.parent_path()), builder_(file) {}

  SceneDesc parse() {
    std::size_t index = 0;
    while (index < lines_.size()) {
      const TokenLine& header = lines_[index];
      const Token& kind = header.tokens.front();
      if (kind.text == "end")
        fail(kind.where, "'end' without an open block");
      if (!contains(kBlockKinds, kind.text))
        fail(kind.where, "unknown keyword " + quoteToken(kind.text) +
                             ", expected a block: " + listOf(kBlockKinds));
      const std::string_view argument =
          kind.text == "object" ? "model path" : (kind.text == "scene" ? "glTF path" : "name");
      expectValueCount(header, 1, 1, kind.text, argument);
      const std::span<const TokenLine> body = blockBody(index);
      if (kind.text == "material")
        parseMaterial(header, body);
      if (kind.text == "area_light")
        parseLight(header, body);
      if (kind.text == "camera")
        parseCamera(header, body);
      if (kind.text == "object")
        parseObject(header, body);
      if (kind.text == "scene")
        parseImport(header, body);
      index += body.size() + 2;
    }
    // After every block, so that a material block or camera anywhere in the file overrides the
    // glTF's.
    if (import_)
      importGltfScene(builder_, import_->file, import_->where);
    return builder_.finish();
  }

 private:
  // The lines between the header at `headerIndex` and its `end`. Blocks do not nest, so a
  // block header before the `end` means the `end` was forgotten.
  std::span<const TokenLine> blockBody(std::size_t headerIndex) const {
    const TokenLine& header = lines_[headerIndex];
    const std::string block = keyOf(header) + " " + quoteToken(header.tokens[1].text);
    for (std::size_t index = headerIndex + 1; index < lines_.size(); ++index) {
      const TokenLine& line = lines_[index];
      if (contains(kBlockKinds, keyOf(line)))
        fail(line.tokens.front().where, "expected 'end' to close " + block + " (opened at " +
                                            header.tokens.front().where.str() + ") before " +
                                            quoteToken(keyOf(line)));
      if (keyOf(line) != "end")
        continue;
      if (line.tokens.size() > 1)
        fail(line.tokens[1].where,
             "unexpected " + quoteToken(line.tokens[1].text) + " after 'end'");
      return std::span<const TokenLine>(lines_).subspan(headerIndex + 1, index - headerIndex - 1);
    }
    fail(header.tokens.front().where,
         block + " is not closed: expected 'end' before the end of the file");
  }

  std::filesystem::path resolve(const Token& token) const { return directory_ / token.text; }

  // A texture key's path; an unquoted -1 means "no texture", a quoted one is a file named -1.
  std::optional<std::filesystem::path> readTexturePath(const TokenLine& line) const {
    const Token& path = readWord(line, "path");
    if (!path.quoted && path.text == "-1")
      return std::nullopt;
    return resolve(path);
  }

  void parseMaterial(const TokenLine& header, std::span<const TokenLine> body) {
    MaterialDesc material;
    material.name = header.tokens[1].text;
    material.where = header.tokens.front().where;
    for (const TokenLine& line : body) {
      const std::string& key = keyOf(line);
      if (key == "amb") {
        material.ambient = readVec3Key(line);
      } else if (key == "dif") {
        material.diffuse = readVec3Key(line);
      } else if (key == "spec") {
        material.specular = readVec3Key(line);
      } else if (key == "shin") {
        material.shininess = readFloat(line);
      } else if (key == "tex") {
        material.texture = readTexturePath(line);
      } else if (key == "emit") {
        material.emission = readVec3Key(line);
      } else if (key == "emit_tex") {
        material.emissionTexture = readTexturePath(line);
      } else if (key == "two_sided") {
        material.twoSided = readSwitch(line);
      } else {
        failUnknownKey(line, "a material block", kMaterialKeys);
      }
    }
    // The format's rule: on a light, `tex` is the emission texture. An object drawn with an
    // emitting material is a light, so `tex` is its emission texture unless `emit_tex` is given.
    if (material.emission && !material.emissionTexture)
      material.emissionTexture = material.texture;
    // Checked after the block, by the builder, so that only the texture finally chosen has to
    // exist: its token is the last `tex`.
    builder_.addMaterial(std::move(material), BlockTokens(header, body));
  }

  void parseLight(const TokenLine& header, std::span<const TokenLine> body) {
    AreaLightDesc light;
    light.name = header.tokens[1].text;
    light.where = header.tokens.front().where;
    std::array<bool, 4> cornerGiven{};
    bool materialGiven = false;
    for (const TokenLine& line : body) {
      const std::string& key = keyOf(line);
      if (key.size() == 4 && key.starts_with("pos") && key[3] >= '1' && key[3] <= '4') {
        const auto corner = static_cast<std::size_t>(key[3] - '1');
        light.corners[corner] = readVec3Key(line);
        cornerGiven[corner] = true;
      } else if (key == "at") {
        light.emittingSidePoint = readVec3Key(line);
      } else if (key == "mat") {
        const Token& name = readWord(line, "material name");
        light.material = name.text;
        light.materialWhere = name.where;
        materialGiven = true;
      } else {
        failUnknownKey(line, "an area_light block", kLightKeys);
      }
    }
    std::vector<std::string_view> missing;
    for (std::size_t corner = 0; corner < 4; ++corner)
      if (!cornerGiven[corner])
        missing.push_back(kLightKeys[corner]);
    if (!materialGiven)
      missing.push_back("mat");
    requireKeys(missing, "area_light", light.name, light.where);
    builder_.addLight(std::move(light), BlockTokens(header, body));
  }

  void parseCamera(const TokenLine& header, std::span<const TokenLine> body) {
    CameraDesc camera;
    camera.name = header.tokens[1].text;
    camera.where = header.tokens.front().where;
    bool positionGiven = false;
    bool targetGiven = false;
    for (const TokenLine& line : body) {
      const std::string& key = keyOf(line);
      if (key == "pos") {
        camera.position = readVec3Key(line);
        positionGiven = true;
      } else if (key == "at") {
        camera.target = readVec3Key(line);
        targetGiven = true;
      } else if (key == "up") {
        camera.up = readVec3Key(line);
      } else if (key == "fovy") {
        camera.fovyDegrees = readFloat(line);
      } else if (key == "near") {
        camera.nearPlane = readFloat(line);
      } else if (key == "far") {
        camera.farPlane = readFloat(line);
      } else if (key == "screen_size") {
        expectValueCount(line, 1, 2, key, "number");
        camera.screenSize = {readInteger(line.tokens[1]), readInteger(line.tokens[2])};
      } else {
        failUnknownKey(line, "a camera block", kCameraKeys);
      }
    }
    std::vector<std::string_view> missing;
    if (!positionGiven)
      missing.push_back("pos");
    if (!targetGiven)
      missing.push_back("at");
    requireKeys(missing, "camera", camera.name, camera.where);
    builder_.setCamera(std::move(camera), BlockTokens(header, body));
  }

  void parseObject(const TokenLine& header, std::span<const TokenLine> body) {
    ObjectDesc object;
    object.model = resolve(header.tokens[1]);
    object.where = header.tokens.front().where;
    for (const TokenLine& line : body) {
      const std::string& key = keyOf(line);
      if (key == "translate") {
        object.transform.push_back({TransformStep::Kind::Translate, readVec3Key(line)});
      } else if (key == "rotate") {
        expectValueCount(line, 1, 4, key, "number");
        object.transform.push_back(
            {TransformStep::Kind::Rotate, readVec3(line, 2), parseNumber(line.tokens[1])});
      } else if (key == "scale") {
        object.transform.push_back({TransformStep::Kind::Scale, readScale(line)});
      } else if (key == "anim") {
        object.animations.push_back(readAnimation(line));
      } else if (key == "mat") {
        const Token& name = readWord(line, "material name");
        object.material = name.text;
        object.materialWhere = name.where;
      } else if (key == "normals") {
        object.normals = readNormalsMode(line);
      } else {
        failUnknownKey(line, "an object block", kObjectKeys);
      }
    }
    // The model file is checked after the block, by the builder.
    builder_.addObject(std::move(object), BlockTokens(header, body));
  }

  void parseImport(const TokenLine& header, std::span<const TokenLine> body) {
    const Token& path = header.tokens[1];
    if (import_)
      fail(header.tokens.front().where, "a second scene block " + quotePath(path.text) +
                                            ": only one glTF scene may be imported, " +
                                            quotePath(import_->written) + " is imported at " +
                                            import_->where.str());
    if (!body.empty())
      failUnknownKey(body.front(), "a scene block", kSceneKeys);
    import_ = Import{resolve(path), path.text, path.where};
  }

  static glm::vec3 readScale(const TokenLine& line) {
    const std::size_t found = line.tokens.size() - 1;
    if (found != 1 && found != 3)
      fail(found < 3 ? line.tokens.front().where : line.tokens[4].where,
           "expected 1 or 3 numbers after 'scale', found " + std::to_string(found));
    return found == 1 ? glm::vec3(parseNumber(line.tokens[1])) : readVec3(line);
  }

  static Animation readAnimation(const TokenLine& line) {
    if (line.tokens.size() < 2)
      fail(line.tokens.front().where, "expected 'rotate' or 'translate' after 'anim'");
    const Token& kind = line.tokens[1];
    if (!contains(kAnimationKinds, kind.text))
      fail(kind.where, "unknown animation " + quoteToken(kind.text) +
                           ", expected one of: " + listOf(kAnimationKinds));
    expectValueCount(line, 2, 4, "anim " + kind.text, "number");
    Animation animation;
    animation.kind = kind.text == "rotate" ? Animation::Kind::Rotate : Animation::Kind::Translate;
    animation.axis = readVec3(line, 2);
    animation.step = parseNumber(line.tokens[5]);
    return animation;
  }

  static bool readSwitch(const TokenLine& line) {
    const Token& value = readWord(line, "value");
    if (!contains(kSwitchValues, value.text))
      fail(value.where, "unknown " + quoteToken(keyOf(line)) + " value " + quoteToken(value.text) +
                            ", expected one of: " + listOf(kSwitchValues));
    return value.text == "on";
  }

  static NormalsMode readNormalsMode(const TokenLine& line) {
    const Token& mode = readWord(line, "mode");
    if (mode.text == "file")
      return NormalsMode::File;
    if (mode.text == "smooth")
      return NormalsMode::Smooth;
    if (mode.text == "flat")
      return NormalsMode::Flat;
    fail(mode.where, "unknown normals mode " + quoteToken(mode.text) +
                         ", expected one of: " + listOf(kNormalsModes));
  }

  struct Import {
    std::filesystem::path file;
    std::string written;  // as the scene file writes it
    SourceLocation where;
  };

  std::vector<TokenLine> lines_;
  std::filesystem::path directory_;
  SceneBuilder builder_;
  std::optional<Import> import_;
};

}  // namespace

SceneDesc parseScene(std::string_view text, const std::filesystem::path& file) {
  return SceneParser(text, file).parse();
}

SceneDesc parseSceneFile(const std::filesystem::path& file) {
  const SourceLocation wholeFile{file.string(), 0, 0};
  std::error_code error;
  if (!std::filesystem::exists(file, error))
    fail(wholeFile, "scene file not found");
  if (std::filesystem::is_directory(file, error))
    fail(wholeFile, "is a directory, not a scene file");
  if (!std::filesystem::is_regular_file(file, error))
    fail(wholeFile, "not a regular file");
  if (isGltfFile(file)) {
    SceneBuilder builder(file);
    importGltfScene(builder, file, wholeFile);
    return builder.finish();
  }
  // Checked before reading: the whole text is held in memory, and no real scene comes near this.
  constexpr std::uintmax_t kMaxSceneFileBytes = std::uintmax_t{256} << 20;
  const std::uintmax_t bytes = std::filesystem::file_size(file, error);
  if (!error && bytes > kMaxSceneFileBytes) {
    fail(wholeFile, "the scene file is " + std::to_string(bytes) +
                        " bytes; scene files are limited to 256 MiB");
  }
  std::ifstream in(file, std::ios::binary);
  if (!in)
    fail(wholeFile, "cannot open the scene file");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad())
    fail(wholeFile, "cannot read the scene file");
  return parseScene(text.str(), file);
}

}  // namespace penumbra
