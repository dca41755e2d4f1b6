// The std430 buffer layouts the generated kernels read, mirrored in C++.
// gpu/scene.glsl declares the same structs; every size and offset
// here is static_asserted, so a change on one side that the other misses
// fails to compile instead of rendering garbage.
#pragma once

#include <cstddef>
#include <cstdint>

namespace prism::gpu {

// Storage-buffer binding points (at most 8: GL's guaranteed minimum of
// shader storage blocks per compute shader).
enum Binding : uint32_t {
  kBindRecords = 0,    // double[]: every object's plugin record
  kBindObjects = 1,    // GpuObject[]: BVH leaf order, then the unbounded objects
  kBindNodes = 2,      // GpuNode[]
  kBindMaterials = 3,  // GpuMaterial[]
  kBindLights = 4,     // GpuLight[]
  kBindTexels = 5,     // vec4[]: every texture's texels, one after another
  kBindFrame = 6,      // GpuFrame, then dvec2 sample offsets[]
  kBindOutput = 7,     // render: ray counters + pixel planes; trace: GpuTraceRay[]
  kBindingCount = 8
};

struct alignas(32) GpuObject {
  double center[4];      // xyz; w unused
  double columns[3][4];  // the columns of R (local -> world), xyz
  uint32_t record;       // index of the record's first double
  uint32_t type;         // index into the kernel's primitive types
  uint32_t material;
  uint32_t rotated;      // 1: apply `columns`
  int32_t id;            // the object id of the scene file
  int32_t pad[3];
};
static_assert(sizeof(GpuObject) == 160 && offsetof(GpuObject, record) == 128 && offsetof(GpuObject, id) == 144);

// Bounds rounded outward to float (traversal tests them in double).
struct GpuNode {
  float lo[3];
  uint32_t first;
  float hi[3];
  uint32_t count;
};
static_assert(sizeof(GpuNode) == 32);

struct GpuMaterial {
  float color[3];
  float diffuse;
  float absorb[3];
  float specular;
  float shininess;
  float reflect;
  float ior;
  float pad;
  float uv_scale[2];
  float uv_offset[2];
  int32_t texture[4];  // texel offset (-1: none), width, height, unused
};
static_assert(sizeof(GpuMaterial) == 80 && offsetof(GpuMaterial, texture) == 64);

struct alignas(32) GpuLight {
  double position[4];  // point: position, w radius; directional: unit direction of travel
  float color[3];
  float intensity;
  float linear;
  float quadratic;
  uint32_t directional;
  uint32_t pad;
};
static_assert(sizeof(GpuLight) == 64 && offsetof(GpuLight, color) == 32);

struct alignas(32) GpuFrame {
  double camera_position[4];
  double camera_forward[4];
  double camera_right[4];
  double camera_up[4];
  double tan_half_fov;
  double aspect;
  double pad0[2];
  float ambient[4];
  float shadow_ambient[4];
  float background[4];
  int32_t size[4];     // width, height, spp, max_depth
  int32_t counts[4];   // objects, bounded objects (the BVH's), lights, nodes
  int32_t flags[4];    // x: aov path wanted, y: trace ray count, z: the normal/path and albedo/depth planes wanted
  int32_t cubemap[6][4];  // per face: texel offset, width, height, unused
  float anchor[4];        // what a float world's positions are relative to (xyz; zero in a double world)
  float pad1[4];
  // followed by dvec2 sample_offsets[spp] (offset 384)
};
static_assert(sizeof(GpuFrame) == 384 && offsetof(GpuFrame, ambient) == 160 && offsetof(GpuFrame, cubemap) == 256 &&
              offsetof(GpuFrame, anchor) == 352);

// Render output: the ray counters come first (one per ray kind), then the
// tile's pixels as planes of float4, each plane as long as the tile: rgb and
// id; then, only when the frame asks for them (flags.z), normal and path, and
// albedo and depth. A frame without those AOVs reads back 16 bytes a pixel.
constexpr size_t kRayCounterCount = 8;
constexpr size_t kOutputHeaderBytes = 32;
constexpr size_t kPixelPlaneBytes = 16;
constexpr int kMaxOutputPlanes = 3;

struct alignas(32) GpuTraceRay {
  double origin_tmin[4];  // in: origin, tmin
  double dir[4];          // in: unit direction
  double t_normal[4];     // out: t, normal
  int32_t id[4];          // out: x id
  int32_t pad[4];
};
static_assert(sizeof(GpuTraceRay) == 128);

// The float world's versions (PRISM_WORLD_FLOAT: gpu/scene.glsl) of the
// structs that hold world positions or t: every position relative to the
// scene's anchor, subtracted in double before the rounding to float.
struct alignas(16) GpuObjectF {
  float center[4];
  float columns[3][4];
  uint32_t record;  // index of the record's first float
  uint32_t type;
  uint32_t material;
  uint32_t rotated;
  int32_t id;
  int32_t pad[3];
};
static_assert(sizeof(GpuObjectF) == 96 && offsetof(GpuObjectF, record) == 64 && offsetof(GpuObjectF, id) == 80);

struct alignas(16) GpuLightF {
  float position[4];  // point: position, w radius; directional: unit direction of travel
  float color[3];
  float intensity;
  float linear;
  float quadratic;
  uint32_t directional;
  uint32_t pad;
};
static_assert(sizeof(GpuLightF) == 48 && offsetof(GpuLightF, color) == 16);

struct alignas(16) GpuFrameF {
  float camera_position[4];
  float camera_forward[4];
  float camera_right[4];
  float camera_up[4];
  float tan_half_fov;
  float aspect;
  float pad0[2];
  float ambient[4];
  float shadow_ambient[4];
  float background[4];
  int32_t size[4];
  int32_t counts[4];
  int32_t flags[4];
  int32_t cubemap[6][4];
  float anchor[4];
  float pad1[4];
  // followed by vec2 sample_offsets[spp] (offset 304)
};
static_assert(sizeof(GpuFrameF) == 304 && offsetof(GpuFrameF, ambient) == 80 && offsetof(GpuFrameF, cubemap) == 176 &&
              offsetof(GpuFrameF, anchor) == 272);

struct alignas(16) GpuTraceRayF {
  float origin_tmin[4];
  float dir[4];
  float t_normal[4];
  int32_t id[4];
  int32_t pad[4];
};
static_assert(sizeof(GpuTraceRayF) == 80);

}  // namespace prism::gpu
