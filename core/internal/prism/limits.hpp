// The input limits a scene is checked against (docs/scene-format.md,
// "Limits"). The image and sample bounds are the format's; the others are
// this implementation's, chosen so that a hostile or mistaken file is
// refused with a message before it can exhaust the stack or memory.
#pragma once

#include <cstddef>
#include <cstdint>

namespace prism::limits {

// The format's bounds on `image` (and the command-line flags that override it).
constexpr int kMaxImageSide = 16384;
constexpr int kMaxSpp = 4096;
constexpr int kMaxDepth = 64;

// A scene file larger than this is refused from its size, before it is read.
// The 100,000-sphere benchmark scene is about 10 MiB.
constexpr std::uintmax_t kMaxSceneFileBytes = std::uintmax_t(64) << 20;

// Arrays and objects nested deeper than this are refused while parsing. A
// valid scene nests at most 5 levels (the root, objects, objects[i],
// objects[i].rotation, objects[i].rotation.axis); the bound keeps every
// later walk over the tree shallow.
constexpr size_t kMaxJsonDepth = 64;

// All textures of one scene together (cube-map faces included) hold at most
// this many pixels: 4 GiB of RGBA float texels (and 1 GiB of codes beside
// them where the files are 8-bit: Texture::codes). Each file's size is checked
// from its header before any pixel is allocated.
constexpr size_t kMaxTexturePixels = size_t(1) << 28;

// A material's `ior` is 0 (opaque) or in [1, kMaxIor]: no material comes
// near it (diamond 2.42, germanium 4.0), and under it eta² in the refraction
// can never overflow into a NaN.
constexpr double kMaxIor = 100.0;

// `prism trace --rays`: at most this many rays (about 1 GiB of rays and
// results in memory), counted while the file is read.
constexpr size_t kMaxTraceRays = size_t(10) << 20;

}  // namespace prism::limits
