#pragma once
// Indirect light, pass 2: secondary VPLs, sampled from the reflective shadow maps in proportion
// to the flux their texels reflect. On the CPU: the maps are small (5 x 64^2 texels per light by
// default), so reading them back costs little, and a plain prefix sum with a binary search keeps
// the sampling exact and easy to check; on llvmpipe the stall of the read-back costs nothing
// the GPU could have overlapped.

#include <vector>

#include "image/image.h"
#include "render/vpls.h"
#include "shared.h"

namespace penumbra {

// `count` VPLs placed by stratified inverse-CDF sampling over the texels' flux (sum of the rgb
// radiance times the area): sample k takes the texel where the cumulative flux first exceeds
// (k + 1/2)/count of the total, so the result is deterministic. A texel chosen with probability
// p stands for area A / (count p) with the texel's radiance, so that every VPL carries
// 1/count of the total flux summed over channels, and the sum of the VPLs' flux (pi L A) is the
// maps' total. The images hold the atlas in texel order (ReflectiveShadowMap::read): each VPL's
// normal.w is the index of the light whose map it came from, its texel row divided by
// `faceSize`. The VPLs come in cluster order: by light, by face of the map, then along the
// Morton curve of their texel within the face, so that a run of consecutive VPLs (and of each
// interleaved subset's) lies close together on one surface, and the voxel programs shadow each
// run with one ray (secondary_gather.glsl). Empty when no texel reflects any light.
std::vector<gpu::GpuVpl> sampleSecondaryVpls(const Image& positionArea, const Image& normal,
                                             const Image& radiance, int count, int faceSize);

// Uploads `vpls` into `target` (readVpls in vpls.h reads them back).
void uploadVpls(const std::vector<gpu::GpuVpl>& vpls, VplBuffer& target);

}  // namespace penumbra
