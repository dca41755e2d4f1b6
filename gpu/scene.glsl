// Prism GPU kernels, part 1 of 3: the scene buffers (layouts mirrored in
// gpu_layout.hpp) and the closest-hit and occlusion queries over them: a BVH
// over the bounded objects, the unbounded ones (planes, unclipped quadrics)
// tested beside it, and the visible light spheres. Shared unchanged by the
// OpenGL and Vulkan backends; the kernel generator places it after the
// plugins' intersectors and the generated prism_intersect_type /
// prism_surface_type dispatch.

struct PrismObject {
  dvec4 center;
  dvec4 columns[3];  // R, local -> world
  uvec4 info;        // record, type, material, rotated
  ivec4 id;          // x: object id
};
layout(std430, binding = PRISM_BINDING_OBJECTS) readonly buffer PrismObjectBuffer { PrismObject prism_objects[]; };

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
layout(std430, binding = PRISM_BINDING_MATERIALS) readonly buffer PrismMaterialBuffer { PrismMaterial prism_materials[]; };

struct PrismLight {
  dvec4 position;  // point: position, radius; directional: direction
  vec4 color_intensity;
  vec2 attenuation;  // linear, quadratic
  uint directional;
  uint pad;
};
layout(std430, binding = PRISM_BINDING_LIGHTS) readonly buffer PrismLightBuffer { PrismLight prism_lights[]; };

#if defined(PRISM_FEATURE_TEXTURES) || defined(PRISM_FEATURE_SKYBOX)
layout(std430, binding = PRISM_BINDING_TEXELS) readonly buffer PrismTexelBuffer { vec4 prism_texels[]; };
#endif

layout(std430, binding = PRISM_BINDING_FRAME) readonly buffer PrismFrameBuffer {
  dvec4 camera_position;
  dvec4 camera_forward;
  dvec4 camera_right;
  dvec4 camera_up;
  double tan_half_fov;
  double aspect;
  double pad0[2];
  vec4 ambient;
  vec4 shadow_ambient;
  vec4 background;
  ivec4 size;    // width, height, spp, max_depth
  ivec4 counts;  // objects, bounded objects, lights, BVH nodes
  ivec4 flags;   // x: path AOV wanted, y: trace ray count, z: depth/normal/albedo AOVs wanted
  ivec4 cubemap[6];
  dvec2 sample_offsets[];
} prism_frame;

const int PRISM_MISS_ID = -1;

// The closest hit so far; `object` indexes prism_objects.
struct PrismClosest {
  double t;
  int id;  // object id, -2-k for light k's sphere, -1 for none
  uint object;
  PrismHit hit;
};

PrismClosest prism_no_hit() {
  PrismClosest c;
  c.t = prism_inf();
  c.id = PRISM_MISS_ID;
  c.object = 0u;
  prism_clear_hit(c.hit);
  return c;
}

// The largest double below x (x > 0): `t < x` as an inclusive bound.
double prism_next_below(double x) {
  uvec2 bits = unpackDouble2x32(x);
  if (bits.x == 0u) {
    bits.x = 0xffffffffu;
    bits.y -= 1u;
  } else {
    bits.x -= 1u;
  }
  return packDouble2x32(bits);
}

// A ray in world space (double whatever `real` is: the kernel's positions
// and t), and a hit's world point, outward unit normal and uv.
struct PrismWorldRay {
  dvec3 origin;
  dvec3 dir;
};

struct PrismWorldSurface {
  dvec3 point;
  dvec3 normal;
  dvec2 uv;
};

// A world ray in object i's local frame (rotations keep t), as the plugins
// take it: computed in double, then rounded to `real` (a float kernel's
// plugins intersect in float after the re-centring in double).
PrismRay prism_to_local(uint i, PrismWorldRay ray) {
  dvec3 o = ray.origin - prism_objects[i].center.xyz;
  PrismRay local;
  if (prism_objects[i].info.w == 0u) {
    local.origin = real3(o);
    local.dir = real3(ray.dir);
    return local;
  }
  dvec3 c0 = prism_objects[i].columns[0].xyz, c1 = prism_objects[i].columns[1].xyz, c2 = prism_objects[i].columns[2].xyz;
  local.origin = real3(dvec3(dot(c0, o), dot(c1, o), dot(c2, o)));
  local.dir = real3(dvec3(dot(c0, ray.dir), dot(c1, ray.dir), dot(c2, ray.dir)));
  return local;
}

// A world ray in object i's local frame is tested by one call of the
// generated type dispatch: a GPU compiler inlines every call, so each call
// site of prism_intersect_type is a copy of every intersector in the kernel.
// prism_traverse therefore has exactly one, for closest and any hit alike.

// 1/d with zero components replaced by a huge finite value, so the slab test
// never forms 0 * inf.
dvec3 prism_inverse_dir(dvec3 d) {
  const double huge = 1e300LF;
  return dvec3(d.x != 0.0LF ? 1.0LF / d.x : huge, d.y != 0.0LF ? 1.0LF / d.y : huge,
               d.z != 0.0LF ? 1.0LF / d.z : huge);
}

// Slab test in double against a float box; tfar is widened by a few ulps so
// rounding never drops a hit on the box's face.
bool prism_enter_node(uint node, dvec3 o, dvec3 inv, double tmin, double tmax, out double tnear) {
  dvec3 t0 = (dvec3(prism_nodes[node].lo) - o) * inv;
  dvec3 t1 = (dvec3(prism_nodes[node].hi) - o) * inv;
  dvec3 near3 = min(t0, t1), far3 = max(t0, t1);
  tnear = max(max(near3.x, near3.y), max(near3.z, tmin));
  double tfar = min(min(far3.x, far3.y), min(far3.z, tmax)) * 1.0000000000000009LF;
  return tnear <= tfar;
}

#define PRISM_BVH_STACK 64

// Tests objects first .. first + count - 1: the closest hit with t > tmin
// into `best` (ties: the format's rule, lower object id at equal t), or, when
// `any_hit`, true as soon as one lies at tmin < t <= tmax.
bool prism_test_objects(uint first, uint count, PrismWorldRay ray, double tmin, double tmax, bool any_hit,
                        inout PrismClosest best) {
  for (uint i = first; i < first + count; ++i) {
    PrismHit h;
    uvec4 info = prism_objects[i].info;
    if (!prism_intersect_type(info.y, info.x, prism_to_local(i, ray), real(tmin), real(any_hit ? tmax : best.t), h))
      continue;
    if (any_hit) return true;
    int id = prism_objects[i].id.x;
    if (double(h.t) < best.t || id < best.id) {
      best.t = double(h.t);
      best.id = id;
      best.object = i;
      best.hit = h;
    }
  }
  return false;
}

// Closest object hit or any hit (see prism_test_objects): the leaves a BVH
// walk reaches, nearest child first, then the unbounded objects (planes,
// unclipped quadrics).
bool prism_traverse(PrismWorldRay ray, double tmin, double tmax, bool any_hit, inout PrismClosest best) {
  dvec3 inv = prism_inverse_dir(ray.dir);
  uint stack[PRISM_BVH_STACK];
  int top = 0;
  uint node = 0u;
  double tnear;
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
      double limit = any_hit ? tmax : best.t, tl, tr;
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

// Closest hit with t > tmin over objects and visible light spheres; objects
// win ties with light spheres, lower light index wins among lights.
PrismClosest prism_closest(PrismWorldRay ray, double tmin) {
  PrismClosest best = prism_no_hit();
  prism_traverse(ray, tmin, 0.0LF, false, best);
#ifdef PRISM_FEATURE_LIGHT_SPHERES
  double limit = best.t;
  for (int k = 0; k < prism_frame.counts.z; ++k) {
    double radius = prism_lights[k].position.w;
    if (prism_lights[k].directional != 0u || !(radius > 0.0LF)) continue;
    real t;
    if (prism_intersect_sphere(real3(ray.origin - prism_lights[k].position.xyz), real3(ray.dir), real(radius),
                               real(tmin), real(limit), t) &&
        double(t) < best.t) {
      best.t = double(t);
      best.id = -2 - k;
    }
  }
#endif
  return best;
}

// True when an object lies at 0 < t < tmax (light spheres never block).
bool prism_occluded(PrismWorldRay ray, double tmax) {
  PrismClosest unused = prism_no_hit();
  return prism_traverse(ray, 0.0LF, prism_next_below(tmax), true, unused);
}

// World point, outward unit normal (-dir where undefined) and uv of a hit.
PrismWorldSurface prism_world_surface(PrismWorldRay ray, PrismClosest c) {
  PrismSurface local;
  uint i = c.object;
  prism_surface_type(prism_objects[i].info.y, prism_objects[i].info.x, prism_to_local(i, ray), c.hit, local);
  dvec3 point = dvec3(local.point), normal = dvec3(local.normal);
  PrismWorldSurface s;
  s.uv = dvec2(local.uv);
  if (prism_objects[i].info.w != 0u) {
    dvec3 c0 = prism_objects[i].columns[0].xyz, c1 = prism_objects[i].columns[1].xyz, c2 = prism_objects[i].columns[2].xyz;
    point = c0 * point.x + c1 * point.y + c2 * point.z;
    normal = c0 * normal.x + c1 * normal.y + c2 * normal.z;
  }
  s.point = prism_objects[i].center.xyz + point;
  double len = length(normal);
  s.normal = (len > 0.0LF && !isinf(len) && !isnan(len)) ? normal / len : -ray.dir;
  return s;
}
