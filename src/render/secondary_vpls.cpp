#include "render/secondary_vpls.h"

#include <algorithm>
#include <cstdint>

namespace penumbra {

namespace {

// The Morton code of a texel within its face: the bits of u and v interleaved, so that texels
// close together in the face lie close together in the code's order.
std::uint64_t mortonCode(std::uint32_t u, std::uint32_t v) {
  std::uint64_t code = 0;
  for (int bit = 0; bit < 16; ++bit) {
    code |= std::uint64_t{(u >> bit) & 1u} << (2 * bit);
    code |= std::uint64_t{(v >> bit) & 1u} << (2 * bit + 1);
  }
  return code;
}

}  // namespace

std::vector<gpu::GpuVpl> sampleSecondaryVpls(const Image& positionArea, const Image& normal,
                                             const Image& radiance, int count, int faceSize) {
  std::vector<double> cumulative(radiance.pixels.size());
  double total = 0.0;
  for (std::size_t i = 0; i < radiance.pixels.size(); ++i) {
    const glm::vec4 L = radiance.pixels[i];
    const double area = positionArea.pixels[i].w;
    const double flux = normal.pixels[i].w > 0.0f ? (double{L.r} + L.g + L.b) * area : 0.0;
    total += std::max(flux, 0.0);
    cumulative[i] = total;
  }
  std::vector<gpu::GpuVpl> vpls;
  if (!(total > 0.0) || count < 1)
    return vpls;
  std::vector<std::size_t> texels(static_cast<std::size_t>(count));
  for (int k = 0; k < count; ++k) {
    const double target = (k + 0.5) / count * total;
    const auto found = std::upper_bound(cumulative.begin(), cumulative.end(), target);
    texels[static_cast<std::size_t>(k)] = static_cast<std::size_t>(std::min<std::ptrdiff_t>(
        found - cumulative.begin(), static_cast<std::ptrdiff_t>(cumulative.size()) - 1));
  }
  const auto width = static_cast<std::size_t>(radiance.width);
  const auto face = static_cast<std::size_t>(faceSize);
  const auto clusterOrder = [&](std::size_t index) {
    const std::size_t row = index / width;
    const std::size_t column = index % width;
    const std::uint64_t light = row / face;
    const std::uint64_t faceOfLight = column / face;
    return light << 40 | faceOfLight << 32 |
           mortonCode(static_cast<std::uint32_t>(column % face),
                      static_cast<std::uint32_t>(row % face));
  };
  std::ranges::stable_sort(texels, {}, clusterOrder);
  vpls.reserve(texels.size());
  for (const std::size_t index : texels) {
    const glm::vec4 L = radiance.pixels[index];
    const double sum = double{L.r} + L.g + L.b;
    // p = sum * A / total, so A / (count p) = total / (count sum).
    const auto area = static_cast<float>(total / (count * sum));
    gpu::GpuVpl vpl;
    vpl.positionArea = glm::vec4(glm::vec3(positionArea.pixels[index]), area);
    const auto row = static_cast<int>(index / width);
    vpl.normal = glm::vec4(glm::vec3(normal.pixels[index]), static_cast<float>(row / faceSize));
    vpl.radiance = glm::vec4(glm::vec3(L), 0.0f);
    vpls.push_back(vpl);
  }
  return vpls;
}

void uploadVpls(const std::vector<gpu::GpuVpl>& vpls, VplBuffer& target) {
  const auto count = static_cast<int>(vpls.size());
  // The buffer keeps room for at least one VPL so that it can always be bound.
  glNamedBufferData(target.buffer.id(),
                    static_cast<GLsizeiptr>(std::max<std::size_t>(vpls.size(), 1)) *
                        static_cast<GLsizeiptr>(sizeof(gpu::GpuVpl)),
                    vpls.empty() ? nullptr : vpls.data(), GL_DYNAMIC_DRAW);
  target.count = count;
}

}  // namespace penumbra
