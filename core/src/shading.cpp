#include "shading.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iterator>

#include "prism/phong_bound.hpp"
#include "prism/texture.hpp"

namespace prism {

namespace {

double pow5(double x) { return x * x * x * x * x; }  // by multiplication, as the format fixes

glm::dvec3 reflect_dir(const glm::dvec3& d, const glm::dvec3& n) { return glm::normalize(d - 2.0 * glm::dot(d, n) * n); }

// The format's secondary-ray offset for a hit at P.
double offset_epsilon(const glm::dvec3& p) {
  return 1e-4 * (1.0 + std::max(std::max(std::abs(p.x), std::abs(p.y)), std::abs(p.z)));
}

using Clock = std::chrono::steady_clock;

// Adds the time of its scope to one phase of a profile (nothing without one).
class PhaseScope {
 public:
  PhaseScope(PhaseProfile* profile, Phase phase) : profile_(profile), phase_(phase) {
    if (profile_) start_ = Clock::now();
  }
  ~PhaseScope() {
    if (profile_) profile_->ms[size_t(phase_)] += std::chrono::duration<double, std::milli>(Clock::now() - start_).count();
  }
  PhaseScope(const PhaseScope&) = delete;
  PhaseScope& operator=(const PhaseScope&) = delete;

 private:
  PhaseProfile* profile_;
  Phase phase_;
  Clock::time_point start_;
};

// The time of its scope counted as shading, less the queries inside it
// (which their own PhaseScopes add to their phases).
class ShadingTime {
 public:
  explicit ShadingTime(PhaseProfile* profile)
      : profile_(profile), before_(profile ? profile->ms : std::array<double, kPhases>{}), scope_(profile, kPhaseShading) {}
  ~ShadingTime() {
    if (!profile_) return;
    for (int phase = 0; phase < kPhases; ++phase)
      if (phase != kPhaseShading) profile_->ms[kPhaseShading] -= profile_->ms[size_t(phase)] - before_[size_t(phase)];
  }
  ShadingTime(const ShadingTime&) = delete;
  ShadingTime& operator=(const ShadingTime&) = delete;

 private:
  PhaseProfile* profile_;
  std::array<double, kPhases> before_;
  PhaseScope scope_;
};

}  // namespace

static_assert(std::size(kRayKindNames) == kRayKinds);
static_assert(std::size(kPhaseNames) == kPhases);

const char* ray_kind_name(int kind) { return kRayKindNames[kind]; }

struct Shader::Surface {
  glm::dvec3 position;
  glm::dvec3 outward;  // the surface's outward normal N
  glm::dvec3 n;        // N facing the incoming ray
  bool front;
  double cosi;
  double t;
  glm::dvec3 color;  // c: material colour times texture
  double alpha;      // a
  const Material* material;
  int32_t id;  // the object hit
  double epsilon;
  glm::dvec2 uv;  // the texture coordinates (textured materials only)
  Ray spawn(const glm::dvec3& dir, double side) const { return {position + side * epsilon * n, dir}; }
};

Shader::Shader(const Scene& scene, const ObjectQuery& query, RayCounts& counts, PhaseProfile* profile)
    : scene_(scene),
      query_(query),
      counts_(counts),
      profile_(profile),
      entry_(query.entry()),
      sphere_lights_(lights_with_spheres(scene)),
      camera_sphere_lights_(sphere_lights_),
      last_blocker_(scene.lights.size(), kMissId),
      lanes_(std::make_unique_for_overwrite<LightLanes>()) {  // no zeroing: every lane is written before it is read
  results_.reserve(kSamplesPerFinish);
  terms_.reserve(2 * kSamplesPerFinish);
  // A wave holds at most two rays per sample (a Shade1 ray and the path's next).
  wave_.reserve(2 * kSamplesPerFinish);
  next_wave_.reserve(2 * kSamplesPerFinish);
  // Sized once: a wave's arrays only grow (see fit_wave_arrays).
  wave_hits_.resize(2 * kSamplesPerFinish);
  wave_surfaces_.resize(2 * kSamplesPerFinish);
  wave_locals_.resize(2 * kSamplesPerFinish);
}

Shader::~Shader() = default;

Hit Shader::closest(const Ray& ray, double tmin) const {
  Hit hit = query_.closest(ray, tmin);
  add_light_spheres(hit, ray, tmin, sphere_lights_);
  return hit;
}

// A light sphere some ray from `eye` in the cone meets: its centre within
// the cone's half-angle plus the sphere's angular radius (and a microradian
// for the rounding of both), or the eye inside it.
void Shader::set_camera_cone(const glm::dvec3& eye, const glm::dvec3& axis, double cos_half) {
  camera_sphere_lights_.clear();
  const double half = std::acos(std::clamp(cos_half, -1.0, 1.0));
  for (const uint32_t k : sphere_lights_) {
    const Light& light = scene_.lights[k];
    const glm::dvec3 v = light.position - eye;
    const double d = glm::length(v);
    const bool around_eye = !(d > light.radius * (1 + 1e-9));
    if (around_eye || half >= 1.5 ||
        std::acos(std::clamp(glm::dot(axis, v) / d, -1.0, 1.0)) <= half + std::asin(light.radius / d) + 1e-6)
      camera_sphere_lights_.push_back(k);
  }
}

void Shader::camera_hits(std::span<const Ray> rays, Hit* hits) const {
  PhaseScope scope(profile_, kPhaseCameraRays);
  query_.camera_closest_batch(rays, hits);
  if (camera_sphere_lights_.empty()) return;
  for (size_t j = 0; j < rays.size(); ++j) add_light_spheres(hits[j], rays[j], 0.0, camera_sphere_lights_);
}

void Shader::add_light_spheres(Hit& hit, const Ray& ray, double tmin, std::span<const uint32_t> lights) const {
  if (lights.empty()) return;
  const Hit light = intersect_light_spheres(scene_, lights, ray, tmin, hit.t);
  if (!(light.t < hit.t)) return;  // equal t: the object wins
  hit.t = light.t;
  hit.id = light.id;
}

// Every element is written before it is read, so the arrays never shrink:
// shrunk to each wave and grown back at the next tile's first, they
// value-initialised (zeroed) some 30 KB of surfaces a tile.
void Shader::fit_wave_arrays() {
  if (wave_hits_.size() >= wave_.size()) return;
  wave_hits_.resize(wave_.size());
  wave_surfaces_.resize(wave_.size());
  wave_locals_.resize(wave_.size());
}

void Shader::wave_closest() {
  {
    PhaseScope scope(profile_, kPhaseSecondaryRays);
    query_.closest_leaving_batch(wave_.rays, wave_.leaving.data(), wave_hits_.data());
  }
  for (size_t i = 0; i < wave_.size(); ++i) add_light_spheres(wave_hits_[i], wave_.rays[i], 0.0, sphere_lights_);
}

// The object a ray spawned on the side s.n faces cannot meet again, or
// kMissId: a front-facing hit on a convex object (PRISM_PRIMITIVE_CONVEX).
int32_t Shader::left_behind(const Surface& s) const {
  const bool convex = (scene_.objects[size_t(s.id)].desc->flags & PRISM_PRIMITIVE_CONVEX) != 0;
  return s.front && convex ? s.id : kMissId;
}

void Shader::local_surface_at(const Ray& ray, const Hit& hit, LocalSurface& local) const {
  const Object& object = scene_.objects[size_t(hit.id)];
  const bool textured = scene_.materials[size_t(object.material)].texture >= 0;
  local_surface(object, ray, hit.prim, entry_, textured, local);
}

void Shader::surface_at(const Ray& ray, const Hit& hit, const LocalSurface& local, Surface& s) const {
  const Object& object = scene_.objects[size_t(hit.id)];
  const Material& material = scene_.materials[size_t(object.material)];
  const SurfacePoint sp = world_surface(object, ray, local);
  s.position = sp.position;
  s.outward = sp.normal;
  s.front = glm::dot(ray.dir, sp.normal) < 0;
  s.n = s.front ? sp.normal : -sp.normal;
  s.cosi = std::clamp(-glm::dot(ray.dir, s.n), 0.0, 1.0);
  s.t = sp.t;
  s.material = &material;
  s.id = hit.id;
  s.color = s.material->color;
  s.alpha = 1.0;
  if (s.material->texture >= 0) s.uv = sp.uv * s.material->uv_scale + s.material->uv_offset;
  s.epsilon = offset_epsilon(s.position);
}

void Shader::apply_texture(Surface& s) const {
  const glm::dvec4 texel = sample_texture(scene_.textures[size_t(s.material->texture)], s.uv);
  s.color *= glm::dvec3(texel);
  s.alpha = texel.a;
}

// The first-hit AOVs of a camera ray that meets light `-2 - hit.id`'s sphere.
void Shader::note_light_sphere(SampleResult& result, const Ray& ray, const Hit& hit) const {
  result.first_t = hit.t;
  result.first_normal = light_sphere_normal(scene_, ray, hit);
  result.first_albedo = scene_.lights[size_t(-2 - hit.id)].color;
}

void Shader::note(uint32_t value) {
  if (!hashing_) return;
  for (int byte = 0; byte < 4; ++byte) {  // FNV-1a, one byte at a time
    hash_ ^= (value >> (8 * byte)) & 0xffu;
    hash_ *= 16777619u;
  }
}

bool Shader::shadowed(size_t light, const Ray& ray, double distance, int32_t self, int32_t key) {
  ++counts_.n[kShadowRay];
  PhaseScope scope(profile_, kPhaseShadowRays);
  // Neighbouring shadow rays toward one light are mostly blocked by the same
  // object: where the query has nothing cheaper than its full search
  // (kUnkeyed), trying that object first skips the search for them. The
  // answer is the same either way (any blocking object will do), and the
  // query need not test that object again. A keyed ray's short candidate
  // list, each behind a bounding-sphere test, is cheaper than the guess:
  // tried for those too, it cost the showcase 1.4 % more instructions.
  KnownClear clear{self, kMissId};
  int32_t& last = last_blocker_[light];
  if (key == ObjectQuery::kUnkeyed && last != kMissId && last != self) {
    if (blocks(scene_.objects[size_t(last)], ray, distance, entry_)) return true;
    clear.tested = last;
  }
  const int32_t blocker = query_.keyed_light_occluder(light, ray, distance, clear, key);
  if (blocker != kMissId) last = blocker;
  return blocker != kMissId;
}

int32_t Shader::local_light(const Surface& s, const glm::dvec3& dir) {
  if (lanes_->full()) light_batch();
  const Material& m = *s.material;
  const LightLanes::Point point{s.position, s.n,          s.position + s.epsilon * s.n,
                                s.color,    dir,          m.diffuse,
                                m.specular, m.shininess, left_behind(s)};
  // Every shadow ray of the point leaves the surface on the side s.n faces
  // (ndl > 0, origin offset along s.n).
  return int32_t(lanes_->add(point, scene_.ambient));
}

// Each shadow ray's answer into a.blocked, ray by ray, each noted in the
// path hash as it is taken.
void Shader::take_shadow_answers_in_order(size_t k, const uint8_t* keyed, const int32_t* blockers) {
  LightLanes::Arrays& a = lanes_->arrays();
  for (size_t j = 0; j < lanes_->size(); ++j) {
    if (!(a.ndl[j] > 0)) continue;
    bool blocked;
    if (keyed[j]) {
      ++counts_.n[kShadowRay];
      blocked = blockers[j] != kMissId;
      if (blocked) last_blocker_[k] = blockers[j];
    } else {
      blocked = shadowed(k, unkeyed_shadow_ray(j), a.distance[j], a.self[j], a.key[j]);
    }
    note(0x80000000u | (uint32_t(k) << 1) | (blocked ? 1u : 0u));
    a.blocked[j] = blocked ? 1.0 : 0.0;
  }
}

// The same answers where no hash records their order: the keyed rays' in
// one loop without branches, then the others' one by one. Only
// last_blocker_, a guess, may end up otherwise than in order (the last
// keyed ray's blocker before the others'), and a guess changes no answer.
void Shader::take_shadow_answers(size_t k, const uint8_t* keyed, const int32_t* blockers) {
  LightLanes::Arrays& a = lanes_->arrays();
  const size_t count = lanes_->size();
  uint64_t cast = 0;
  int32_t last = kMissId;
  bool unkeyed = false;
  for (size_t j = 0; j < count; ++j) {
    const bool blocked = keyed[j] && blockers[j] != kMissId;
    a.blocked[j] = blocked ? 1.0 : 0.0;
    cast += keyed[j];
    last = blocked ? blockers[j] : last;
    unkeyed |= !keyed[j] && a.ndl[j] > 0;
  }
  counts_.n[kShadowRay] += cast;
  if (last != kMissId) last_blocker_[k] = last;
  if (!unkeyed) return;
  for (size_t j = 0; j < count; ++j) {
    if (keyed[j] || !(a.ndl[j] > 0)) continue;
    a.blocked[j] = shadowed(k, unkeyed_shadow_ray(j), a.distance[j], a.self[j], a.key[j]) ? 1.0 : 0.0;
  }
}

Ray Shader::unkeyed_shadow_ray(size_t j) const {
  const LightLanes::Arrays& a = lanes_->arrays();
  return {{a.o[0][j], a.o[1][j], a.o[2][j]}, {a.l[0][j], a.l[1][j], a.l[2][j]}};
}

void Shader::light_batch() {
  LightLanes& lanes = *lanes_;
  LightLanes::Arrays& a = lanes.arrays();
  const size_t count = lanes.size();
  for (size_t k = 0; k < scene_.lights.size(); ++k) {
    lanes.light_terms(scene_.lights[k]);  // l, energy, distance, n.l, diffuse, highlight; blocked and phong 0
    query_.light_keys(k, lanes.shadow_rays(), a.key.data());
    // A light behind the surface (n.l <= 0) adds nothing and needs no shadow
    // ray. The keyed rays are answered together, the others one by one
    // (shadowed() tries their likely blocker first); where the path hash
    // is kept, every answer is taken in the rays' order.
    std::array<uint8_t, LightLanes::kCapacity> keyed;
    for (size_t j = 0; j < count; ++j) keyed[j] = a.ndl[j] > 0 && a.key[j] != ObjectQuery::kUnkeyed;
    std::array<int32_t, LightLanes::kCapacity> blockers;
    {
      PhaseScope scope(profile_, kPhaseShadowRays);
      query_.keyed_light_occluders(k, lanes.shadow_rays(), a.key.data(), a.self.data(), keyed.data(), blockers.data());
    }
    if (hashing_)
      take_shadow_answers_in_order(k, keyed.data(), blockers.data());
    else
      take_shadow_answers(k, keyed.data(), blockers.data());
    // pow(0, shininess >= 1) is 0: only a highlight facing the viewer needs pow.
    for (size_t j = 0; j < count; ++j) {
      const double specular = a.specular[j], highlight = a.highlight[j];
      if (!(a.ndl[j] > 0 && specular > 0 && highlight > 0)) continue;
      const glm::dvec3 diffuse(a.diffuse[0][j], a.diffuse[1][j], a.diffuse[2][j]);
      if (!highlight_vanishes(specular, highlight, a.shininess[j], diffuse))
        a.phong[j] = specular * std::pow(highlight, a.shininess[j]);
    }
    lanes.accumulate(scene_.shadow_ambient);
  }
  for (size_t i = terms_lit_; i < terms_.size(); ++i) {
    Radiance& value = terms_[i].value;
    if (value.point < 0) continue;
    const glm::dvec3 light = lanes.sum(size_t(value.point));
    value.known = value.absorbed ? light * value.known : light;
    value.point = -1;
  }
  terms_lit_ = terms_.size();
  lanes.clear();
}

void Shader::trace_samples(std::span<const Ray> camera_rays, const Hit* camera_hits, const uint8_t* want_path,
                           int max_depth) {
  if (finished_) {
    results_.clear();
    finished_ = false;
  }
  // The samples that want no path hash together, each that does alone.
  size_t begin = 0;
  for (size_t j = 0; j < camera_rays.size(); ++j) {
    if (!want_path[j]) continue;
    if (j > begin) trace_wave(camera_rays.subspan(begin, j - begin), camera_hits + begin, max_depth, false);
    trace_wave(camera_rays.subspan(j, 1), camera_hits + j, max_depth, true);
    begin = j + 1;
  }
  if (begin < camera_rays.size()) trace_wave(camera_rays.subspan(begin), camera_hits + begin, max_depth, false);
}

void Shader::trace_wave(std::span<const Ray> camera_rays, const Hit* camera_hits, int max_depth, bool hashing) {
  // The hash records this sample's shadow rays only: the batch's earlier points go first.
  if (hashing && lanes_->size() > 0) {
    ShadingTime time(profile_);
    light_batch();
  }
  ShadingTime time(profile_);
  hashing_ = hashing;
  hash_ = 2166136261u;
  const uint32_t first = uint32_t(results_.size());
  results_.resize(results_.size() + camera_rays.size());
  wave_.clear();
  for (size_t j = 0; j < camera_rays.size(); ++j)
    wave_.add(camera_rays[j], kMissId, glm::dvec3(1.0), first + uint32_t(j), kCameraRay);
  for (int depth = 1; !wave_.empty(); ++depth) {
    fit_wave_arrays();
    // The wave's queries first, all together, then its shading in order.
    const Hit* hits = camera_hits;
    if (depth > 1) {
      wave_closest();
      hits = wave_hits_.data();
    }
    // Then the surfaces at its hits, each independent of the others, in
    // three loops, each short enough per hit that one hit's long chains
    // (the plugin's square roots and divisions, the normal's, a texel's
    // dependent loads) overlap the next hits' work instead of holding it up:
    // the plugins' answers, then the world-space surfaces, then the textures.
    for (size_t i = 0; i < wave_.size(); ++i)
      if (hits[i].id >= 0) local_surface_at(wave_.rays[i], hits[i], wave_locals_[i]);
    for (size_t i = 0; i < wave_.size(); ++i)
      if (hits[i].id >= 0) surface_at(wave_.rays[i], hits[i], wave_locals_[i], wave_surfaces_[i]);
    for (size_t i = 0; i < wave_.size(); ++i)
      if (hits[i].id >= 0 && wave_surfaces_[i].material->texture >= 0) apply_texture(wave_surfaces_[i]);
    next_wave_.clear();
    for (size_t i = 0; i < wave_.size(); ++i) {
      const PathRay& path = wave_.paths[i];
      ++counts_.n[size_t(path.kind)];
      note(uint32_t(hits[i].id));
      if (path.kind == kShade1Ray)
        shade1_hit(wave_.rays[i], path, hits[i], wave_surfaces_[i]);
      else
        shade_hit(wave_.rays[i], path, hits[i], wave_surfaces_[i], depth, max_depth);
    }
    std::swap(wave_, next_wave_);
  }
  if (hashing) {
    results_[first].path_hash = (hash_ >> 24) ^ (hash_ & 0xffffffu);  // folded to 24 bits: exact in a float
    hashing_ = false;
  }
}

void Shader::shade1_hit(const Ray& ray, const PathRay& path, const Hit& hit, const Surface& s) {
  if (!hit.found()) return add_known_term(path.sample, path.w, background_radiance(scene_, ray.dir));
  if (hit.id < 0) return add_known_term(path.sample, path.w, scene_.lights[size_t(-2 - hit.id)].color);
  const int32_t point = local_light(s, ray.dir);
  if (s.material->dielectric() && !s.front) {
    const glm::dvec3 absorption = glm::exp(-s.material->absorb * s.t);
    return add_point_term(path.sample, path.w, point, &absorption);
  }
  add_point_term(path.sample, path.w, point);
}

void Shader::shade_hit(const Ray& ray, const PathRay& path, const Hit& hit, const Surface& s, int depth,
                       int max_depth) {
  SampleResult& result = results_[path.sample];
  if (depth == 1) result.first_id = hit.id;
  if (!hit.found()) return add_known_term(path.sample, path.w, background_radiance(scene_, ray.dir));
  if (hit.id < 0) {
    if (depth == 1) note_light_sphere(result, ray, hit);
    return add_known_term(path.sample, path.w, scene_.lights[size_t(-2 - hit.id)].color);
  }
  if (depth == 1) {
    result.first_t = s.t;  // polished where ill-conditioned, as `prism trace` reports it
    result.first_normal = s.outward;
    result.first_albedo = s.color;
  }
  const bool last = depth == max_depth;
  glm::dvec3 w = path.w;
  const Material& m = *s.material;
  if (m.dielectric() && !s.front) w *= glm::exp(-m.absorb * s.t);
  if (!m.dielectric()) {
    const double F = m.reflect > 0 ? m.reflect + (1 - m.reflect) * pow5(1 - s.cosi) : 0.0;
    const double weight = s.alpha * (1 - F);
    if (weight > 0) add_point_term(path.sample, w * weight, local_light(s, ray.dir));
    if (last) return;
    if (s.alpha < 1)
      spawn_ray(path, w * (1 - s.alpha), s.spawn(ray.dir, -1), kPassRay, kMissId);
    else if (F > 0)
      spawn_ray(path, w * F, s.spawn(reflect_dir(ray.dir, s.n), +1), kReflectRay, left_behind(s));
    return;
  }
  const double n1 = s.front ? 1.0 : m.ior, n2 = s.front ? m.ior : 1.0, eta = n1 / n2;
  const double dn = glm::dot(s.n, ray.dir);
  const double k = 1 - eta * eta * (1 - dn * dn);
  if (k < 0) {  // total internal reflection: w unchanged
    if (!last) spawn_ray(path, w, s.spawn(reflect_dir(ray.dir, s.n), +1), kReflectRay, left_behind(s));
    return;
  }
  const double r0 = ((n1 - n2) / (n1 + n2)) * ((n1 - n2) / (n1 + n2));
  const double x = n1 <= n2 ? s.cosi : std::sqrt(k);
  const double F = r0 + (1 - r0) * pow5(1 - x);
  // The one-level reflection is traced whatever the depth, as its own ray of the next wave.
  spawn_ray(path, w * F, s.spawn(reflect_dir(ray.dir, s.n), +1), kShade1Ray, left_behind(s));
  if (!last) spawn_ray(path, w * (1 - F), s.spawn(glm::normalize(eta * ray.dir - (eta * dn + std::sqrt(k)) * s.n), -1), kRefractRay, kMissId);
}

std::span<const SampleResult> Shader::finish() {
  if (lanes_->size() > 0) {
    ShadingTime time(profile_);
    light_batch();
  }
  // Each radiance summed term by term, in the order the scalar loop adds them.
  for (const Term& term : terms_) results_[term.sample].radiance += term.coef * term.value.known;
  terms_.clear();
  terms_lit_ = 0;
  finished_ = true;
  return results_;
}

}  // namespace prism
