#pragma once
// Scenes built in memory: materials, quad lights, a camera, and objects that are model files or
// meshes given as arrays. Every check of the scene format that is not about its syntax lives here,
// and the parser is a client: a scene built through this API and the same scene in a file pass the
// same checks and fail with the same messages (SceneError::message()). A scene built in memory has
// no file, so its errors are located at the builder's origin name (e.g. "in-memory scene: error:
// 'dif' values must be in [0, 1], found '1.5'").
//
// Nothing here has a syntax counterpart: a missing key cannot be missing from a struct, and a
// number that is not finite is reported as the tokenizer reports it ("expected a finite number").

#include <cstdint>
#include <filesystem>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "scene/model.h"
#include "scene/scene_desc.h"

namespace penumbra {

// One value as an error message names it: where it is, and how it is written.
struct ValueSite {
  SourceLocation where;
  std::string text;
};

// Where the values of one block came from. The default (a block built in memory) knows nothing,
// so each value is located at the block and quoted as the builder formats it; the parser answers
// with the token that holds the value, as written in the file.
class ValueSites {
 public:
  static constexpr std::size_t kLast = std::numeric_limits<std::size_t>::max();
  virtual ~ValueSites() = default;
  // Token `index` (1: the first value after the key) of the `occurrence`-th `key` statement of the
  // block (counted from 0; kLast: the last one), or of the block's header line for key "" (1: the
  // block's name or model path). nullopt when the block has no such token.
  virtual std::optional<ValueSite> find(std::string_view key, std::size_t index,
                                        std::size_t occurrence) const;
};

// A triangle mesh given as arrays, in the object's own coordinates.
struct MeshArrays {
  std::string name;  // names the mesh in messages
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;     // one per position, or none (then computed, see NormalsMode)
  std::vector<glm::vec2> uvs;         // one per position, or none (then (0, 0))
  std::vector<glm::uvec3> triangles;  // indices into positions
};

// A model holding the one mesh, drawn with the default material unless the object names one.
// `normals` as for a model file: `file` keeps the given normals (smooth ones when there are none
// or any is zero), `smooth` and `flat` compute them. Throws SceneError at `where` for an empty
// mesh, array sizes that differ, indices out of range and values that are not finite.
std::shared_ptr<const Model> makeMeshModel(const MeshArrays& mesh, NormalsMode normals,
                                           const SourceLocation& where);

class SceneBuilder {
 public:
  // `origin` names the scene: a scene file's path, or for a scene built in memory a name that
  // locates its errors. Paths in the descriptions are used as given (the parser resolves them
  // against the scene file's directory).
  explicit SceneBuilder(std::filesystem::path origin = "in-memory scene");

  // Each call checks its block and throws SceneError at the first problem. A `where` left empty
  // is set to the origin.
  void addMaterial(MaterialDesc material, const ValueSites& sites = ValueSites());
  void addLight(AreaLightDesc light, const ValueSites& sites = ValueSites());
  // One camera per scene: a second call is an error, as a second camera block is.
  void setCamera(CameraDesc camera, const ValueSites& sites = ValueSites());
  // A model file (`model`) or a mesh in memory (`mesh`, see makeMeshModel); sets staticTransform
  // from the transform steps.
  void addObject(ObjectDesc object, const ValueSites& sites = ValueSites());

  // Whether a material of this name, or a camera, was added: an imported glTF scene leaves both
  // to the scene file (gltf_import.h).
  bool hasMaterial(const std::string& name) const;
  bool hasCamera() const;
  // A note for the user about the scene, e.g. a feature of an imported file that is not used.
  void addWarning(std::string warning);

  // Checks that every material named by a light or an object exists, and returns the scene.
  SceneDesc finish();

  // Where errors of calls without a location are reported.
  SourceLocation origin() const;

 private:
  SceneDesc scene_;
  std::map<std::string, SourceLocation> materialNames_;
  std::map<std::string, SourceLocation> lightNames_;
  struct MaterialReference {
    std::string name;
    SourceLocation where;
  };
  std::vector<MaterialReference> references_;  // in the order of the calls
};

}  // namespace penumbra
