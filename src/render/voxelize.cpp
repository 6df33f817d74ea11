#include "render/voxelize.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

#include "gl/dispatch.h"
#include "gl/uniforms.h"
#include "render/readback.h"
#include "render/render_error.h"

namespace penumbra {
namespace {

int roundUpTo32(int value) {
  return (value + 31) / 32 * 32;
}

// The scene's bounds and a margin, so that surfaces on the bounds lie inside the grid; a flat scene
// (a single floor) still gets a box with depth.
VoxelGridBox worldGridBox(const FrameGeometry& geometry) {
  const glm::vec3 extent = geometry.boundsMax - geometry.boundsMin;
  const float largest = std::max({extent.x, extent.y, extent.z, 1e-3f});
  const glm::vec3 margin = glm::vec3(0.01f * largest);
  return {geometry.boundsMin - margin, geometry.boundsMax + margin};
}

// Voxels per axis: x, y columns and z slices, whole words of 32 (VoxelSettings::Shape). Cubic
// voxels give a flat scene a flat grid, whose contact shadows then do not depend on which way the
// scene is longest (docs/shadows.md, "Cubic voxels"); z takes the nearest whole number of words,
// so its voxels differ from the others' size by up to 16 slices' worth.
glm::ivec3 gridResolution(const VoxelSettings& settings, glm::vec3 boxSize) {
  if (settings.grid != VoxelSettings::Grid::World)
    return {settings.resolution, settings.resolution, roundUpTo32(settings.depthSlices)};
  if (settings.shape == VoxelSettings::Shape::Equal)
    return {settings.resolution, settings.resolution, roundUpTo32(settings.resolution)};
  const double resolution = settings.resolution;
  const double voxelSide =
      std::cbrt(static_cast<double>(boxSize.x) * boxSize.y * boxSize.z) / resolution;
  glm::ivec3 voxels;
  for (int axis = 0; axis < 3; ++axis) {
    const double count = std::round(static_cast<double>(boxSize[axis]) / voxelSide);
    voxels[axis] = static_cast<int>(std::clamp(count, 1.0, static_cast<double>(kMaxVoxelsPerAxis)));
  }
  voxels.z = std::max(32, (voxels.z + 16) / 32 * 32);
  return voxels;
}

// Words of the voxel columns (voxel_grid.glsl, columnStart): along z, and for a world grid along x
// and y too, for the exact traversal.
std::size_t columnWordCount(const VoxelSettings& settings, glm::ivec3 resolution) {
  const auto n = glm::u64vec3(resolution);
  const glm::u64vec3 words = (n + std::uint64_t{31}) / std::uint64_t{32};
  std::size_t columns = n.x * n.y * words.z;
  if (settings.grid == VoxelSettings::Grid::World)
    columns += n.z * n.y * words.x + n.x * n.z * words.y;
  return columns;
}

// The occupancy pyramid of a world grid (GpuVoxelGrid::occupancy), its levels stored after the
// columns: halving until the coarsest level has at most 4 cells per axis, so that the clear-light
// test starts from at most 4^3 cells.
struct OccupancyPyramid {
  int levelCount = 0;
  std::array<glm::ivec4, gpu::kMaxOccupancyLevels> levels{};
  std::size_t words = 0;
};

// Words of level `level` of an occupancy pyramid with `cells` cells per axis: level 1 a bit per
// cell in columns along z, the others a word per cell (voxel_grid.glsl, cellBounds). Its build
// (voxel_occupancy.comp) runs a thread per word.
std::size_t occupancyLevelWords(int level, glm::ivec3 cells) {
  const auto columns = static_cast<std::size_t>(cells.x) * static_cast<std::size_t>(cells.y);
  const auto depth = static_cast<std::size_t>(cells.z);
  return level == 1 ? columns * ((depth + 31) / 32) : columns * depth;
}

OccupancyPyramid occupancyPyramid(const VoxelSettings& settings, glm::ivec3 resolution) {
  OccupancyPyramid pyramid;
  // The widened traversal tests voxels next to its segment, which the clear-light test does not
  // bound.
  if (settings.grid != VoxelSettings::Grid::World || settings.widen)
    return pyramid;
  const std::size_t firstWord = columnWordCount(settings, resolution);
  glm::ivec3 cells = resolution;
  while (pyramid.levelCount < gpu::kMaxOccupancyLevels &&
         (pyramid.levelCount == 0 || std::max({cells.x, cells.y, cells.z}) > 4)) {
    cells = (cells + 1) / 2;
    pyramid.levels[static_cast<std::size_t>(pyramid.levelCount)] =
        glm::ivec4(cells, static_cast<int>(firstWord + pyramid.words));
    ++pyramid.levelCount;
    pyramid.words += occupancyLevelWords(pyramid.levelCount, cells);
  }
  return pyramid;
}

// Where the boxes inside the voxels lie (GpuVoxelGrid::occupancy): after the occupancy levels, a
// word that counts the bricks handed out, the brick table (a word per cell of level
// kVoxelBrickLevel), then the pool. A grid without that level (a screen grid, --widen, or fewer
// than 9 voxels per axis) has none, nor one with --no-voxel-boxes.
struct BoxLayout {
  std::size_t counterWord = 0;  // 0: no boxes
  std::size_t tableWord = 0;
  std::size_t cells = 0;
  glm::ivec3 cellsPerAxis{0};
  std::size_t poolWord = 0;
};

BoxLayout boxLayout(const VoxelSettings& settings, glm::ivec3 resolution) {
  const OccupancyPyramid pyramid = occupancyPyramid(settings, resolution);
  BoxLayout layout;
  if (!settings.boxes || pyramid.levelCount < gpu::kVoxelBrickLevel)
    return layout;
  const glm::ivec4 cells = pyramid.levels[static_cast<std::size_t>(gpu::kVoxelBrickLevel - 1)];
  layout.counterWord = columnWordCount(settings, resolution) + pyramid.words;
  layout.tableWord = layout.counterWord + 1;
  layout.cellsPerAxis = glm::ivec3(cells);
  layout.cells = static_cast<std::size_t>(cells.x) * static_cast<std::size_t>(cells.y) *
                 static_cast<std::size_t>(cells.z);
  layout.poolWord = layout.tableWord + layout.cells;
  return layout;
}

gpu::GpuVoxelGrid describeGrid(const VoxelGridBox& box, const Camera& camera,
                               const VoxelSettings& settings, glm::ivec3 resolution,
                               unsigned brickCapacity) {
  gpu::GpuVoxelGrid grid{};
  const bool world = settings.grid == VoxelSettings::Grid::World;
  const int slices = resolution.z;
  grid.resolution = glm::ivec4(resolution, slices / 32);
  grid.modes = {world ? gpu::kGridWorld : gpu::kGridScreen,
                settings.traversal == VoxelSettings::Traversal::Dda ? gpu::kTraversalDda
                                                                    : gpu::kTraversalUniform,
                settings.steps, settings.widen ? 1 : 0};
  const OccupancyPyramid pyramid = occupancyPyramid(settings, resolution);
  const BoxLayout boxes = boxLayout(settings, resolution);
  grid.occupancy = {pyramid.levelCount, static_cast<int>(boxes.tableWord),
                    static_cast<int>(boxes.poolWord), static_cast<int>(brickCapacity)};
  for (std::size_t level = 0; level < pyramid.levels.size(); ++level)
    grid.occupancyLevels[level] = pyramid.levels[level];

  const glm::vec3 low = box.low;
  const glm::vec3 high = box.high;
  const glm::vec3 voxelSize = (high - low) / glm::vec3(resolution);
  grid.boundsMin = glm::vec4(low, settings.originOffset);
  grid.voxelSize = glm::vec4(voxelSize, glm::length(voxelSize));

  const glm::vec3 forward = glm::normalize(camera.target - camera.position);
  grid.viewForward = glm::vec4(forward, 0.0f);
  grid.eyePosition = glm::vec4(camera.position, 1.0f);
  float nearest = camera.farPlane;
  float farthest = camera.nearPlane;
  for (int corner = 0; corner < 8; ++corner) {
    const glm::vec3 point((corner & 1) ? high.x : low.x, (corner & 2) ? high.y : low.y,
                          (corner & 4) ? high.z : low.z);
    const float depth = glm::dot(point - camera.position, forward);
    nearest = std::min(nearest, depth);
    farthest = std::max(farthest, depth);
  }
  nearest = std::clamp(nearest, camera.nearPlane, camera.farPlane);
  farthest = std::clamp(farthest, nearest + 1e-3f, camera.farPlane);
  grid.depthRange = {nearest, farthest, 0.0f, 0.0f};
  if (!world) {
    // Voxel sizes of a screen grid vary with depth; the offset uses the size at mid depth.
    const float middle = 0.5f * (nearest + farthest);
    const float columnSize = 2.0f * middle * std::tan(glm::radians(camera.fovyDegrees) * 0.5f) /
                             static_cast<float>(settings.resolution);
    const float sliceSize = (farthest - nearest) / static_cast<float>(slices);
    grid.voxelSize.w = glm::length(glm::vec3(columnSize, columnSize, sliceSize));
  }
  const glm::mat4 clipFromWorld = camera.clipFromView() * camera.viewFromWorld();
  for (int column = 0; column < 4; ++column)
    grid.clipFromWorld[column] = clipFromWorld[column];
  return grid;
}

}  // namespace

std::size_t voxelGridBytes(const VoxelSettings& settings, glm::vec3 boxSize,
                           unsigned brickCapacity) {
  const bool world = settings.grid == VoxelSettings::Grid::World;
  const int slices = world ? settings.resolution : settings.depthSlices;
  if (settings.resolution < 1 || settings.resolution > kMaxVoxelsPerAxis || slices < 1 ||
      slices > kMaxVoxelsPerAxis) {
    throw RenderError("voxel grid resolution " + std::to_string(settings.resolution) + " x " +
                      std::to_string(slices) + " is outside 1 to " +
                      std::to_string(kMaxVoxelsPerAxis) + " per axis");
  }
  if (settings.steps < 1 || settings.steps > 4096)
    throw RenderError("ray steps " + std::to_string(settings.steps) + " are outside 1 to 4096");
  if (!(settings.originOffset >= 0.0f) || settings.originOffset > 100.0f) {
    throw RenderError("shadow-ray origin offset " + std::to_string(settings.originOffset) +
                      " is outside 0 to 100 voxel layers");
  }
  if (!world && settings.traversal == VoxelSettings::Traversal::Dda) {
    throw RenderError(
        "the exact (DDA) traversal needs the world grid; the screen grid is not linear in "
        "depth: use --traversal uniform with --voxel-grid screen");
  }
  const glm::ivec3 resolution = gridResolution(settings, boxSize);
  const BoxLayout boxes = boxLayout(settings, resolution);
  const std::size_t words =
      boxes.counterWord == 0
          ? columnWordCount(settings, resolution) + occupancyPyramid(settings, resolution).words
          : boxes.poolWord +
                std::size_t{brickCapacity} * static_cast<std::size_t>(gpu::kBrickWords);
  const std::size_t bytes = words * 4;
  if (bytes > kMaxVoxelGridBytes) {
    throw RenderError("a voxel grid of " + std::to_string(resolution.x) + " x " +
                      std::to_string(resolution.y) + " x " + std::to_string(resolution.z) +
                      " needs " + std::to_string(bytes >> 20) + " MiB, more than the limit of " +
                      std::to_string(kMaxVoxelGridBytes >> 20) + " MiB");
  }
  return bytes;
}

VoxelizePass::WorldPrograms VoxelizePass::compileWorldPrograms() {
  WorldPrograms programs;
  for (const WorldPass pass :
       {WorldPass::Solid, WorldPass::Surface, WorldPass::PlaneNormals, WorldPass::Boxes}) {
    for (const int dispatch : {gpu::kVoxelizeEveryTriangle, gpu::kVoxelizeSpanningTriangles,
                               gpu::kVoxelizeFurtherTiles}) {
      if (pass == WorldPass::Solid && dispatch == gpu::kVoxelizeSpanningTriangles)
        continue;
      programs[static_cast<std::size_t>(pass)][static_cast<std::size_t>(dispatch)] =
          gl::Program::compute("voxelize_world.comp",
                               {"VOXELIZE_PASS " + std::to_string(static_cast<int>(pass)),
                                "VOXELIZE_DISPATCH " + std::to_string(dispatch)});
    }
  }
  return programs;
}

VoxelizePass::VoxelizePass()
    : world_(compileWorldPrograms()),
      screen_(gl::Program::graphics("gbuffer.vert", "voxelize_screen.frag")),
      transpose_(gl::Program::compute("voxel_transpose.comp")),
      occupancy_(gl::Program::compute("voxel_occupancy.comp")),
      bricks_(gl::Program::compute("voxel_bricks.comp")) {}

void VoxelizePass::run(const Inputs& in, const Outputs& out) const {
  VoxelGrid& grid = out.grid;
  const VoxelGridBox box = worldGridBox(in.scene.geometry());
  const glm::ivec3 resolution = gridResolution(in.settings, box.high - box.low);
  const BoxLayout boxes = boxLayout(in.settings, resolution);
  // A first guess at the bricks a scene needs: surfaces take bricks in proportion to their area,
  // so as many as the grid's own six faces hold (13,824 on a cube of 192 voxels per axis).
  if (boxes.counterWord != 0 && grid.brickCapacity == 0)
    grid.brickCapacity = static_cast<unsigned>(2 * (boxes.cellsPerAxis.x * boxes.cellsPerAxis.y +
                                                    boxes.cellsPerAxis.y * boxes.cellsPerAxis.z +
                                                    boxes.cellsPerAxis.z * boxes.cellsPerAxis.x));
  const unsigned bricksNeeded = voxelize(in, box, grid);
  if (bricksNeeded > grid.brickCapacity) {
    // The pool ran out, so some voxels kept their whole box: grow it and voxelize again, once,
    // since the same frame needs no more.
    grid.brickCapacity = bricksNeeded + bricksNeeded / 4;
    voxelize(in, box, grid);
  } else if (bricksNeeded < grid.brickCapacity / 2) {
    // Far more than the scene needs: the next frame's pool is smaller.
    grid.brickCapacity = std::max(bricksNeeded + bricksNeeded / 4, 64u);
  }
}

unsigned VoxelizePass::voxelize(const Inputs& in, const VoxelGridBox& box, VoxelGrid& grid) const {
  const SceneGpu& scene = in.scene;
  const Camera& camera = in.camera;
  const VoxelSettings& settings = in.settings;
  const glm::ivec3 resolution = gridResolution(settings, box.high - box.low);
  const BoxLayout boxes = boxLayout(settings, resolution);
  const unsigned brickCapacity = boxes.counterWord == 0 ? 0 : grid.brickCapacity;
  const std::size_t bytes = voxelGridBytes(settings, box.high - box.low, brickCapacity);
  grid.description = describeGrid(box, camera, settings, resolution, brickCapacity);
  if (grid.wordCount != bytes / 4) {
    glNamedBufferData(grid.words.id(), static_cast<GLsizeiptr>(bytes), nullptr, GL_DYNAMIC_DRAW);
    grid.wordCount = bytes / 4;
  }
  glNamedBufferData(grid.header.id(), sizeof(grid.description), &grid.description, GL_DYNAMIC_DRAW);
  const std::uint32_t zero = 0;
  glClearNamedBufferData(grid.words.id(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
  glBindBufferBase(GL_UNIFORM_BUFFER, gpu::kVoxelGridBinding, grid.header.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gpu::kVoxelBinding, grid.words.id());

  const bool solid = settings.fill == VoxelSettings::Fill::Solid;
  // Solid mode flips the interiors first; the surface pass then adds the shells on top.
  for (const bool solidPass : {true, false}) {
    if (solidPass && !solid)
      continue;
    if (settings.grid == VoxelSettings::Grid::World) {
      voxelizeWorld(scene, grid, solidPass ? WorldPass::Solid : WorldPass::Surface);
    } else {
      voxelizeScreen(scene, camera, grid, solidPass);
    }
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  }
  if (settings.grid != VoxelSettings::Grid::World)
    return 0;
  transposeColumns(grid);
  buildOccupancy(grid);
  if (boxes.counterWord == 0)
    return 0;
  const auto cells = static_cast<unsigned>(boxes.cells);
  gl::dispatchLinear(bricks_, cells);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
  // Each voxel's plane first, then the boxes and the slabs around those planes.
  for (const WorldPass pass : {WorldPass::PlaneNormals, WorldPass::Boxes}) {
    voxelizeWorld(scene, grid, pass);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  }
  // The one read-back of the pass: how many bricks the scene needs, so that the pool can grow.
  return readBuffer<std::uint32_t>(grid.words.id(), boxes.counterWord, 1).front();
}

void VoxelizePass::buildOccupancy(VoxelGrid& grid) const {
  occupancy_.use();
  for (int level = 1; level <= grid.description.occupancy.x; ++level) {
    const glm::ivec4 cells = grid.description.occupancyLevels[static_cast<std::size_t>(level - 1)];
    const auto words = static_cast<unsigned>(occupancyLevelWords(level, glm::ivec3(cells)));
    gl::setUniform(occupancy_, "level", level);
    gl::dispatchLinear(occupancy_, words);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  }
}

void VoxelizePass::transposeColumns(VoxelGrid& grid) const {
  // voxel_transpose.comp: a thread per tile of 32 words along z by 32 voxels along the axis, in
  // each plane of constant y (axis 0) or x (axis 1).
  const glm::ivec4 resolution = grid.description.resolution;
  const std::array<unsigned, 2> tiles = {
      static_cast<unsigned>(resolution.y * resolution.w * ((resolution.x + 31) / 32)),
      static_cast<unsigned>(resolution.x * resolution.w * ((resolution.y + 31) / 32))};
  for (int axis = 0; axis < 2; ++axis) {
    gl::setUniform(transpose_, "axis", axis);
    gl::dispatchLinear(transpose_, tiles[static_cast<std::size_t>(axis)]);
  }
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

void VoxelizePass::voxelizeWorld(const SceneGpu& scene, VoxelGrid& grid, WorldPass pass) const {
  const auto& programs = world_[static_cast<std::size_t>(pass)];
  const gl::Program& everyTriangle = programs[gpu::kVoxelizeEveryTriangle];
  const gl::Program& furtherTiles = programs[gpu::kVoxelizeFurtherTiles];
  const std::array<std::array<GLuint, 2>, 2> buffers = {
      {{scene.surfaceVertexBuffer(), scene.surfaceIndexBuffer()},
       {scene.lightVertexBuffer(), scene.lightIndexBuffer()}}};
  const std::array<unsigned, 2> triangleCounts = {scene.surfaceTriangleCount(),
                                                  scene.lightTriangleCount()};
  // voxelize_world.comp: tiles of 16 x 16 voxel columns; a triangle's bounding box spans up to
  // `tiles` of them per side.
  const glm::ivec4 resolution = grid.description.resolution;
  const auto tiles =
      static_cast<unsigned>((std::max({resolution.x, resolution.y, resolution.z}) + 15) / 16);
  gl::setUniform(furtherTiles, "tilesPerSide", static_cast<int>(tiles));
  // Triangles go in batches of as many work groups as a dispatch may have along x, so that the
  // listed triangles' dispatches, a group per 64 listed triangles, stay within the limit too; and
  // of few enough that the further tiles' dispatch numbers each of its invocations (a triangle's
  // further tiles one after the other, fewer than tiles^2 per triangle, over the listed
  // triangles rounded up to whole work groups) within 32 bits.
  const unsigned groupSize = furtherTiles.workGroupSize().x;
  const unsigned batchSize =
      std::min(gl::kMaxWorkGroupsPerDimension * everyTriangle.workGroupSize().x,
               std::numeric_limits<std::uint32_t>::max() / (tiles * tiles) - groupSize);
  const unsigned mostTriangles =
      std::min(std::max(triangleCounts[0], triangleCounts[1]), batchSize);
  constexpr std::size_t kListCount = 2;
  if (grid.triangleListCapacity < mostTriangles) {
    glNamedBufferData(grid.triangleLists.id(),
                      static_cast<GLsizeiptr>(kListCount * (sizeof(gpu::DispatchIndirect) +
                                                            sizeof(std::uint32_t) * mostTriangles)),
                      nullptr, GL_DYNAMIC_DRAW);
    grid.triangleListCapacity = mostTriangles;
  }
  // The dispatches after the first, each over the triangles of a list; the solid pass lists only
  // those that span more than one tile.
  struct ListedDispatch {
    int stage;
    int list;
  };
  constexpr std::array<ListedDispatch, kListCount> listedDispatches = {
      {{gpu::kVoxelizeSpanningTriangles, gpu::kSpanningTriangleList},
       {gpu::kVoxelizeFurtherTiles, gpu::kLargeTriangleList}}};
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gpu::kTriangleListBinding, grid.triangleLists.id());
  for (std::size_t part = 0; part < buffers.size(); ++part) {
    if (triangleCounts[part] == 0)
      continue;
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gpu::kGeometryVertexBinding, buffers[part][0]);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gpu::kGeometryIndexBinding, buffers[part][1]);
    for (unsigned first = 0; first < triangleCounts[part]; first += batchSize) {
      const unsigned count = std::min(triangleCounts[part] - first, batchSize);
      // Every triangle first; it lists those that span more than a voxel, and the next dispatch
      // those that span more than a tile.
      const std::array<gpu::DispatchIndirect, kListCount> emptyLists = {
          {{0, 1, 1, 0}, {0, tiles * tiles - 1, 1, 0}}};
      glNamedBufferSubData(grid.triangleLists.id(), 0, sizeof(emptyLists), emptyLists.data());
      gl::setUniform(everyTriangle, "firstTriangle", first);
      gl::setUniform(everyTriangle, "endTriangle", first + count);
      everyTriangle.use();
      const glm::uvec3 groups = everyTriangle.groupsFor({count, 1, 1});
      glDispatchCompute(groups.x, groups.y, groups.z);
      glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, grid.triangleLists.id());
      for (const ListedDispatch& dispatch : listedDispatches) {
        if (pass == WorldPass::Solid && dispatch.stage == gpu::kVoxelizeSpanningTriangles)
          continue;
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
        programs[static_cast<std::size_t>(dispatch.stage)].use();
        glDispatchComputeIndirect(static_cast<GLintptr>(sizeof(gpu::DispatchIndirect)) *
                                  dispatch.list);
      }
      glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, 0);
      glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    }
  }
}

void VoxelizePass::voxelizeScreen(const SceneGpu& scene, const Camera& camera, VoxelGrid& grid,
                                  bool solid) const {
  const glm::ivec2 columns(grid.description.resolution.x, grid.description.resolution.y);
  glNamedFramebufferParameteri(emptyFramebuffer_.id(), GL_FRAMEBUFFER_DEFAULT_WIDTH, columns.x);
  glNamedFramebufferParameteri(emptyFramebuffer_.id(), GL_FRAMEBUFFER_DEFAULT_HEIGHT, columns.y);
  glBindFramebuffer(GL_FRAMEBUFFER, emptyFramebuffer_.id());
  glViewport(0, 0, columns.x, columns.y);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  gl::setUniform(screen_, "clipFromWorld", camera.clipFromView() * camera.viewFromWorld());
  gl::setUniform(screen_, "solidFill", solid);
  screen_.use();
  glBindVertexArray(scene.surfaceVertexArray());
  glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(scene.surfaceTriangleCount() * 3),
                 GL_UNSIGNED_INT, nullptr);
  glBindVertexArray(scene.lightVertexArray());
  glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(scene.lightTriangleCount() * 3),
                 GL_UNSIGNED_INT, nullptr);
  glBindVertexArray(0);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

}  // namespace penumbra
