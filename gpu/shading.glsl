// Prism GPU kernels, part 2 of 3: the scene format's Whitted shading, the
// one GLSL copy shared by the OpenGL and Vulkan backends. It computes what
// core/src/shading.cpp computes, term for term and in the same order (same
// ray kinds, same path hash), as one loop per sample (prism_trace_sample
// says why). Features the scene does not use
// are compiled out through the PRISM_FEATURE_* macros the generator sets.
//
// Geometry (points, normals, directions, t) is double; colours are float.
// pow/exp have no double versions in GLSL; their float results are far
// inside an 8-bit pixel.

const int PRISM_RAY_CAMERA = 0;
const int PRISM_RAY_SHADOW = 1;
const int PRISM_RAY_REFLECT = 2;
const int PRISM_RAY_REFRACT = 3;
const int PRISM_RAY_ALPHA = 4;
const int PRISM_RAY_SHADE1 = 5;
const int PRISM_RAY_KINDS = 6;

uint prism_ray_counts[PRISM_RAY_KINDS];
bool prism_hashing;
uint prism_hash;

void prism_note(uint value) {
  if (!prism_hashing) return;
  for (int byte = 0; byte < 4; ++byte) {  // FNV-1a, one byte at a time
    prism_hash ^= (value >> (8 * byte)) & 0xffu;
    prism_hash *= 16777619u;
  }
}

double prism_pow5(double x) { return x * x * x * x * x; }  // by multiplication, as the format fixes

dvec3 prism_reflect(dvec3 d, dvec3 n) { return normalize(d - 2.0LF * dot(d, n) * n); }

// Euclidean modulo of an integer-valued double, exact below 2^53.
int prism_wrap(double i, int n) { return int(i - double(n) * floor(i / double(n))); }

#if defined(PRISM_FEATURE_TEXTURES) || defined(PRISM_FEATURE_SKYBOX)
vec4 prism_texel(ivec4 tex, int x, int y) { return prism_texels[tex.x + y * tex.y + x]; }

// Bilinear blend at texel coordinates (x, y): repeat wrap, or clamp to the
// edge texels (cube-map faces).
vec4 prism_bilinear(ivec4 tex, double x, double y, bool clamp_to_edge) {
  double fx0 = floor(x), fy0 = floor(y);
  float fx = float(x - fx0), fy = float(y - fy0);
  int xa, xb, ya, yb;
  if (clamp_to_edge) {
    xa = int(clamp(fx0, 0.0LF, double(tex.y - 1)));
    xb = int(clamp(fx0 + 1.0LF, 0.0LF, double(tex.y - 1)));
    ya = int(clamp(fy0, 0.0LF, double(tex.z - 1)));
    yb = int(clamp(fy0 + 1.0LF, 0.0LF, double(tex.z - 1)));
  } else {
    xa = prism_wrap(fx0, tex.y);
    xb = prism_wrap(fx0 + 1.0LF, tex.y);
    ya = prism_wrap(fy0, tex.z);
    yb = prism_wrap(fy0 + 1.0LF, tex.z);
  }
  vec4 top = prism_texel(tex, xa, ya) * (1.0 - fx) + prism_texel(tex, xb, ya) * fx;
  vec4 bottom = prism_texel(tex, xa, yb) * (1.0 - fx) + prism_texel(tex, xb, yb) * fx;
  return top * (1.0 - fy) + bottom * fy;
}
#endif

#ifdef PRISM_FEATURE_TEXTURES
vec4 prism_sample_texture(ivec4 tex, dvec2 uv) {
  return prism_bilinear(tex, uv.x * double(tex.y) - 0.5LF, uv.y * double(tex.z) - 0.5LF, false);
}
#endif

// Background radiance for a miss along d: colour, or the cube map with the
// OpenGL face table, sampled in code (no hardware seamless filtering).
vec3 prism_background(dvec3 d) {
#ifdef PRISM_FEATURE_SKYBOX
  // Every feature test is also made at run time, so a kernel with features
  // forced in renders any scene exactly as the specialised one does.
  if (prism_frame.cubemap[0].x < 0) return prism_frame.background.rgb;
  double ax = abs(d.x), ay = abs(d.y), az = abs(d.z);
  int face;
  double sc, tc, ma;
  if (ax >= ay && ax >= az) {
    face = d.x >= 0.0LF ? 0 : 1;
    sc = d.x >= 0.0LF ? -d.z : d.z;
    tc = -d.y;
    ma = d.x;
  } else if (ay >= az) {
    face = d.y >= 0.0LF ? 2 : 3;
    sc = d.x;
    tc = d.y >= 0.0LF ? d.z : -d.z;
    ma = d.y;
  } else {
    face = d.z >= 0.0LF ? 4 : 5;
    sc = d.z >= 0.0LF ? d.x : -d.x;
    tc = -d.y;
    ma = d.z;
  }
  double m = abs(ma);
  double s = (sc / m + 1.0LF) * 0.5LF, t = (tc / m + 1.0LF) * 0.5LF;
  ivec4 tex = prism_frame.cubemap[face];
  return prism_bilinear(tex, s * double(tex.y) - 0.5LF, t * double(tex.z) - 0.5LF, true).rgb;
#else
  return prism_frame.background.rgb;
#endif
}

// What shading needs at one hit.
struct PrismShadingPoint {
  dvec3 position;
  dvec3 n;  // facing the incoming ray
  bool front;
  double cosi;
  double t;
  vec3 color;   // c
  float alpha;  // a
  uint material;
  double epsilon;
};

PrismWorldRay prism_spawn(PrismShadingPoint s, dvec3 dir, double side) {
  PrismWorldRay r;
  r.origin = s.position + side * s.epsilon * s.n;
  r.dir = dir;
  return r;
}

PrismShadingPoint prism_shading_point(PrismWorldRay ray, PrismClosest hit) {
  PrismWorldSurface sp = prism_world_surface(ray, hit);
  PrismShadingPoint s;
  s.position = sp.point;
  s.front = dot(ray.dir, sp.normal) < 0.0LF;
  s.n = s.front ? sp.normal : -sp.normal;
  s.cosi = clamp(-dot(ray.dir, s.n), 0.0LF, 1.0LF);
  s.t = hit.t;
  s.material = prism_objects[hit.object].info.z;
  s.color = prism_materials[s.material].color_diffuse.rgb;
  s.alpha = 1.0;
#ifdef PRISM_FEATURE_TEXTURES
  ivec4 tex = prism_materials[s.material].texture;
  if (tex.x >= 0) {
    vec4 uvt = prism_materials[s.material].uv;
    vec4 texel = prism_sample_texture(tex, sp.uv * dvec2(uvt.xy) + dvec2(uvt.zw));
    s.color *= texel.rgb;
    s.alpha = texel.a;
  }
#endif
  dvec3 p = abs(s.position);
  s.epsilon = 1e-4LF * (1.0LF + max(p.x, max(p.y, p.z)));
  return s;
}

bool prism_shadowed(dvec3 origin, dvec3 to_light, double distance) {
  ++prism_ray_counts[PRISM_RAY_SHADOW];
  PrismWorldRay r;
  r.origin = origin;
  r.dir = to_light;
  return prism_occluded(r, distance);
}

// Step 4 of the format: ambient plus every light that faces the surface.
vec3 prism_local_light(PrismShadingPoint s, dvec3 dir) {
  vec3 sum = prism_frame.ambient.rgb * s.color;
#if defined(PRISM_FEATURE_POINT_LIGHTS) || defined(PRISM_FEATURE_DIRECTIONAL_LIGHTS)
  PrismMaterial m = prism_materials[s.material];
  dvec3 origin = s.position + s.epsilon * s.n;
  for (int k = 0; k < prism_frame.counts.z; ++k) {
    PrismLight light = prism_lights[k];
    vec3 energy = light.color_intensity.rgb * light.color_intensity.a;
    dvec3 l;
    double distance = prism_inf();
    if (light.directional == 0u) {
      dvec3 to = light.position.xyz - s.position;
      double d = length(to);
      l = to / d;
      energy /= float(1.0LF + double(light.attenuation.x) * d + double(light.attenuation.y) * d * d);
      distance = length(light.position.xyz - origin);
    } else {
      l = -light.position.xyz;
    }
    double ndl = dot(s.n, l);
    if (!(ndl > 0.0LF)) continue;  // behind the surface: adds nothing, needs no shadow ray
    bool blocked = prism_shadowed(origin, l, distance);
    prism_note(0x80000000u | (uint(k) << 1) | (blocked ? 1u : 0u));
    vec3 visibility = blocked ? prism_frame.shadow_ambient.rgb : vec3(1.0);
    float phong = 0.0;
#ifdef PRISM_FEATURE_SPECULAR
    if (m.absorb_specular.w > 0.0) {
      dvec3 r = -l - 2.0LF * dot(-l, s.n) * s.n;
      phong = m.absorb_specular.w * pow(float(max(0.0LF, dot(r, -dir))), m.params.x);
    }
#endif
    sum += energy * visibility * (m.color_diffuse.w * s.color * float(ndl) + phong);
  }
#endif
  return sum;
}

// first_t, first_normal, first_albedo: the first hit's t, outward unit
// normal and colour c (a light sphere's: its colour); +inf, 0, 0 on a miss.
struct PrismSample {
  vec3 radiance;
  int first_id;
  uint path_hash;
  double first_t;
  dvec3 first_normal;
  vec3 first_albedo;
};

// One loop traces a sample's whole path, Shade1 rays included: a GPU
// compiler inlines every call, so each call site of the closest-hit query or
// of the light loop is a copy of every intersector, and this kernel has one
// of each (compile time and code size fall several-fold). A dielectric hit
// sends its reflected ray first, marked `shade1` (Shade1 of the format: its
// first hit's local light only, weight w F); the refracted ray waits in
// `after` (weight w (1 - F)) and carries on from the same depth once the
// Shade1 ray is done, so sums, notes and counts happen in the format's order.
PrismSample prism_trace_sample(PrismWorldRay camera_ray, int max_depth, bool want_path) {
  prism_hashing = want_path;
  prism_hash = 2166136261u;
  PrismSample result;
  result.first_id = PRISM_MISS_ID;
  result.first_t = prism_inf();
  result.first_normal = dvec3(0.0LF);
  result.first_albedo = vec3(0.0);
  vec3 w = vec3(1.0), radiance = vec3(0.0);
  PrismWorldRay ray = camera_ray;
  int kind = PRISM_RAY_CAMERA;
  bool shade1 = false;
  vec3 shade1_w = vec3(0.0), after_w = vec3(0.0);
  PrismWorldRay after = camera_ray;
  int depth = 1;
  while (depth <= max_depth) {
    ++prism_ray_counts[kind];
    PrismClosest hit = prism_closest(ray, 0.0LF);
    bool first = depth == 1 && !shade1;
    if (first) result.first_id = hit.id;
    prism_note(uint(hit.id));
    vec3 value;  // a miss's, a light sphere's or a Shade1 ray's radiance
    if (hit.id == PRISM_MISS_ID) {
      value = prism_background(ray.dir);
    } else if (hit.id < 0) {
      value = prism_lights[-2 - hit.id].color_intensity.rgb;
      if (first) {
        result.first_t = hit.t;
        result.first_normal = normalize(ray.origin + hit.t * ray.dir - prism_lights[-2 - hit.id].position.xyz);
        result.first_albedo = value;
      }
    } else {
      PrismShadingPoint s = prism_shading_point(ray, hit);
      if (first) {
        result.first_t = hit.t;
        result.first_normal = s.front ? s.n : -s.n;
        result.first_albedo = s.color;
      }
      PrismMaterial m = prism_materials[s.material];
      bool dielectric = m.params.z >= 1.0;
      vec3 absorbed = vec3(1.0);  // times 1.0 is exact: multiplying by it changes nothing
#ifdef PRISM_FEATURE_ABSORPTION
      if (dielectric && !s.front) absorbed = exp(-m.absorb_specular.rgb * float(hit.t));
#endif
      double F = 0.0LF;
      float weight = 0.0;
      if (!dielectric && !shade1) {
        double r = double(m.params.y);
        F = r > 0.0LF ? r + (1.0LF - r) * prism_pow5(1.0LF - s.cosi) : 0.0LF;
        weight = s.alpha * float(1.0LF - F);
      }
      vec3 light = vec3(0.0);
      if (shade1 || weight > 0.0) light = prism_local_light(s, ray.dir);
      if (!shade1) {
        w *= absorbed;
        if (!dielectric) {
          if (weight > 0.0) radiance += w * weight * light;
#ifdef PRISM_FEATURE_ALPHA
          if (s.alpha < 1.0) {
            w *= 1.0 - s.alpha;
            ray = prism_spawn(s, ray.dir, -1.0LF);
            kind = PRISM_RAY_ALPHA;
            ++depth;
            continue;
          }
#endif
#ifdef PRISM_FEATURE_REFLECTION
          if (F > 0.0LF) {
            w *= float(F);
            ray = prism_spawn(s, prism_reflect(ray.dir, s.n), 1.0LF);
            kind = PRISM_RAY_REFLECT;
            ++depth;
            continue;
          }
#endif
          break;
        }
#ifdef PRISM_FEATURE_DIELECTRICS
        double ior = double(m.params.z);
        double n1 = s.front ? 1.0LF : ior, n2 = s.front ? ior : 1.0LF, eta = n1 / n2;
        double dn = dot(s.n, ray.dir);
        double k = 1.0LF - eta * eta * (1.0LF - dn * dn);
        PrismWorldRay reflected = prism_spawn(s, prism_reflect(ray.dir, s.n), 1.0LF);
        if (k < 0.0LF) {  // total internal reflection: w unchanged
          ray = reflected;
          kind = PRISM_RAY_REFLECT;
          ++depth;
          continue;
        }
        double r0 = ((n1 - n2) / (n1 + n2)) * ((n1 - n2) / (n1 + n2));
        double x = n1 <= n2 ? s.cosi : sqrt(k);
        double Fd = r0 + (1.0LF - r0) * prism_pow5(1.0LF - x);
        shade1_w = w * float(Fd);
        after_w = w * float(1.0LF - Fd);
        after = prism_spawn(s, normalize(eta * ray.dir - (eta * dn + sqrt(k)) * s.n), -1.0LF);
        ray = reflected;
        kind = PRISM_RAY_SHADE1;
        shade1 = true;
        continue;
#else
        ++depth;
        continue;
#endif
      }
      value = light * absorbed;
    }
    if (!shade1) {
      radiance += w * value;
      break;
    }
    radiance += shade1_w * value;  // the Shade1 ray is done: on along the refracted ray
    ray = after;
    w = after_w;
    kind = PRISM_RAY_REFRACT;
    shade1 = false;
    ++depth;
  }
  result.radiance = radiance;
  result.path_hash = (prism_hash >> 24) ^ (prism_hash & 0xffffffu);  // folded to 24 bits: exact in a float
  return result;
}
