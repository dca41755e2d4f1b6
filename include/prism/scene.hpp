// The scene model: what a validated scene file turns into. Backends read it;
// only the loader (scene_loader.hpp) and the public API build it.
#pragma once

#include <array>
#include <cstddef>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "prism/primitive_abi.h"

namespace prism {

class PrimitivePlugin;  // registry.hpp

// Linear RGBA float texels, row 0 = top row of the file.
struct Texture {
  std::string name;
  std::filesystem::path path;
  int width = 0;
  int height = 0;
  std::vector<glm::vec4> texels;  // width * height
  // The same texels a quarter the size, where each channel takes one of 256
  // values (8-bit files): R, G, B and A codes from the low byte up, and each
  // code's value, colour codes' first (256), then alpha's (256), so that
  // texels[i][c] == code_values[(c == 3 ? 256 : 0) + code c of codes[i]]
  // for every texel, bit for bit. The CPU sampler reads these when present:
  // a scene's textures then stay in a core's second-level cache. Empty for
  // other files and for textures built by hand; code that changes texels
  // clears them.
  std::vector<uint32_t> codes;
  std::vector<double> code_values;
};

struct Material {
  std::string name;
  glm::dvec3 color{0.8, 0.8, 0.8};
  int texture = -1;  // index into Scene::textures
  glm::dvec2 uv_scale{1, 1};
  glm::dvec2 uv_offset{0, 0};
  double diffuse = 1.0;
  double specular = 0.0;
  double shininess = 32.0;
  double reflect = 0.0;
  double ior = 0.0;  // 0: opaque
  glm::dvec3 absorb{0, 0, 0};
  bool dielectric() const { return ior >= 1.0; }
};

struct Light {
  enum class Type { Point, Directional };
  Type type = Type::Point;
  glm::dvec3 position{0, 0, 0};   // point
  glm::dvec3 direction{0, -1, 0}; // directional, unit length (as given, normalized)
  glm::dvec3 color{1, 1, 1};
  double intensity = 1.0;
  double linear = 0.0;
  double quadratic = 0.0;
  double radius = 0.0;  // > 0: a visible sphere
  bool visible_sphere() const { return type == Type::Point && radius > 0.0; }
};

struct Box3 {
  glm::dvec3 lo{0}, hi{0};
};

// A rotation in long double, row-major, local -> world: what polishing an
// ill-conditioned hit moves the ray with (PrismPrimitiveDesc::refine).
using RotationExt = std::array<long double, 9>;

// One object: a primitive plugin, its packed parameter record, and its frame.
// What every intersection test reads comes first (the descriptor, the
// frame's flags and centre, a small record kept inline), so that one test
// of a sphere, box, ring or torus touches one or two adjacent cache lines:
// a scene of 100,000 objects does not fit the cache, and a record of its
// own allocation was a second miss per candidate object.
struct alignas(64) Object {
  static constexpr size_t kInlineRecordBytes = 32;

  const PrismPrimitiveDesc* desc = nullptr;  // plugin->desc(), cached
  bool has_rotation = false;                 // false: rotation is identity, skip the multiply
  bool bounded = false;
  int material = 0;  // index into Scene::materials
  glm::dvec3 center{0, 0, 0};
  uint32_t record_size = 0;  // bytes; inline up to kInlineRecordBytes, else on the heap
  alignas(16) std::array<std::byte, kInlineRecordBytes> record_inline{};
  glm::dmat3 rotation{1.0};  // local -> world
  const PrimitivePlugin* plugin = nullptr;
  std::shared_ptr<const RotationExt> rotation_ext;  // `rotation` before rounding; null when identity
  std::vector<std::byte> record_heap;  // a record larger than kInlineRecordBytes (16-aligned start)
  Box3 world_bounds;  // valid when bounded

  const void* record() const { return record_size <= kInlineRecordBytes ? record_inline.data() : record_heap.data(); }
  // A zeroed record of `size` bytes to pack into.
  void* reset_record(size_t size) {
    record_size = static_cast<uint32_t>(size);
    record_inline.fill(std::byte{0});
    record_heap.assign(size > kInlineRecordBytes ? size : 0, std::byte{0});
    return const_cast<void*>(record());
  }
};

struct Camera {
  glm::dvec3 position{0, 0, 0};
  glm::dvec3 forward{0, 0, -1};
  glm::dvec3 right{1, 0, 0};
  glm::dvec3 up{0, 1, 0};  // true_up
  double fov_y = 60.0;     // degrees
};

struct ImageSettings {
  int width = 640;
  int height = 360;
  int spp = 1;
  int max_depth = 5;
};

struct Background {
  glm::dvec3 color{0, 0, 0};
  std::array<int, 6> cubemap{-1, -1, -1, -1, -1, -1};  // +x -x +y -y +z -z texture indices
  bool has_cubemap() const { return cubemap[0] >= 0; }
};

struct Scene {
  std::filesystem::path source;  // the scene file, for messages
  Camera camera;
  ImageSettings image;
  Background background;
  glm::dvec3 ambient{0, 0, 0};
  glm::dvec3 shadow_ambient{0, 0, 0};
  std::vector<Texture> textures;
  std::vector<Material> materials;  // index 0 is the default material
  std::vector<Light> lights;
  std::vector<Object> objects;
  // The primitive plugins this scene uses (kept alive while the scene lives).
  std::vector<std::shared_ptr<const PrimitivePlugin>> plugins;
  // What the loader found suspicious but valid, each "source: path: what"
  // (no light at all, a colour in 0-255, an object behind the camera).
  std::vector<std::string> warnings;

  std::vector<std::string> plugin_names() const;
  // Bytes of the objects' frames and packed records: what every backend
  // holds for the geometry before any acceleration structure.
  size_t packed_object_bytes() const;
};

}  // namespace prism
