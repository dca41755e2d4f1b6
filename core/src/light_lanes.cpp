#include "prism/light_lanes.hpp"

#include <cmath>
#include <limits>

namespace prism {

namespace {

using Arrays = LightLanes::Arrays;

// Each loop below is the scalar shading's expression for one point, written
// out with glm's order of operations (a dot product is (x + y) + z, a vector
// over a scalar divides each component, a scalar times a vector multiplies
// each); GCC vectorizes the loops (the core's hot sources are built at -O3).

// A point light at `at`: l, energy over its falloff, the shadow ray's length.
[[gnu::always_inline]] inline void point_light(Arrays& a, size_t count, glm::dvec3 at, glm::dvec3 energy,
                                               double linear, double quadratic) {
  for (size_t j = 0; j < count; ++j) {
    const double tx = at.x - a.p[0][j], ty = at.y - a.p[1][j], tz = at.z - a.p[2][j];
    const double d = std::sqrt(tx * tx + ty * ty + tz * tz);
    a.l[0][j] = tx / d;
    a.l[1][j] = ty / d;
    a.l[2][j] = tz / d;
    const double falloff = 1.0 + linear * d + quadratic * d * d;
    a.energy[0][j] = energy.x / falloff;
    a.energy[1][j] = energy.y / falloff;
    a.energy[2][j] = energy.z / falloff;
    const double ux = at.x - a.o[0][j], uy = at.y - a.o[1][j], uz = at.z - a.o[2][j];
    a.distance[j] = std::sqrt(ux * ux + uy * uy + uz * uz);
  }
}

// A directional light: l = -direction everywhere, no falloff, no end.
[[gnu::always_inline]] inline void directional_light(Arrays& a, size_t count, glm::dvec3 l, glm::dvec3 energy) {
  for (size_t j = 0; j < count; ++j) {
    a.l[0][j] = l.x;
    a.l[1][j] = l.y;
    a.l[2][j] = l.z;
    a.energy[0][j] = energy.x;
    a.energy[1][j] = energy.y;
    a.energy[2][j] = energy.z;
    a.distance[j] = std::numeric_limits<double>::infinity();
  }
}

// n.l, the diffuse term and the Phong base, from l.
[[gnu::always_inline]] inline void surface_terms(Arrays& a, size_t count) {
  for (size_t j = 0; j < count; ++j) {
    const double lx = a.l[0][j], ly = a.l[1][j], lz = a.l[2][j];
    const double nx = a.n[0][j], ny = a.n[1][j], nz = a.n[2][j];
    const double ndl = nx * lx + ny * ly + nz * lz;
    a.ndl[j] = ndl;
    a.diffuse[0][j] = a.kd[j] * a.c[0][j] * ndl;
    a.diffuse[1][j] = a.kd[j] * a.c[1][j] * ndl;
    a.diffuse[2][j] = a.kd[j] * a.c[2][j] * ndl;
    // r = -l - 2 (-l . n) n, the highlight r . -dir.
    const double twice = 2.0 * (-lx * nx + -ly * ny + -lz * nz);
    const double rx = -lx - twice * nx, ry = -ly - twice * ny, rz = -lz - twice * nz;
    a.highlight[j] = rx * -a.d[0][j] + ry * -a.d[1][j] + rz * -a.d[2][j];
    a.blocked[j] = 0.0;
    a.phong[j] = 0.0;
  }
}

// sum += energy x visibility x (diffuse + phong) where n.l > 0.
[[gnu::always_inline]] inline void add_channel(Arrays& a, size_t count, int c, double shadow_ambient) {
  const double* energy = a.energy[size_t(c)].data();
  const double* diffuse = a.diffuse[size_t(c)].data();
  double* sum = a.sum[size_t(c)].data();
  for (size_t j = 0; j < count; ++j) {
    const double visibility = a.blocked[j] != 0 ? shadow_ambient : 1.0;
    const double term = energy[j] * visibility * (diffuse[j] + a.phong[j]);
    sum[j] = a.ndl[j] > 0 ? sum[j] + term : sum[j];
  }
}

[[gnu::always_inline]] inline void add_light(Arrays& a, size_t count, glm::dvec3 shadow_ambient) {
  add_channel(a, count, 0, shadow_ambient.x);
  add_channel(a, count, 1, shadow_ambient.y);
  add_channel(a, count, 2, shadow_ambient.z);
}

struct Kernels {
  void (*light)(Arrays&, size_t, const Light&);
  void (*add)(Arrays&, size_t, const glm::dvec3&);
};

[[gnu::always_inline]] inline void light_terms(Arrays& a, size_t count, const Light& light) {
  const glm::dvec3 energy = light.color * light.intensity;
  if (light.type == Light::Type::Point)
    point_light(a, count, light.position, energy, light.linear, light.quadratic);
  else
    directional_light(a, count, -light.direction, energy);
  surface_terms(a, count);
}

void light_terms2(Arrays& a, size_t count, const Light& light) { light_terms(a, count, light); }
void add_light2(Arrays& a, size_t count, const glm::dvec3& shadow_ambient) { add_light(a, count, shadow_ambient); }

#if defined(__x86_64__)
[[gnu::target("avx2")]] void light_terms4(Arrays& a, size_t count, const Light& light) { light_terms(a, count, light); }
[[gnu::target("avx2")]] void add_light4(Arrays& a, size_t count, const glm::dvec3& shadow_ambient) {
  add_light(a, count, shadow_ambient);
}
#endif

// The kernels of `width` lanes (0: the widest the processor runs).
Kernels kernels(int width) {
  static const int widest = LightLanes::widths().back();
#if defined(__x86_64__)
  if ((width == 0 ? widest : width) == 4) return {&light_terms4, &add_light4};
#endif
  (void)width;
  return {&light_terms2, &add_light2};
}

}  // namespace

std::vector<int> LightLanes::widths() {
  std::vector<int> widths = {2};
#if defined(__x86_64__)
  if (__builtin_cpu_supports("avx2")) widths.push_back(4);
#endif
  return widths;
}

size_t LightLanes::add(const Point& p, const glm::dvec3& ambient) {
  const size_t j = size_++;
  for (int c = 0; c < 3; ++c) {
    a_.p[c][j] = p.position[c];
    a_.n[c][j] = p.n[c];
    a_.o[c][j] = p.origin[c];
    a_.c[c][j] = p.color[c];
    a_.d[c][j] = p.dir[c];
    a_.sum[c][j] = ambient[c] * p.color[c];
  }
  a_.kd[j] = p.diffuse;
  a_.specular[j] = p.specular;
  a_.shininess[j] = p.shininess;
  a_.self[j] = p.self;
  return j;
}

void LightLanes::light_terms(const Light& light) { kernels(width_).light(a_, size_, light); }

void LightLanes::accumulate(const glm::dvec3& shadow_ambient) { kernels(width_).add(a_, size_, shadow_ambient); }

}  // namespace prism
