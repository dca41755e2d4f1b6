// Prism GPU kernels, part 1 of 3: the scene buffers (layouts mirrored in
// gpu_layout.hpp) and the closest-hit and occlusion queries over them: a BVH
// over the bounded objects, the unbounded ones (planes, unclipped quadrics)
// tested beside it, and the visible light spheres. Shared unchanged by the
// OpenGL and Vulkan backends; the kernel generator places it after the
// plugins' intersectors and the generated prism_intersect_type /
// prism_surface_type dispatch.
//
// World precision: positions, directions and t are `wreal`: double, or float
// in a float kernel (PRISM_WORLD_FLOAT, which also makes every plugin's
// `real` float), where every position is relative to the scene's anchor (the
// camera), subtracted in double on the host before rounding: a float kernel
// holds no double at all, and runs on a device without shaderFloat64.
#ifdef PRISM_WORLD_FLOAT
#define wreal float
#define wvec2 vec2
#define wvec3 vec3
#define wvec4 vec4
#define WL(x) x
#define PRISM_OFFSET_SCALE 1e-4
#else
#define wreal double
#define wvec2 dvec2
#define wvec3 dvec3
#define wvec4 dvec4
// glslang pastes no tokens onto float literals: the conversion is exact for
// every WL literal (small dyadic numbers); the spec's offset scale is not one.
#define WL(x) double(x)
#define PRISM_OFFSET_SCALE 1e-4LF
#endif

// +infinity in world precision.
wreal prism_winf() {
#ifdef PRISM_WORLD_FLOAT
  return uintBitsToFloat(0x7f800000u);
#else
  return packDouble2x32(uvec2(0u, 0x7ff00000u));
#endif
}

struct PrismObject {
  wvec4 center;
  wvec4 columns[3];  // R, local -> world
  uvec4 info;        // record, type, material, rotated
  ivec4 id;          // x: object id
};
layout(std430, binding = PRISM_BINDING_OBJECTS) readonly buffer PrismObjectBuffer { PrismObject prism_objects[]; };

// Caches. A scene small enough to be unrolled (PRISM_UNROLLED_OBJECTS) has
// its objects and their records, and a scene of a few lights its lights,
// read once at the kernel's start (prism_fill_caches, generated) into these
// copies, which every test then reads at fixed indices: inside a loop
// llvmpipe and lavapipe read a buffer with a bounds check and a branch per
// number even at a fixed offset, several times what the arithmetic of an
// object test costs. The copies are made before the kernel's first branch,
// where every lane is known to run: a copy made under a mask is no longer
// one value for all lanes to the driver's compiler (measured: 1.3x the
// cost of a whole frame).
#ifdef PRISM_UNROLLED_OBJECTS
PrismObject prism_object_cache[PRISM_OBJECT_COUNT];
#define PRISM_OBJECT(i) prism_object_cache[i]
#else
#define PRISM_OBJECT(i) prism_objects[i]
#endif

struct PrismNode {
  vec3 lo;
  uint first;  // inner: left child (the right one follows it); leaf: first object
  vec3 hi;
  uint count;  // 0: inner node
};
layout(std430, binding = PRISM_BINDING_NODES) readonly buffer PrismNodeBuffer { PrismNode prism_nodes[]; };

struct PrismMaterial {
  vec4 color_diffuse;
  vec4 absorb_specular;
  vec4 params;  // shininess, reflect, ior, unused
  vec4 uv;      // uv_scale, uv_offset
  ivec4 texture;  // texel offset (-1: none), width, height
};
// The materials: a uniform block over the same buffer where they fit
// (PRISM_MATERIAL_BLOCK, KernelOptions::material_block; std140 lays the
// struct out as std430 does: five 16-byte members), else the storage buffer.
#ifdef PRISM_MATERIAL_BLOCK
layout(std140, binding = PRISM_BINDING_MATERIAL_BLOCK) uniform PrismMaterialBlock {
  PrismMaterial prism_materials[PRISM_MATERIAL_COUNT];
};
#else
layout(std430, binding = PRISM_BINDING_MATERIALS) readonly buffer PrismMaterialBuffer { PrismMaterial prism_materials[]; };
#endif

struct PrismLight {
  wvec4 position;  // point: position, radius; directional: direction
  vec4 color_intensity;
  vec2 attenuation;  // linear, quadratic
  uint directional;
  uint pad;
};
layout(std430, binding = PRISM_BINDING_LIGHTS) readonly buffer PrismLightBuffer { PrismLight prism_lights[]; };

// Light k (< PRISM_LIGHT_COUNT, which the generator defines): up to
// PRISM_LIGHTS_BY_CONSTANT lights, chosen from the cache by comparisons
// (no lane reads memory), else read lane by lane.
#if PRISM_LIGHT_COUNT > 0 && PRISM_LIGHT_COUNT <= PRISM_LIGHTS_BY_CONSTANT
#define PRISM_CACHED_LIGHTS 1
PrismLight prism_light_cache[PRISM_LIGHT_COUNT];
#endif

PrismLight prism_light(int k) {
#ifdef PRISM_CACHED_LIGHTS
  PrismLight light = prism_light_cache[0];
  for (int j = 1; j < PRISM_LIGHT_COUNT; ++j)
    if (k == j) light = prism_light_cache[j];
  return light;
#else
  return prism_lights[k];
#endif
}

#if defined(PRISM_FEATURE_TEXTURES) || defined(PRISM_FEATURE_SKYBOX)
// The texels: through a buffer texture over the same buffer where the
// backend can (PRISM_TEXEL_SAMPLER, KernelOptions::texel_sampler), else
// the storage buffer.
#ifdef PRISM_TEXEL_SAMPLER
layout(binding = PRISM_BINDING_TEXEL_SAMPLER) uniform samplerBuffer prism_texel_sampler;
#else
layout(std430, binding = PRISM_BINDING_TEXELS) readonly buffer PrismTexelBuffer { vec4 prism_texels[]; };
#endif
#endif

// The frame's constants (gpu_layout.hpp: GpuFrame, GpuFrameF, whose sizes
// are multiples of the struct's std430 alignment, so the sample offsets
// follow at the same offset as in a flat block).
struct PrismFrame {
  wvec4 camera_position;
  wvec4 camera_forward;
  wvec4 camera_right;
  wvec4 camera_up;
  wreal tan_half_fov;
  wreal aspect;
  wreal pad0[2];
  vec4 ambient;
  vec4 shadow_ambient;
  vec4 background;
  ivec4 size;    // width, height, spp, max_depth
  ivec4 counts;  // objects, bounded objects, lights, BVH nodes
  ivec4 flags;   // x: path AOV wanted, y: trace ray count, z: depth/normal/albedo AOVs wanted
  ivec4 cubemap[6];
  vec4 anchor;  // a float world's positions are relative to it (zero in a double world)
  vec4 pad1;
};

layout(std430, binding = PRISM_BINDING_FRAME) readonly buffer PrismFrameBuffer {
  PrismFrame constants;
  wvec2 sample_offsets[];
} prism_frame_buffer;

// The constants copied from the buffer once at the kernel's start
// (prism_copy_frame, called first by prism_fill_caches): a CPU driver reads
// a storage buffer with a bounds check and a branch per number, in every
// pass of a loop, where this copy is read like any variable.
PrismFrame prism_frame;

void prism_copy_frame() { prism_frame = prism_frame_buffer.constants; }

const int PRISM_MISS_ID = -1;

// The closest hit so far; `object` indexes prism_objects.
struct PrismClosest {
  wreal t;
  int id;  // object id, -2-k for light k's sphere, -1 for none
  uint object;
  PrismHit hit;
};

PrismClosest prism_no_hit() {
  PrismClosest c;
  c.t = prism_winf();
  c.id = PRISM_MISS_ID;
  c.object = 0u;
  prism_clear_hit(c.hit);
  return c;
}

// The largest wreal below x (x > 0): `t < x` as an inclusive bound.
wreal prism_next_below(wreal x) {
#ifdef PRISM_WORLD_FLOAT
  return uintBitsToFloat(floatBitsToUint(x) - 1u);
#else
  uvec2 bits = unpackDouble2x32(x);
  if (bits.x == 0u) {
    bits.x = 0xffffffffu;
    bits.y -= 1u;
  } else {
    bits.x -= 1u;
  }
  return packDouble2x32(bits);
#endif
}

// A ray in world space (world precision whatever `real` is: the kernel's
// positions and t), and a hit's world point, outward unit normal and uv.
struct PrismWorldRay {
  wvec3 origin;
  wvec3 dir;
};

struct PrismWorldSurface {
  wvec3 point;
  wvec3 normal;
  wvec2 uv;
};

// A world ray in object i's local frame (rotations keep t), as the plugins
// take it: computed in world precision, then rounded to `real` (the plugins
// of a double kernel with --precision float intersect in float after the
// re-centring in double).
PrismRay prism_to_local(uint i, PrismWorldRay ray) {
  wvec3 o = ray.origin - PRISM_OBJECT(i).center.xyz;
  // Always rotated, the identity for an object without rotation (exact: a
  // dot with a unit axis is that component): a branch would cost more on a
  // driver that runs both sides of it than the nine products do.
  wvec3 c0 = PRISM_OBJECT(i).columns[0].xyz, c1 = PRISM_OBJECT(i).columns[1].xyz, c2 = PRISM_OBJECT(i).columns[2].xyz;
  PrismRay local;
  local.origin = real3(wvec3(dot(c0, o), dot(c1, o), dot(c2, o)));
  local.dir = real3(wvec3(dot(c0, ray.dir), dot(c1, ray.dir), dot(c2, ray.dir)));
  return local;
}

// A world surface from a local one already turned to world axes: the point
// moved to object i's centre, the normal made unit (-dir where undefined).
PrismWorldSurface prism_placed_surface(uint i, PrismWorldRay ray, wvec3 turned_point, wvec3 turned_normal, wvec2 uv) {
  PrismWorldSurface s;
  s.uv = uv;
  s.point = PRISM_OBJECT(i).center.xyz + turned_point;
  wreal len = length(turned_normal);
  s.normal = (len > WL(0.0) && !isinf(len) && !isnan(len)) ? turned_normal / len : -ray.dir;
  return s;
}

// A plugin's local surface on object i in the world: point, outward unit
// normal (-dir where undefined) and uv.
PrismWorldSurface prism_to_world(uint i, PrismWorldRay ray, PrismSurface local) {
  wvec3 point = wvec3(local.point), normal = wvec3(local.normal);
  wvec3 c0 = PRISM_OBJECT(i).columns[0].xyz, c1 = PRISM_OBJECT(i).columns[1].xyz, c2 = PRISM_OBJECT(i).columns[2].xyz;
  return prism_placed_surface(i, ray, c0 * point.x + c1 * point.y + c2 * point.z,
                              c0 * normal.x + c1 * normal.y + c2 * normal.z, wvec2(local.uv));
}

// The same two for an object without rotation, which an unrolled kernel
// knows from its source (the generator writes these calls for it): no
// multiply by the identity, as the CPU's to_local skips it, and so the same
// numbers (the identity's products would also turn -0 into +0). Nine
// products and six sums fewer per object test, and per surface.
PrismRay prism_to_local_unrotated(uint i, PrismWorldRay ray) {
  PrismRay local;
  local.origin = real3(ray.origin - PRISM_OBJECT(i).center.xyz);
  local.dir = real3(ray.dir);
  return local;
}

PrismWorldSurface prism_to_world_unrotated(uint i, PrismWorldRay ray, PrismSurface local) {
  return prism_placed_surface(i, ray, wvec3(local.point), wvec3(local.normal), wvec2(local.uv));
}

// A world ray in object i's local frame is tested by one call of the
// generated type dispatch: a GPU compiler inlines every call, so each call
// site of prism_intersect_type is a copy of every intersector in the kernel.
// prism_traverse therefore has exactly one, for closest and any hit alike.

// 1/d with zero components replaced by a huge finite value, so the slab test
// never forms 0 * inf.
wvec3 prism_inverse_dir(wvec3 d) {
#ifdef PRISM_WORLD_FLOAT
  const float huge = 1e30;
#else
  const double huge = 1e300LF;
#endif
  return wvec3(d.x != WL(0.0) ? WL(1.0) / d.x : huge, d.y != WL(0.0) ? WL(1.0) / d.y : huge,
               d.z != WL(0.0) ? WL(1.0) / d.z : huge);
}

// Slab test in world precision against a float box; tfar is widened by a
// few ulps so rounding never drops a hit on the box's face.
bool prism_enter_node(uint node, wvec3 o, wvec3 inv, wreal tmin, wreal tmax, out wreal tnear) {
  wvec3 t0 = (wvec3(prism_nodes[node].lo) - o) * inv;
  wvec3 t1 = (wvec3(prism_nodes[node].hi) - o) * inv;
  wvec3 near3 = min(t0, t1), far3 = max(t0, t1);
  tnear = max(max(near3.x, near3.y), max(near3.z, tmin));
#ifdef PRISM_WORLD_FLOAT
  wreal tfar = min(min(far3.x, far3.y), min(far3.z, tmax)) * 1.0000005;
#else
  wreal tfar = min(min(far3.x, far3.y), min(far3.z, tmax)) * 1.0000000000000009LF;
#endif
  return tnear <= tfar;
}

#define PRISM_BVH_STACK 64

// A hit `h` on object `id` (in slot `slot`) that an intersector found: into
// `best` when it is the closest so far (ties: the format's rule, lower
// object id at equal t); true for an any-hit query, which stops there.
bool prism_take_hit(bool any_hit, int id, uint slot, PrismHit h, inout PrismClosest best) {
  if (any_hit) return true;
  if (wreal(h.t) < best.t || id < best.id) {
    best.t = wreal(h.t);
    best.id = id;
    best.object = slot;
    best.hit = h;
  }
  return false;
}

#ifdef PRISM_UNROLLED_OBJECTS

// Every object in turn, each with its slot and record as constants (the
// generator writes it after this file): a driver that runs every lane
// through the same code reads the objects' data at fixed offsets, once for
// all lanes, instead of gathering it lane by lane (docs/architecture.md,
// "Objects unrolled").
bool prism_test_every_object(PrismWorldRay ray, wreal tmin, wreal tmax, bool any_hit, inout PrismClosest best);

bool prism_traverse(PrismWorldRay ray, wreal tmin, wreal tmax, bool any_hit, inout PrismClosest best) {
  return prism_test_every_object(ray, tmin, tmax, any_hit, best);
}

#else

// Tests objects first .. first + count - 1: the closest hit with t > tmin
// into `best`, or, when `any_hit`, true as soon as one lies at tmin < t <= tmax.
bool prism_test_objects(uint first, uint count, PrismWorldRay ray, wreal tmin, wreal tmax, bool any_hit,
                        inout PrismClosest best) {
  for (uint i = first; i < first + count; ++i) {
    PrismHit h;
    uvec4 info = prism_objects[i].info;
    if (prism_intersect_type(info.y, info.x, prism_to_local(i, ray), real(tmin), real(any_hit ? tmax : best.t), h) &&
        prism_take_hit(any_hit, prism_objects[i].id.x, i, h, best))
      return true;
  }
  return false;
}

// Closest object hit or any hit (see prism_test_objects): the leaves a BVH
// walk reaches, nearest child first, then the unbounded objects (planes,
// unclipped quadrics).
bool prism_traverse(PrismWorldRay ray, wreal tmin, wreal tmax, bool any_hit, inout PrismClosest best) {
  wvec3 inv = prism_inverse_dir(ray.dir);
  uint stack[PRISM_BVH_STACK];
  int top = 0;
  uint node = 0u;
  wreal tnear;
  bool visit = prism_frame.counts.w > 0 && prism_enter_node(0u, ray.origin, inv, tmin, any_hit ? tmax : best.t, tnear);
  bool unbounded_done = false;
  for (;;) {
    // The next run of objects: a leaf the walk reaches, else the unbounded ones once.
    uint first = 0u, count = 0u;
    while (visit || top > 0) {
      if (!visit) {
        node = stack[--top];
        visit = true;
      }
      uint node_count = prism_nodes[node].count, node_first = prism_nodes[node].first;
      if (node_count > 0u) {
        first = node_first;
        count = node_count;
        visit = false;
        break;
      }
      wreal limit = any_hit ? tmax : best.t, tl, tr;
      bool left = prism_enter_node(node_first, ray.origin, inv, tmin, limit, tl);
      bool right = prism_enter_node(node_first + 1u, ray.origin, inv, tmin, limit, tr);
      if (left && right) {
        bool left_first = tl <= tr;
        stack[top++] = left_first ? node_first + 1u : node_first;
        node = left_first ? node_first : node_first + 1u;
      } else if (left || right) {
        node = left ? node_first : node_first + 1u;
      } else {
        visit = false;
      }
    }
    if (count == 0u) {
      if (unbounded_done) break;
      unbounded_done = true;
      first = uint(prism_frame.counts.y);
      count = uint(prism_frame.counts.x) - first;
    }
    if (prism_test_objects(first, count, ray, tmin, tmax, any_hit, best)) return true;
  }
  return false;
}

#endif

// Closest hit with t > tmin over objects and visible light spheres; objects
// win ties with light spheres, lower light index wins among lights.
PrismClosest prism_closest(PrismWorldRay ray, wreal tmin) {
  PrismClosest best = prism_no_hit();
  prism_traverse(ray, tmin, WL(0.0), false, best);
#ifdef PRISM_FEATURE_LIGHT_SPHERES
  wreal limit = best.t;
  for (int k = 0; k < PRISM_LIGHT_COUNT; ++k) {
    PrismLight light = prism_light(k);
    wreal radius = light.position.w;
    if (light.directional != 0u || !(radius > WL(0.0))) continue;
    real t;
    if (prism_intersect_sphere(real3(ray.origin - light.position.xyz), real3(ray.dir), real(radius),
                               real(tmin), real(limit), t) &&
        wreal(t) < best.t) {
      best.t = wreal(t);
      best.id = -2 - k;
    }
  }
#endif
  return best;
}

// True when an object lies at 0 < t < tmax (light spheres never block).
bool prism_occluded(PrismWorldRay ray, wreal tmax) {
  PrismClosest unused = prism_no_hit();
  return prism_traverse(ray, WL(0.0), prism_next_below(tmax), true, unused);
}

#ifndef PRISM_UNROLLED_OBJECTS

// World point, outward unit normal (-dir where undefined) and uv of a hit,
// and the material of the object hit. (Unrolled, the generator writes them
// object by object, with constant slots, records and materials.)
PrismWorldSurface prism_world_surface(PrismWorldRay ray, PrismClosest c) {
  PrismSurface local;
  uint i = c.object;
  prism_surface_type(prism_objects[i].info.y, prism_objects[i].info.x, prism_to_local(i, ray), c.hit, local);
  return prism_to_world(i, ray, local);
}

#else

PrismWorldSurface prism_world_surface(PrismWorldRay ray, PrismClosest c);

#endif

// The material of the object hit, read lane by lane (measured: cheaper here
// than choosing among cached materials by comparisons, for a material of
// twenty numbers).
uint prism_hit_material(PrismClosest c) { return prism_objects[c.object].info.z; }
