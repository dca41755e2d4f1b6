// Prism GPU kernels, part 2 of 3: the scene format's Whitted shading, the
// one GLSL copy shared by the OpenGL and Vulkan backends. It computes what
// core/src/shading.cpp computes, term for term and in the same order (same
// ray kinds, same path hash), one interaction at a time (prism_pass says
// how). Features the scene does not use are compiled out through the
// PRISM_FEATURE_* macros the generator sets.
//
// Geometry (points, normals, directions, t) is in world precision
// (gpu/scene.glsl); colours are float. pow/exp have no double versions in
// GLSL; their float results are far inside an 8-bit pixel.

const int PRISM_RAY_CAMERA = 0;
const int PRISM_RAY_SHADOW = 1;
const int PRISM_RAY_REFLECT = 2;
const int PRISM_RAY_REFRACT = 3;
const int PRISM_RAY_ALPHA = 4;
const int PRISM_RAY_SHADE1 = 5;
const int PRISM_RAY_KINDS = 6;

uint prism_ray_counts[PRISM_RAY_KINDS];

// One more ray of `kind`: every counter is added to, at a fixed index (an
// index that differs from lane to lane would be written lane by lane).
void prism_count_ray(int kind) {
  for (int k = 0; k < PRISM_RAY_KINDS; ++k) prism_ray_counts[k] += kind == k ? 1u : 0u;
}
bool prism_hashing;
uint prism_hash;

// A sample's path hash starts afresh; only sample 0's is the path AOV.
void prism_start_sample(int k) {
  prism_hashing = k == 0 && prism_frame.flags.x != 0;
  prism_hash = 2166136261u;
}

void prism_note(uint value) {
  if (!prism_hashing) return;
  for (int byte = 0; byte < 4; ++byte) {  // FNV-1a, one byte at a time
    prism_hash ^= (value >> (8 * byte)) & 0xffu;
    prism_hash *= 16777619u;
  }
}

wreal prism_pow5(wreal x) { return x * x * x * x * x; }  // by multiplication, as the format fixes

wvec3 prism_reflect(wvec3 d, wvec3 n) { return normalize(d - WL(2.0) * dot(d, n) * n); }

// Euclidean modulo of an integer-valued wreal, exact below 2^53.
int prism_wrap(wreal i, int n) { return int(i - wreal(n) * floor(i / wreal(n))); }

#if defined(PRISM_FEATURE_TEXTURES) || defined(PRISM_FEATURE_SKYBOX)
vec4 prism_texel(ivec4 tex, int x, int y) {
#ifdef PRISM_TEXEL_SAMPLER
  return texelFetch(prism_texel_sampler, tex.x + y * tex.y + x);  // RGBA32F: the stored floats, unfiltered
#else
  return prism_texels[tex.x + y * tex.y + x];
#endif
}

// Bilinear blend at texel coordinates (x, y): repeat wrap, or clamp to the
// edge texels (cube-map faces).
vec4 prism_bilinear(ivec4 tex, wreal x, wreal y, bool clamp_to_edge) {
  wreal fx0 = floor(x), fy0 = floor(y);
  float fx = float(x - fx0), fy = float(y - fy0);
  int xa, xb, ya, yb;
  if (clamp_to_edge) {
    xa = int(clamp(fx0, WL(0.0), wreal(tex.y - 1)));
    xb = int(clamp(fx0 + WL(1.0), WL(0.0), wreal(tex.y - 1)));
    ya = int(clamp(fy0, WL(0.0), wreal(tex.z - 1)));
    yb = int(clamp(fy0 + WL(1.0), WL(0.0), wreal(tex.z - 1)));
  } else {
    xa = prism_wrap(fx0, tex.y);
    xb = prism_wrap(fx0 + WL(1.0), tex.y);
    ya = prism_wrap(fy0, tex.z);
    yb = prism_wrap(fy0 + WL(1.0), tex.z);
  }
  vec4 top = prism_texel(tex, xa, ya) * (1.0 - fx) + prism_texel(tex, xb, ya) * fx;
  vec4 bottom = prism_texel(tex, xa, yb) * (1.0 - fx) + prism_texel(tex, xb, yb) * fx;
  return top * (1.0 - fy) + bottom * fy;
}
#endif

#ifdef PRISM_FEATURE_TEXTURES
vec4 prism_sample_texture(ivec4 tex, wvec2 uv) {
  return prism_bilinear(tex, uv.x * wreal(tex.y) - WL(0.5), uv.y * wreal(tex.z) - WL(0.5), false);
}
#endif

// Background radiance for a miss along d: colour, or the cube map with the
// OpenGL face table, sampled in code (no hardware seamless filtering).
vec3 prism_background(wvec3 d) {
#ifdef PRISM_FEATURE_SKYBOX
  // Every feature test is also made at run time, so a kernel with features
  // forced in renders any scene exactly as the specialised one does.
  if (prism_frame.cubemap[0].x < 0) return prism_frame.background.rgb;
  wreal ax = abs(d.x), ay = abs(d.y), az = abs(d.z);
  int face;
  wreal sc, tc, ma;
  if (ax >= ay && ax >= az) {
    face = d.x >= WL(0.0) ? 0 : 1;
    sc = d.x >= WL(0.0) ? -d.z : d.z;
    tc = -d.y;
    ma = d.x;
  } else if (ay >= az) {
    face = d.y >= WL(0.0) ? 2 : 3;
    sc = d.x;
    tc = d.y >= WL(0.0) ? d.z : -d.z;
    ma = d.y;
  } else {
    face = d.z >= WL(0.0) ? 4 : 5;
    sc = d.z >= WL(0.0) ? d.x : -d.x;
    tc = -d.y;
    ma = d.z;
  }
  wreal m = abs(ma);
  wreal s = (sc / m + WL(1.0)) * WL(0.5), t = (tc / m + WL(1.0)) * WL(0.5);
  ivec4 tex = prism_frame.cubemap[face];
  return prism_bilinear(tex, s * wreal(tex.y) - WL(0.5), t * wreal(tex.z) - WL(0.5), true).rgb;
#else
  return prism_frame.background.rgb;
#endif
}

// What shading needs at one hit.
struct PrismShadingPoint {
  wvec3 position;
  wvec3 n;  // facing the incoming ray
  bool front;
  wreal cosi;
  wreal t;
  vec3 color;   // c
  float alpha;  // a
  uint material;
  wreal epsilon;
};

PrismWorldRay prism_spawn(PrismShadingPoint s, wvec3 dir, wreal side) {
  PrismWorldRay r;
  r.origin = s.position + side * s.epsilon * s.n;
  r.dir = dir;
  return r;
}

PrismShadingPoint prism_shading_point(PrismWorldRay ray, PrismClosest hit) {
  PrismWorldSurface sp = prism_world_surface(ray, hit);
  PrismShadingPoint s;
  s.position = sp.point;
  s.front = dot(ray.dir, sp.normal) < WL(0.0);
  s.n = s.front ? sp.normal : -sp.normal;
  s.cosi = clamp(-dot(ray.dir, s.n), WL(0.0), WL(1.0));
  s.t = hit.t;
  s.material = prism_hit_material(hit);
  s.color = prism_materials[s.material].color_diffuse.rgb;
  s.alpha = 1.0;
#ifdef PRISM_FEATURE_TEXTURES
  ivec4 tex = prism_materials[s.material].texture;
  if (tex.x >= 0) {
    vec4 uvt = prism_materials[s.material].uv;
    vec4 texel = prism_sample_texture(tex, sp.uv * wvec2(uvt.xy) + wvec2(uvt.zw));
    s.color *= texel.rgb;
    s.alpha = texel.a;
  }
#endif
  wvec3 p = abs(s.position + wvec3(prism_frame.anchor.xyz));  // the world point, for the format's offset
  s.epsilon = PRISM_OFFSET_SCALE * (WL(1.0) + max(p.x, max(p.y, p.z)));
  return s;
}

bool prism_shadowed(wvec3 origin, wvec3 to_light, wreal distance) {
  prism_count_ray(PRISM_RAY_SHADOW);
  PrismWorldRay r;
  r.origin = origin;
  r.dir = to_light;
  return prism_occluded(r, distance);
}

// Step 4 of the format: ambient plus every light that faces the surface.
vec3 prism_local_light(PrismShadingPoint s, wvec3 dir) {
  vec3 sum = prism_frame.ambient.rgb * s.color;
#if defined(PRISM_FEATURE_POINT_LIGHTS) || defined(PRISM_FEATURE_DIRECTIONAL_LIGHTS)
  PrismMaterial m = prism_materials[s.material];
  wvec3 origin = s.position + s.epsilon * s.n;
  for (int k = 0; k < PRISM_LIGHT_COUNT; ++k) {
    PrismLight light = prism_light(k);
    vec3 energy = light.color_intensity.rgb * light.color_intensity.a;
    wvec3 l;
    wreal distance = prism_winf();
    if (light.directional == 0u) {
      wvec3 to = light.position.xyz - s.position;
      wreal d = length(to);
      l = to / d;
      energy /= float(WL(1.0) + wreal(light.attenuation.x) * d + wreal(light.attenuation.y) * d * d);
      distance = length(light.position.xyz - origin);
    } else {
      l = -light.position.xyz;
    }
    wreal ndl = dot(s.n, l);
    if (!(ndl > WL(0.0))) continue;  // behind the surface: adds nothing, needs no shadow ray
    bool blocked = prism_shadowed(origin, l, distance);
    prism_note(0x80000000u | (uint(k) << 1) | (blocked ? 1u : 0u));
    vec3 visibility = blocked ? prism_frame.shadow_ambient.rgb : vec3(1.0);
    float phong = 0.0;
#ifdef PRISM_FEATURE_SPECULAR
    if (m.absorb_specular.w > 0.0) {
      wvec3 r = -l - WL(2.0) * dot(-l, s.n) * s.n;
      phong = m.absorb_specular.w * pow(float(max(WL(0.0), dot(r, -dir))), m.params.x);
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
  wreal first_t;
  wvec3 first_normal;
  vec3 first_albedo;
};

// A sample's path between two interactions: what prism_pass carries from
// one to the next.
struct PrismPathState {
  vec3 w;
  vec3 radiance;
  PrismWorldRay ray;
  int kind;
  int depth;
  bool shade1;  // the ray is a dielectric's reflected ray (Shade1 of the format)
  vec3 shade1_w;
  vec3 after_w;
  PrismWorldRay after;  // the dielectric's refracted ray, waiting for the Shade1 ray
  PrismSample result;
};

PrismPathState prism_start_path(PrismWorldRay camera_ray) {
  PrismPathState st;
  st.w = vec3(1.0);
  st.radiance = vec3(0.0);
  st.ray = camera_ray;
  st.kind = PRISM_RAY_CAMERA;
  st.depth = 1;
  st.shade1 = false;
  st.shade1_w = vec3(0.0);
  st.after_w = vec3(0.0);
  st.after = camera_ray;
  st.result.first_id = PRISM_MISS_ID;
  st.result.first_t = prism_winf();
  st.result.first_normal = wvec3(WL(0.0));
  st.result.first_albedo = vec3(0.0);
  st.result.radiance = vec3(0.0);
  st.result.path_hash = 0u;
  return st;
}

// Sends the path on along `ray` (of `kind`, one interaction deeper unless a
// Shade1 ray): false when that is past max_depth, where the path ends.
bool prism_next(inout PrismPathState st, PrismWorldRay ray, int kind, int deeper) {
  st.ray = ray;
  st.kind = kind;
  st.depth += deeper;
  return st.depth <= prism_frame.size.w;
}

// One interaction of the format's loop: the closest hit of the path's ray
// and what it adds; true while the path goes on. A dielectric hit sends its
// reflected ray first, marked `shade1` (Shade1 of the format: its first
// hit's local light only, weight w F); the refracted ray waits in `after`
// (weight w (1 - F)) and carries on from the same depth once the Shade1 ray
// is done, so sums, notes and counts happen in the format's order.
bool prism_pass(inout PrismPathState st) {
  prism_count_ray(st.kind);
  PrismClosest hit = prism_closest(st.ray, WL(0.0));
  bool first = st.depth == 1 && !st.shade1;
  if (first) st.result.first_id = hit.id;
  prism_note(uint(hit.id));
  vec3 value;  // a miss's, a light sphere's or a Shade1 ray's radiance
  if (hit.id == PRISM_MISS_ID) {
    value = prism_background(st.ray.dir);
  } else if (hit.id < 0) {
    PrismLight sphere_light = prism_light(-2 - hit.id);
    value = sphere_light.color_intensity.rgb;
    if (first) {
      st.result.first_t = hit.t;
      st.result.first_normal = normalize(st.ray.origin + hit.t * st.ray.dir - sphere_light.position.xyz);
      st.result.first_albedo = value;
    }
  } else {
    PrismShadingPoint s = prism_shading_point(st.ray, hit);
    if (first) {
      st.result.first_t = hit.t;
      st.result.first_normal = s.front ? s.n : -s.n;
      st.result.first_albedo = s.color;
    }
    PrismMaterial m = prism_materials[s.material];
    bool dielectric = m.params.z >= 1.0;
    vec3 absorbed = vec3(1.0);  // times 1.0 is exact: multiplying by it changes nothing
#ifdef PRISM_FEATURE_ABSORPTION
    if (dielectric && !s.front) absorbed = exp(-m.absorb_specular.rgb * float(hit.t));
#endif
    wreal F = WL(0.0);
    float weight = 0.0;
    if (!dielectric && !st.shade1) {
      wreal r = wreal(m.params.y);
      F = r > WL(0.0) ? r + (WL(1.0) - r) * prism_pow5(WL(1.0) - s.cosi) : WL(0.0);
      weight = s.alpha * float(WL(1.0) - F);
    }
    vec3 light = vec3(0.0);
    if (st.shade1 || weight > 0.0) light = prism_local_light(s, st.ray.dir);
    if (!st.shade1) {
      st.w *= absorbed;
      if (!dielectric) {
        if (weight > 0.0) st.radiance += st.w * weight * light;
#ifdef PRISM_FEATURE_ALPHA
        if (s.alpha < 1.0) {
          st.w *= 1.0 - s.alpha;
          return prism_next(st, prism_spawn(s, st.ray.dir, -WL(1.0)), PRISM_RAY_ALPHA, 1);
        }
#endif
#ifdef PRISM_FEATURE_REFLECTION
        if (F > WL(0.0)) {
          st.w *= float(F);
          return prism_next(st, prism_spawn(s, prism_reflect(st.ray.dir, s.n), WL(1.0)), PRISM_RAY_REFLECT, 1);
        }
#endif
        return false;
      }
#ifdef PRISM_FEATURE_DIELECTRICS
      wreal ior = wreal(m.params.z);
      wreal n1 = s.front ? WL(1.0) : ior, n2 = s.front ? ior : WL(1.0), eta = n1 / n2;
      wreal dn = dot(s.n, st.ray.dir);
      wreal k = WL(1.0) - eta * eta * (WL(1.0) - dn * dn);
      PrismWorldRay reflected = prism_spawn(s, prism_reflect(st.ray.dir, s.n), WL(1.0));
      if (k < WL(0.0)) return prism_next(st, reflected, PRISM_RAY_REFLECT, 1);  // total internal reflection: w unchanged
      wreal r0 = ((n1 - n2) / (n1 + n2)) * ((n1 - n2) / (n1 + n2));
      wreal x = n1 <= n2 ? s.cosi : sqrt(k);
      wreal Fd = r0 + (WL(1.0) - r0) * prism_pow5(WL(1.0) - x);
      st.shade1_w = st.w * float(Fd);
      st.after_w = st.w * float(WL(1.0) - Fd);
      st.after = prism_spawn(s, normalize(eta * st.ray.dir - (eta * dn + sqrt(k)) * s.n), -WL(1.0));
      st.shade1 = true;
      return prism_next(st, reflected, PRISM_RAY_SHADE1, 0);
#else
      return prism_next(st, st.ray, st.kind, 1);
#endif
    }
    value = light * absorbed;
  }
  if (!st.shade1) {
    st.radiance += st.w * value;
    return false;
  }
  st.radiance += st.shade1_w * value;  // the Shade1 ray is done: on along the refracted ray
  st.w = st.after_w;
  st.shade1 = false;
  return prism_next(st, st.after, PRISM_RAY_REFRACT, 1);
}
