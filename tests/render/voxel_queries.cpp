#include "render/voxel_queries.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <filesystem>

#include "gl/program.h"
#include "gl/uniforms.h"
#include "render/readback.h"
#include "shared.h"
#include "test_files.h"

namespace penumbra::test {
namespace {

// Queries of voxel_queries.comp and its buffers beyond shared.h's.
constexpr int kQuerySegment = 0;
constexpr int kQueryVisibility = 1;
constexpr int kQueryCoordinates = 2;
constexpr int kQueryClearLight = 3;
constexpr int kQuerySegmentByColumns = 4;
constexpr GLuint kEndsBinding = 11;
constexpr GLuint kAnswersBinding = 12;

// The kernel's includes are the renderer's shaders: it is compiled from the source tree's shader
// folder, named relative to it, while this is alive.
struct SourceShaderFolder {
  SourceShaderFolder() { gl::setShaderDirectory(gl::sourceShaderDirectory()); }
  ~SourceShaderFolder() { gl::setShaderDirectory(std::nullopt); }
  SourceShaderFolder(const SourceShaderFolder&) = delete;
  SourceShaderFolder& operator=(const SourceShaderFolder&) = delete;
};

gl::Program loadKernel() {
  const SourceShaderFolder folder;
  const auto kernel = sourceDirectory() / "tests/data/shaders/voxel_queries.comp";
  return gl::Program::compute(
      std::filesystem::relative(kernel, gl::sourceShaderDirectory()).string());
}

glm::vec4 point(glm::vec3 value) {
  return glm::vec4(value, 1.0f);
}

int wordsAlong(glm::ivec3 resolution, int axis) {
  return (resolution[axis] + 31) / 32;
}

std::size_t blockWords(glm::ivec3 resolution, int axis) {
  return static_cast<std::size_t>(resolution[(axis + 1) % 3]) * resolution[(axis + 2) % 3] *
         wordsAlong(resolution, axis);
}

}  // namespace

std::size_t voxelWordCount(glm::ivec3 resolution, bool allAxes) {
  return allAxes ? blockWords(resolution, 0) + blockWords(resolution, 1) + blockWords(resolution, 2)
                 : blockWords(resolution, 2);
}

std::size_t occupancyWordCount(const gpu::GpuVoxelGrid& grid) {
  std::size_t words = 0;
  for (int level = 1; level <= grid.occupancy.x; ++level) {
    const glm::ivec4 cells = grid.occupancyLevels[static_cast<std::size_t>(level - 1)];
    const auto cellCount = static_cast<std::size_t>(cells.x) * static_cast<std::size_t>(cells.y) *
                           static_cast<std::size_t>(cells.z);
    words += level == 1 ? static_cast<std::size_t>(cells.x) * static_cast<std::size_t>(cells.y) *
                              ((static_cast<std::size_t>(cells.z) + 31) / 32)
                        : cellCount;
  }
  return words;
}

std::size_t boxWordCount(const gpu::GpuVoxelGrid& grid) {
  if (grid.occupancy.y == 0)
    return 0;
  const std::size_t firstWord =
      voxelWordCount(glm::ivec3(grid.resolution), true) + occupancyWordCount(grid);
  return static_cast<std::size_t>(grid.occupancy.z) - firstWord +
         static_cast<std::size_t>(grid.occupancy.w) * static_cast<std::size_t>(gpu::kBrickWords);
}

namespace {

// The inverse of voxel_content.glsl's encodePlaneNormal: octahedral u and v on 255 steps each.
glm::vec3 decodePlaneNormal(std::uint32_t code) {
  const glm::vec2 octahedral =
      (glm::vec2(static_cast<float>(code & 255u), static_cast<float>(code >> 8 & 255u)) - 127.0f) /
      127.0f;
  return glm::normalize(glm::vec3(
      octahedral, std::max(1.0f - std::abs(octahedral.x) - std::abs(octahedral.y), 0.0f)));
}

}  // namespace

VoxelContent voxelContent(const std::vector<std::uint32_t>& words, const gpu::GpuVoxelGrid& grid,
                          glm::ivec3 voxel) {
  const glm::vec3 whole(voxel);
  const VoxelContent wholeVoxel{whole, whole + 1.0f, {}};
  if (grid.occupancy.y == 0)
    return wholeVoxel;
  const glm::ivec4 cells = grid.occupancyLevels[gpu::kVoxelBrickLevel - 1];
  const glm::ivec3 cell = voxel >> gpu::kVoxelBrickLevel;
  const std::uint32_t brick = words[static_cast<std::size_t>(
      grid.occupancy.y + (cell.z * cells.y + cell.y) * cells.x + cell.x)];
  if (brick == gpu::kNoBrick)
    return wholeVoxel;
  const int side = 1 << gpu::kVoxelBrickLevel;
  const glm::ivec3 inBrick = voxel & (side - 1);
  const std::size_t first =
      static_cast<std::size_t>(grid.occupancy.z) + std::size_t{brick} * gpu::kBrickWords +
      static_cast<std::size_t>(gpu::kVoxelContentWords) *
          static_cast<std::size_t>((inBrick.z * side + inBrick.y) * side + inBrick.x);
  VoxelContent content = wholeVoxel;
  for (int axis = 0; axis < 3; ++axis) {
    const std::uint32_t slices = words[first + static_cast<std::size_t>(axis)];
    if (slices == 0)
      return wholeVoxel;
    content.low[axis] += static_cast<float>(std::countr_zero(slices)) / gpu::kVoxelBoxSlices;
    content.high[axis] =
        whole[axis] + static_cast<float>(32 - std::countl_zero(slices)) / gpu::kVoxelBoxSlices;
  }
  for (std::size_t plane = 0; plane < 2; ++plane) {
    const std::uint32_t word = words[first + 3 + plane];
    const std::uint32_t code = plane == 0 ? word >> 16 : 0xffffu - (word >> 16);
    VoxelSlab slab;
    slab.normal = decodePlaneNormal(code);
    const float sliceSize =
        (std::abs(slab.normal.x) + std::abs(slab.normal.y) + std::abs(slab.normal.z)) /
        gpu::kVoxelPlaneSlices;
    const std::uint32_t slices = word & 0xffffu;
    const float half = 0.5f * gpu::kVoxelPlaneSlices;
    slab.low = (static_cast<float>(std::countr_zero(slices)) - half) * sliceSize;
    slab.high = (static_cast<float>(32 - std::countl_zero(slices)) - half) * sliceSize;
    content.slabs.push_back(slab);
  }
  return content;
}

std::pair<std::size_t, unsigned> voxelLocation(glm::ivec3 resolution, int axis, glm::ivec3 voxel) {
  std::size_t block = 0;
  for (const int earlier : {2, 0, 1}) {
    if (earlier == axis)
      break;
    block += blockWords(resolution, earlier);
  }
  const int u = voxel[(axis + 1) % 3];
  const int v = voxel[(axis + 2) % 3];
  const std::size_t column = static_cast<std::size_t>(v) * resolution[(axis + 1) % 3] + u;
  return {block + column * wordsAlong(resolution, axis) + voxel[axis] / 32,
          static_cast<unsigned>(voxel[axis] % 32)};
}

VoxelQueries::VoxelQueries() : program_(loadKernel()) {
  // The kernel's VPL buffer must have storage even for queries that do not read it.
  glNamedBufferData(vpls_.id(), sizeof(gpu::GpuVpl), nullptr, GL_STATIC_DRAW);
}

void VoxelQueries::useGrid(GLuint header, GLuint words) {
  header_ = header;
  words_ = words;
}

std::vector<glm::vec4> VoxelQueries::run(int query, const std::vector<glm::vec4>& ends,
                                         std::size_t count, int vplCount) const {
  gl::Buffer endsBuffer;
  gl::Buffer answers;
  glNamedBufferData(endsBuffer.id(), static_cast<GLsizeiptr>(ends.size() * sizeof(glm::vec4)),
                    ends.data(), GL_STATIC_DRAW);
  glNamedBufferData(answers.id(), static_cast<GLsizeiptr>(count * sizeof(glm::vec4)), nullptr,
                    GL_STATIC_READ);
  glBindBufferBase(GL_UNIFORM_BUFFER, gpu::kVoxelGridBinding, header_);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gpu::kVoxelBinding, words_);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, gpu::kVplBinding, vpls_.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kEndsBinding, endsBuffer.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kAnswersBinding, answers.id());
  gl::setUniform(program_, "query", query);
  gl::setUniform(program_, "queryCount", static_cast<GLuint>(count));
  gl::setUniform(program_, "vplCount", vplCount);
  program_.use();
  const glm::uvec3 groups = program_.groupsFor({static_cast<unsigned>(count), 1, 1});
  glDispatchCompute(groups.x, groups.y, groups.z);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  return readBuffer<glm::vec4>(answers.id(), 0, count);
}

std::vector<bool> VoxelQueries::segmentsBlocked(const std::vector<glm::vec3>& ends,
                                                Walk walk) const {
  std::vector<glm::vec4> packed;
  for (const glm::vec3 end : ends)
    packed.push_back(point(end));
  std::vector<bool> blocked;
  const int query = walk == Walk::AsRendered ? kQuerySegment : kQuerySegmentByColumns;
  for (const glm::vec4& answer : run(query, packed, ends.size() / 2, 0))
    blocked.push_back(answer.x != 0.0f);
  return blocked;
}

std::vector<bool> VoxelQueries::vplsVisible(const std::vector<Point>& points,
                                            const std::vector<Vpl>& vpls) const {
  std::vector<gpu::GpuVpl> gpuVpls;
  for (const Vpl& vpl : vpls)
    gpuVpls.push_back(
        {glm::vec4(vpl.position, 0.0f), glm::vec4(vpl.normal, 0.0f), glm::vec4(0.0f)});
  glNamedBufferData(vpls_.id(), static_cast<GLsizeiptr>(gpuVpls.size() * sizeof(gpu::GpuVpl)),
                    gpuVpls.data(), GL_STATIC_DRAW);
  std::vector<glm::vec4> packed;
  for (const Point& p : points) {
    packed.push_back(point(p.position));
    packed.push_back(glm::vec4(p.normal, 0.0f));
  }
  std::vector<bool> visible;
  const auto vplCount = static_cast<int>(vpls.size());
  for (const glm::vec4& answer :
       run(kQueryVisibility, packed, points.size() * vpls.size(), vplCount))
    visible.push_back(answer.x != 0.0f);
  return visible;
}

std::vector<bool> VoxelQueries::lightClear(const std::vector<Point>& points,
                                           const std::array<glm::vec3, 4>& corners,
                                           glm::vec3 lightNormal) const {
  std::vector<glm::vec4> packed;
  for (const Point& p : points) {
    packed.push_back(point(p.position));
    packed.push_back(glm::vec4(p.normal, 0.0f));
  }
  for (const glm::vec3 corner : corners)
    packed.push_back(point(corner));
  packed.push_back(glm::vec4(lightNormal, 0.0f));
  std::vector<bool> clear;
  for (const glm::vec4& answer : run(kQueryClearLight, packed, points.size(), 0))
    clear.push_back(answer.x != 0.0f);
  return clear;
}

std::vector<glm::vec3> VoxelQueries::gridCoordinates(const std::vector<glm::vec3>& points) const {
  std::vector<glm::vec4> packed;
  for (const glm::vec3 p : points)
    packed.push_back(point(p));
  std::vector<glm::vec3> coordinates;
  for (const glm::vec4& answer : run(kQueryCoordinates, packed, points.size(), 0))
    coordinates.push_back(glm::vec3(answer));
  return coordinates;
}

std::vector<VoxelQueries::Point> surfacePoints(const GBuffer& gbuffer) {
  const Image positions = readTexture(gbuffer.positionDepth.id(), gbuffer.size, RowOrder::TopFirst);
  const Image normals = readTexture(gbuffer.normalKind.id(), gbuffer.size, RowOrder::TopFirst);
  std::vector<VoxelQueries::Point> points;
  for (std::size_t i = 0; i < positions.pixels.size(); ++i)
    if (static_cast<int>(normals.pixels[i].w) == gpu::kPixelSurface)
      points.push_back({glm::vec3(positions.pixels[i]), glm::vec3(normals.pixels[i])});
  return points;
}

}  // namespace penumbra::test
