// Double-precision queries through Embree's float32 BVH.
//
// THE FLOAT/DOUBLE SCHEME AND ITS ERROR BOUND
//
// Embree sees only float boxes and a float ray; it decides which bounded
// objects a ray visits. Every visited object is intersected by its plugin in
// double with the original world ray, and hits are compared in double, so
// the result equals a brute-force double loop as long as Embree never skips
// an object whose plugin hit could win. That is what the padding ensures.
//
// Frame. Embree coordinates are world - C, C the centre of a box B that
// holds every BVH object: their union box grown on every side by
// kFrameSlack times its largest extent, room for updates to move objects in
// (embree_update.hpp; nothing below needs B to be tight). An object moved
// out of B needs a new build. S = the largest half extent of B;
// M = the largest |world coordinate| of B. Every object's world box is grown by
//     pad = 4e-6 * S + 2^-40 * M
// in double and rounded outward to float.
//
// Ray. The ray is clipped (in double) to O grown by 2 * pad: [t0, t1], O
// the union of the boxes the BVH holds (O lies in B; updates grow it with
// the boxes they move in). Rays that miss it skip Embree. Its origin is
// moved along the ray to world t = s = max(t0, tmin) (tmin = 0 for
// occlusion), e = (o - C) + s * d, so e lies in B grown by 2 * pad:
// |e| <= S + 2 pad per component. Embree gets
// e_f = fl(e), d_f = fl(d), tnear = 0 and tfar = fl_up(t_limit - s), where
// t_limit = min(best t so far, t1); a callback that finds a better hit
// lowers tfar to fl_up(t_best - s) (rounded up: a tie at t_best, which the
// lower id may still win, stays inside). Embree's tau is world t - s.
//
// Bound. With u = 2^-24, |e_f - e| <= u (S + 2 pad) and |d_f - d| <= u per
// component, and tau never exceeds the diagonal of the grown box,
// 2 sqrt(3) (S + 2 pad). So at equal tau the float ray is within
//     delta = (1 + 2 sqrt 3) u (S + 2 pad) < 4.5 u (S + 2 pad) ~= 2.7e-7 S
// of the double ray, per component. A hit point H = P(tau_h) lies in its
// object's world box (up to the plugin's and the core's double rounding,
// which the 2^-40 M term covers with room to spare), so the float ray stays
// inside the grown float box for tau in [tau_h - r, tau_h + r] with
// r ~= pad - delta. Embree's slab test (lower * rdir - org * rdir, rdir =
// 1/d_f) errs by at most ~6 u (S + 2 pad) / |d_i| per slab bound, far below
// the slab's own margin r / |d_i|. Also 0 <= tau_h <= tfar for every hit
// that could win (t > tmin and t >= t0 + 2 pad; t <= t_best). Hence every
// node on the way to such an object is entered and its callback runs,
// provided pad > delta + 6 u (S + 2 pad), i.e. pad > ~10.6 u S ~= 6.3e-7 S.
// The 4e-6 S used is about 6x that. The double arithmetic that makes e and
// t0 errs by ~4 eps (|o| + |C| + |s|); shift_is_exact_enough() sends the
// rare ray for which that could exceed pad / 64 (an origin some 1e8 S away)
// to the brute-force loop instead.
//
// After an update, rays go through a top-level scene that holds the moved
// objects (their boxes made in this same frame) and an instance of the main
// tree with the identity transform (embree_update.hpp), which Embree
// applies exactly (x * 1 + y * 0 + z * 0 + 0, the same rdir): the float ray
// and its slab tests are the ones above on both levels.
//
// Few objects. With up to BoxFilter::kMaxObjects objects in the BVH a ray
// does not enter Embree: BoxFilter tests it against every BVH object's world
// box grown by the same pad, in double, and the plugins run only for the
// boxes that the ray's part (tmin, t_best] or (0, tmax) enters, nearest box
// first, until a box starts beyond the best hit. The argument above carries
// over with room to spare: the hit point lies in the world box up to the
// 2^-40 M term, and the slab test's rounding, about 2 eps (|box| + |o|) in
// position, is far below pad for every ray shift_is_exact_enough() accepts
// at shift 0. A ray with a zero (or denormal) direction component, whose
// inverse is not finite, takes Embree. On the showcase (8 BVH objects)
// this took a secondary ray from ~770 to ~680 instructions (callgrind);
// camera and shadow rays stay with the light buffers, which cost less than
// the filter for them (testing camera rays through the filter instead of
// the camera buffer added ~4 % to a frame's instructions).
//
// A few objects far larger than the rest (a ground sphere of radius 1e6
// beside unit spheres) would make S, and every box's padding, huge; up to
// kMaxOutliers of them are tested beside the BVH instead.

#include "embree_query.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <cmath>
#include <limits>
#include <type_traits>

#include "embree_update.hpp"
#include "prism/errors.hpp"
#include "prism/geometry.hpp"

namespace prism::embree {

namespace {

constexpr double kRelativePad = 4e-6;  // of S
constexpr double kAbsolutePad = 0x1p-40;  // of M
constexpr double kOutlierRatio = 1e3;  // size > 1000 x the median object size
constexpr size_t kMaxOutliers = 8;
// Light buffers pay while their lists are short: up to this many bounded objects.
constexpr size_t kMaxViewObjects = 64;

// The per-query state the callbacks read. Embree hands back the address of
// `rtc`, the first member of this standard-layout struct.
struct QueryContext {
  RTCIntersectContext rtc;
  const Ray* ray = nullptr;  // the double world ray
  double tmin = 0;           // closest: t > tmin
  double tmax = 0;           // occluded: 0 < t < tmax
  double shift = 0;          // Embree's tau = world t - shift
  Hit* best = nullptr;       // closest so far (double t, id, plugin data): the caller's answer, written in place
  int32_t skip = kMissId;    // closest: an object the ray cannot meet (Embree still visits it)
  int32_t blocker = kMissId; // occluder: an object that blocks the ray
};
static_assert(std::is_standard_layout_v<QueryContext>);

QueryContext& context_of(RTCIntersectContext* rtc) { return *reinterpret_cast<QueryContext*>(rtc); }

// The float next to a finite float f, toward +infinity (sign +1) or
// -infinity (sign -1): std::nextafter without the library call, which the
// per-ray conversions below make millions of times a frame.
float float_step(float f, int sign) {
  if (f == 0.0f) return float(sign) * std::numeric_limits<float>::denorm_min();
  const uint32_t bits = std::bit_cast<uint32_t>(f);
  const bool away_from_zero = (f > 0.0f) == (sign > 0);
  return std::bit_cast<float>(away_from_zero ? bits + 1u : bits - 1u);
}

float float_down(double x) {
  if (x < -std::numeric_limits<float>::max()) return -std::numeric_limits<float>::infinity();
  float f = static_cast<float>(x);
  return static_cast<double>(f) > x ? float_step(f, -1) : f;
}

float float_up(double x) {
  if (x > std::numeric_limits<float>::max()) return std::numeric_limits<float>::infinity();
  float f = static_cast<float>(x);
  return static_cast<double>(f) < x ? float_step(f, +1) : f;
}

// Nested, not std::max({...}): this runs for every ray, and GCC does not unroll the list.
double max_abs(const glm::dvec3& v) { return std::max(std::max(std::abs(v.x), std::abs(v.y)), std::abs(v.z)); }

double half_size(const Box3& box) { return 0.5 * max_abs(box.hi - box.lo); }

bool finite_box(const Box3& box) {
  for (int a = 0; a < 3; ++a) {
    if (!std::isfinite(box.lo[a]) || !std::isfinite(box.hi[a]) || box.lo[a] > box.hi[a]) return false;
  }
  return true;
}

// A bounding sphere grown for misses_bound: by the BVH's pad (the hit point
// of a plugin may lie outside the world box by rounding, which the pad
// covers, as in the top comment) and by a relative 1e-9.
glm::dvec4 grown_bound(const BoundSphere& s, double pad) { return {s.center, s.radius * (1 + 1e-9) + pad}; }

// Whether the part 0 < t < tmax of `ray` surely misses the ball `bound`
// (centre xyz, radius w). The ray's points keep a distance >= |t - tc| and
// >= the line's distance from the centre, tc = (c - o).d; the tests allow
// 1e-14 relative for the rounding of those dot products (d is unit up to a
// few ulps). A shadow ray's candidates mostly fail here at ~20
// instructions, against ~100 for a plugin call.
[[gnu::always_inline]] inline bool misses_bound(const Ray& ray, double tmax, const glm::dvec4& bound) {
  const glm::dvec3 v = glm::dvec3(bound) - ray.origin;
  const double vv = glm::dot(v, v), tc = glm::dot(v, ray.dir), r = bound.w;
  const double slack = 1e-14 * (std::abs(tc) + tmax);
  if (tc + r < -slack || tc - r > tmax + slack) return true;
  return vv - tc * tc > r * r + 1e-14 * vv;
}

// Takes `id`'s hit when it is closer, or as close with a lower id.
void consider(QueryContext& ctx, const Object& object, int32_t id) {
  if (id == ctx.skip) return;
  PrismHit hit;
  if (!intersect_object(object, *ctx.ray, ctx.tmin, ctx.best->t, hit)) return;
  if (hit.t == ctx.best->t && id > ctx.best->id) return;
  ctx.best->t = hit.t;
  ctx.best->id = id;
  ctx.best->prim = hit;
}

}  // namespace

namespace {

// The generic callbacks of every user geometry: no per-type code here, the
// plugin behind each object does the work (style.md #6).
void bounds_callback(const RTCBoundsFunctionArguments* args) {
  const auto& group = *static_cast<const EmbreeQuery::Group*>(args->geometryUserPtr);
  const Box3& box = group.objects[group.ids[args->primID]].world_bounds;
  const Frame& frame = *group.frame;
  const glm::dvec3 lo = box.lo - frame.center - frame.pad;
  const glm::dvec3 hi = box.hi - frame.center + frame.pad;
  RTCBounds& out = *args->bounds_o;
  out.lower_x = float_down(lo.x);
  out.lower_y = float_down(lo.y);
  out.lower_z = float_down(lo.z);
  out.upper_x = float_up(hi.x);
  out.upper_y = float_up(hi.y);
  out.upper_z = float_up(hi.z);
}

// Whether `group` holds `id` no more (it moved to another layer).
bool skipped(const EmbreeQuery::Group& group, int32_t id) { return group.skip != nullptr && (*group.skip)[id] != 0; }

void intersect_callback(const RTCIntersectFunctionNArguments* args) {
  QueryContext& ctx = context_of(args->context);
  const auto& group = *static_cast<const EmbreeQuery::Group*>(args->geometryUserPtr);
  const int32_t id = group.ids[args->primID];
  if (skipped(group, id)) return;
  const int32_t before = ctx.best->id;
  const double before_t = ctx.best->t;
  consider(ctx, group.objects[id], id);
  if (ctx.best->id == before && ctx.best->t == before_t) return;
  // rtcIntersect1 passes one ray (N == 1); every valid lane is that ray.
  const float tfar = float_up(ctx.best->t - ctx.shift);
  RTCRayN* rays = RTCRayHitN_RayN(args->rayhit, args->N);
  RTCHitN* hits = RTCRayHitN_HitN(args->rayhit, args->N);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] == 0) continue;
    float& ray_tfar = RTCRayN_tfar(rays, args->N, i);
    ray_tfar = std::min(ray_tfar, tfar);
    RTCHitN_geomID(hits, args->N, i) = args->geomID;
    RTCHitN_primID(hits, args->N, i) = args->primID;
  }
}

void occluded_callback(const RTCOccludedFunctionNArguments* args) {
  QueryContext& ctx = context_of(args->context);
  const auto& group = *static_cast<const EmbreeQuery::Group*>(args->geometryUserPtr);
  const int32_t id = group.ids[args->primID];
  if (ctx.blocker != kMissId || skipped(group, id) || !blocks(group.objects[id], *ctx.ray, ctx.tmax)) return;
  ctx.blocker = id;
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] != 0) RTCRayN_tfar(args->ray, args->N, i) = -std::numeric_limits<float>::infinity();
  }
}

// The float ray for world t >= shift, up to world t = t_limit (see the top).
RTCRay float_ray(const Ray& ray, const Frame& frame, double shift, double t_limit) {
  const glm::dvec3 e = (ray.origin - frame.center) + shift * ray.dir;
  RTCRay r{};
  r.org_x = static_cast<float>(e.x);
  r.org_y = static_cast<float>(e.y);
  r.org_z = static_cast<float>(e.z);
  r.tnear = 0.0f;
  r.dir_x = static_cast<float>(ray.dir.x);
  r.dir_y = static_cast<float>(ray.dir.y);
  r.dir_z = static_cast<float>(ray.dir.z);
  r.time = 0.0f;
  r.tfar = float_up(t_limit - shift);
  r.mask = 0xFFFFFFFFu;
  r.id = 0;
  r.flags = 0;
  return r;
}

}  // namespace

EmbreeQuery::EmbreeQuery(const Scene& scene, Device& device) : scene_(scene), device_(device) {
  const auto& objects = scene.objects;
  std::vector<double> sizes;
  for (size_t i = 0; i < objects.size(); ++i) {
    const bool in_bvh = objects[i].bounded && finite_box(objects[i].world_bounds);
    (in_bvh ? bvh_ids_ : brute_ids_).push_back(static_cast<int32_t>(i));
    if (in_bvh) sizes.push_back(half_size(objects[i].world_bounds));
  }
  outsized_limit_ = std::numeric_limits<double>::infinity();
  if (!sizes.empty()) {
    auto middle = sizes.begin() + static_cast<std::ptrdiff_t>(sizes.size() / 2);
    std::nth_element(sizes.begin(), middle, sizes.end());
    outsized_limit_ = kOutlierRatio * *middle;
    std::vector<int32_t> outliers;
    for (int32_t id : bvh_ids_) {
      if (half_size(objects[id].world_bounds) > outsized_limit_) outliers.push_back(id);
    }
    if (!outliers.empty() && outliers.size() <= kMaxOutliers) {
      std::erase_if(bvh_ids_, [&](int32_t id) { return std::ranges::binary_search(outliers, id); });
      brute_ids_.insert(brute_ids_.end(), outliers.begin(), outliers.end());
      std::ranges::sort(brute_ids_);
    }
  }
  kinds_.reserve(objects.size());
  for (const Object& object : objects) kinds_.push_back(kind_of(object));
  if (bvh_ids_.empty()) return;
  Box3 all = empty_box();
  for (int32_t id : bvh_ids_) all = box_union(all, objects[id].world_bounds);
  const double slack = kFrameSlack * max_abs(all.hi - all.lo);
  set_frame(Box3{all.lo - slack, all.hi + slack});
  frame_.objects = all;
  build();
}

EmbreeQuery::~EmbreeQuery() = default;

EmbreeQuery::Kind EmbreeQuery::kind_of(const Object& object) const {
  if (!object.bounded || !finite_box(object.world_bounds)) return Kind::kUnbounded;
  return half_size(object.world_bounds) > outsized_limit_ ? Kind::kOutsized : Kind::kRegular;
}

void EmbreeQuery::set_frame(const Box3& bounds) {
  frame_.bounds = bounds;
  frame_.center = 0.5 * (bounds.lo + bounds.hi);
  frame_.half = bounds.hi - frame_.center;
  frame_.pad = kRelativePad * max_abs(frame_.half) + kAbsolutePad * std::max(max_abs(bounds.lo), max_abs(bounds.hi));
}

void EmbreeQuery::build() {
  const auto& objects = scene_.objects;
  if (bvh_ids_.size() <= BoxFilter::kMaxObjects) filter_.emplace(bvh_ids_, objects, frame_.pad);
  boxes_.assign(objects.size(), Box3{});
  for (int32_t id : bvh_ids_) {
    boxes_[id] = objects[id].world_bounds;
    built_area_ += half_area(boxes_[id]);
  }
  now_area_ = built_area_;
  // One user geometry: the callbacks serve any mix of primitive types.
  main_ = Group{objects.data(), &frame_, bvh_ids_, nullptr};  // skips nothing until layers start
  main_scene_.reset(rtcNewScene(device_.get()));
  device_.check("scene creation");
  // HIGH built ~15% slower and rendered no faster on the 100,000-sphere scene.
  rtcSetSceneBuildQuality(main_scene_.get(), RTC_BUILD_QUALITY_MEDIUM);
  attach_objects(main_scene_.get(), main_);
  rtcCommitScene(main_scene_.get());
  device_.check("BVH build");
}

unsigned EmbreeQuery::attach_objects(RTCScene scene, Group& group) {
  RTCGeometry geometry = rtcNewGeometry(device_.get(), RTC_GEOMETRY_TYPE_USER);
  device_.check("geometry creation");
  rtcSetGeometryUserPrimitiveCount(geometry, static_cast<unsigned>(group.ids.size()));
  rtcSetGeometryUserData(geometry, &group);
  rtcSetGeometryBoundsFunction(geometry, &bounds_callback, nullptr);
  rtcSetGeometryIntersectFunction(geometry, &intersect_callback);
  rtcSetGeometryOccludedFunction(geometry, &occluded_callback);
  rtcCommitGeometry(geometry);
  const unsigned id = rtcAttachGeometry(scene, geometry);
  rtcReleaseGeometry(geometry);  // the scene holds it now
  device_.check("geometry setup");
  return id;
}

bool EmbreeQuery::clip(const Ray& ray, double& t0, double& t1) const {
  t0 = -std::numeric_limits<double>::infinity();
  t1 = std::numeric_limits<double>::infinity();
  // A NaN or infinite ray never reaches Embree (its float rays must be finite).
  if (!std::isfinite(max_abs(ray.origin) + max_abs(ray.dir))) return false;
  const glm::dvec3 o = ray.origin - frame_.center;
  const glm::dvec3 lo = frame_.objects.lo - frame_.center - 2.0 * frame_.pad;
  const glm::dvec3 hi = frame_.objects.hi - frame_.center + 2.0 * frame_.pad;
  for (int a = 0; a < 3; ++a) {
    if (ray.dir[a] == 0.0) {
      if (!(lo[a] <= o[a] && o[a] <= hi[a])) return false;
      continue;
    }
    const double inv = 1.0 / ray.dir[a];
    double near = (lo[a] - o[a]) * inv;
    double far = (hi[a] - o[a]) * inv;
    if (near > far) std::swap(near, far);
    t0 = std::max(t0, near);
    t1 = std::min(t1, far);
  }
  return t0 <= t1;
}

bool EmbreeQuery::shift_is_exact_enough(const Ray& ray, double shift) const {
  const double magnitude = max_abs(ray.origin) + max_abs(frame_.center) + std::abs(shift);
  return magnitude * 0x1p-44 <= frame_.pad;
}

bool EmbreeQuery::filter_takes(const Ray& ray, glm::dvec3& inv) const {
  // A NaN or infinite origin makes the sum so (max_abs may drop a NaN).
  const glm::dvec3& o = ray.origin;
  if (!filter_ || !std::isfinite(o.x + o.y + o.z) || !shift_is_exact_enough(ray, 0.0)) return false;
  inv = 1.0 / ray.dir;
  return std::isfinite(inv.x) && std::isfinite(inv.y) && std::isfinite(inv.z);  // and dir is not NaN
}

[[gnu::always_inline]] inline void EmbreeQuery::closest_filtered(const Ray& ray, double tmin, int32_t skip,
                                                                  const glm::dvec3& inv, Hit& best) const {
  QueryContext ctx;
  ctx.best = &best;
  ctx.ray = &ray;
  ctx.tmin = tmin;
  ctx.skip = skip;
  for (int32_t id : brute_ids_) consider(ctx, scene_.objects[id], id);
  std::array<double, BoxFilter::kMaxObjects> enter, leave;
  const uint32_t entered = filter_->clip(ray.origin, inv, tmin, ctx.best->t, std::span(enter).first(filter_->padded_size()),
                                         std::span(leave).first(filter_->padded_size()));
  // The boxes the ray enters, nearest first (insertion sort: a handful).
  std::array<uint8_t, BoxFilter::kMaxObjects> order;
  size_t count = 0;
  for (uint32_t left = entered; left != 0; left &= left - 1) {
    const size_t k = size_t(std::countr_zero(left));
    size_t at = count++;
    for (; at > 0 && enter[order[at - 1]] > enter[k]; --at) order[at] = order[at - 1];
    order[at] = uint8_t(k);
  }
  for (size_t i = 0; i < count; ++i) {
    const size_t k = order[i];
    if (enter[k] > ctx.best->t) break;  // this box and the rest start beyond the best hit (a tie may still win)
    const int32_t id = filter_->id(k);
    consider(ctx, scene_.objects[id], id);
  }
}

int32_t EmbreeQuery::occluder_filtered(const Ray& ray, double tmax, const glm::dvec3& inv) const {
  for (int32_t id : brute_ids_) {
    if (blocks(scene_.objects[id], ray, tmax)) return id;
  }
  std::array<double, BoxFilter::kMaxObjects> enter, leave;
  const uint32_t entered = filter_->clip(ray.origin, inv, 0.0, tmax, std::span(enter).first(filter_->padded_size()),
                                         std::span(leave).first(filter_->padded_size()));
  for (uint32_t left = entered; left != 0; left &= left - 1) {
    const int32_t id = filter_->id(size_t(std::countr_zero(left)));
    if (blocks(scene_.objects[id], ray, tmax)) return id;
  }
  return kMissId;
}

// Inlined into its callers (closest_leaving_batch's loop above all), the
// rays Embree answers called out of line: the filter's rays then cost no
// call but the plugins' (a call's set-up and its frame were some 40
// instructions a ray).
[[gnu::always_inline]] inline void EmbreeQuery::closest_skipping(const Ray& ray, double tmin, int32_t skip,
                                                                  Hit& best) const {
  // Written field by field: a whole Hit stored at once and read back in
  // other pieces would wait for the stores (a store-forwarding stall).
  best.t = kInfinity;
  best.id = kMissId;
  if (glm::dvec3 inv; filter_takes(ray, inv)) return closest_filtered(ray, tmin, skip, inv, best);
  closest_traced(ray, tmin, skip, best);
}

[[gnu::noinline]] void EmbreeQuery::closest_traced(const Ray& ray, double tmin, int32_t skip, Hit& best) const {
  QueryContext ctx;
  rtcInitIntersectContext(&ctx.rtc);
  ctx.best = &best;
  ctx.ray = &ray;
  ctx.tmin = tmin;
  ctx.skip = skip;
  for (int32_t id : brute_ids_) consider(ctx, scene_.objects[id], id);
  double t0 = 0;
  double t1 = 0;
  if (!main_scene_ || !clip(ray, t0, t1) || !(t1 > tmin) || t0 > ctx.best->t) return;
  ctx.shift = std::max(t0, tmin);
  if (!shift_is_exact_enough(ray, ctx.shift)) {
    for (int32_t id : bvh_ids_) consider(ctx, scene_.objects[id], id);
    return;
  }
  RTCRayHit rayhit{};
  rayhit.ray = float_ray(ray, frame_, ctx.shift, std::min(ctx.best->t, t1));
  rayhit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rayhit.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(trace_scene(), &ctx.rtc, &rayhit);
}

Hit EmbreeQuery::closest(const Ray& ray, double tmin) const {
  Hit best;
  closest_skipping(ray, tmin, kMissId, best);
  return best;
}

Hit EmbreeQuery::closest_leaving(const Ray& ray, int32_t self) const {
  Hit best;
  closest_skipping(ray, 0.0, self, best);
  return best;
}

void EmbreeQuery::closest_leaving_batch(std::span<const Ray> rays, const int32_t* self, Hit* hits) const {
  for (size_t j = 0; j < rays.size(); ++j) closest_skipping(rays[j], 0.0, self[j], hits[j]);
}

int32_t EmbreeQuery::occluder(const Ray& ray, double tmax) const {
  if (!(tmax > 0.0)) return kMissId;
  if (glm::dvec3 inv; filter_takes(ray, inv)) return occluder_filtered(ray, tmax, inv);
  QueryContext ctx;
  rtcInitIntersectContext(&ctx.rtc);
  ctx.ray = &ray;
  ctx.tmax = tmax;
  for (int32_t id : brute_ids_) {
    if (blocks(scene_.objects[id], ray, tmax)) return id;
  }
  double t0 = 0;
  double t1 = 0;
  if (!main_scene_ || !clip(ray, t0, t1) || !(t1 > 0.0) || !(t0 < tmax)) return kMissId;
  ctx.shift = std::max(t0, 0.0);
  if (!shift_is_exact_enough(ray, ctx.shift)) {
    auto it = std::ranges::find_if(bvh_ids_, [&](int32_t id) { return blocks(scene_.objects[id], ray, tmax); });
    return it == bvh_ids_.end() ? kMissId : *it;
  }
  RTCRay float_shadow_ray = float_ray(ray, frame_, ctx.shift, std::min(tmax, t1));
  rtcOccluded1(trace_scene(), &ctx.rtc, &float_shadow_ray);
  return ctx.blocker;
}

void EmbreeQuery::start_views() {
  views_.reset();
  views_tried_ = true;
  const auto& objects = scene_.objects;
  if (objects.size() > kMaxViewObjects + 16) return;  // too many for buffers, whatever their kinds
  Views views;
  views.bound_of.resize(objects.size());
  double largest = 0;  // |coordinate| over every bounded object and light
  std::vector<double> radii;
  for (size_t id = 0; id < objects.size(); ++id) {
    if (kinds_[id] == Kind::kUnbounded) {
      views.unbounded.push_back(int32_t(id));
      continue;
    }
    const Box3& box = objects[id].world_bounds;
    const WorldSphere bound = world_bounding_sphere(objects[id]);
    views.spheres.push_back({bound.center, bound.radius, int32_t(id)});
    views.bound_of[id] = grown_bound(views.spheres.back(), frame_.pad);
    radii.push_back(views.spheres.back().radius);
    largest = std::max({largest, max_abs(box.lo), max_abs(box.hi)});
  }
  if (views.spheres.empty() || views.spheres.size() > kMaxViewObjects) return;
  for (const Light& light : scene_.lights) largest = std::max(largest, max_abs(light.position));
  auto middle = radii.begin() + std::ptrdiff_t(radii.size() / 2);
  std::nth_element(radii.begin(), middle, radii.end());
  // A shadow ray ends within its offset (1e-4 (1 + |P|), the format's) of
  // its light: room for hit points out to ~10x the scene's extent, or a
  // twentieth of a median object, whichever is larger.
  views.light_reach = std::max(1e-3 * (1 + largest), 0.05 * *middle);
  views.extent = largest;
  views_ = std::move(views);
}

void EmbreeQuery::prepare_views(const glm::dvec3& eye) {
  if (!views_tried_) start_views();
  if (!views_) return;
  Views& v = *views_;
  const bool new_camera = !v.camera || v.eye != eye;
  const auto& lights = scene_.lights;
  const bool new_lights = v.lights.size() != lights.size() ||
                          !std::ranges::equal(v.lights, lights, [](const Light& a, const Light& b) {
                            return a.type == b.type && a.position == b.position && a.direction == b.direction;
                          });
  if (new_camera) v.eye = eye;
  if (new_lights) {
    v.lights = lights;
    v.points.assign(lights.size(), std::nullopt);
    v.parallels.assign(lights.size(), std::nullopt);
  }
  // The buffers are independent: built side by side (the camera's and three
  // lights' on the showcase, ~1 ms of a process's first frame on one core).
  // Job 0 is the camera's (its rays start at the eye itself), job 1 + k light k's.
  const size_t jobs = 1 + (new_lights ? lights.size() : 0);
  tbb::parallel_for(size_t(new_camera ? 0 : 1), jobs, [&](size_t job) {
    if (job == 0) {
      v.camera.emplace(eye, v.spheres, 0.0);
      return;
    }
    const size_t k = job - 1;
    if (lights[k].type == Light::Type::Point)
      v.points[k].emplace(lights[k].position, v.spheres, v.light_reach);
    else
      v.parallels[k].emplace(-lights[k].direction, v.spheres, v.extent);
  });
}

Hit EmbreeQuery::camera_closest(const Ray& ray) const {
  const bool buffered = views_ && views_->camera && ray.origin == views_->eye && std::isfinite(max_abs(ray.dir));
  if (!buffered) return closest(ray, 0.0);
  Hit best;
  QueryContext ctx;
  ctx.best = &best;
  ctx.ray = &ray;
  for (int32_t id : views_->unbounded) consider(ctx, scene_.objects[id], id);
  // The objects whose cones hold the ray's direction: a cone of it alone.
  std::array<int32_t, kMaxViewObjects> listed;
  const size_t count = views_->camera->cone_candidates(ray.dir, 1.0, listed.data());
  for (size_t k = 0; k < count; ++k) {
    const int32_t id = listed[k];
    if (!misses_bound(ray, best.t, views_->bound_of[size_t(id)])) consider(ctx, scene_.objects[id], id);
  }
  return best;
}

namespace {

// consider() for the rays of a batch, in packets: rays[j] tries `object`
// with tmin 0 and tmax its best t so far, after `bound` (when given) fails
// to rule it out, and takes the hit on the same terms. Each ray meets the
// objects in the order camera_closest gives them, with the same bounds, so
// every plugin answer, and so every best hit, is the one it gives.
void consider_packets(const Object& object, int32_t id, const glm::dvec4* bound, std::span<const Ray> rays,
                      Hit* hits) {
  constexpr size_t kLanes = PRISM_PACKET_SIZE;
  for (size_t base = 0; base < rays.size(); base += kLanes) {
    const size_t lanes = std::min(kLanes, rays.size() - base);
    std::array<double, kLanes> tmin{}, tmax;
    uint32_t active = 0;
    for (size_t i = 0; i < lanes; ++i) {
      tmax[i] = hits[base + i].t;
      if (!bound || !misses_bound(rays[base + i], tmax[i], *bound)) active |= 1u << i;
    }
    if (active == 0) continue;
    std::array<PrismHit, kLanes> found;
    const uint32_t hit = intersect_object_packet(object, rays.data() + base, active, tmin.data(), tmax.data(), found.data());
    for (uint32_t left = hit & active; left != 0; left &= left - 1) {
      const size_t i = size_t(std::countr_zero(left));
      const double t = found[i].t;
      // The plugin's word is checked, as intersect_object checks it.
      if (!(t > 0.0 && t <= tmax[i]) || t == kInfinity) [[unlikely]] {
        reject_hit(object, t, 0.0, tmax[i]);
        continue;
      }
      Hit& best = hits[base + i];
      if (t == best.t && id > best.id) continue;
      best.t = t;
      best.id = id;
      best.prim = found[i];
    }
  }
}

// The cone around the unit directions of `rays` (all from one point): the
// normalised sum as axis and the smallest cosine to it. A NaN axis (rays in
// opposite directions) makes the cosine NaN, which cone_candidates takes as
// every direction.
void cone_of(std::span<const Ray> rays, glm::dvec3& axis, double& cos_half) {
  glm::dvec3 sum(0);
  for (const Ray& ray : rays) sum += ray.dir;
  axis = sum / glm::length(sum);
  cos_half = 1;
  for (const Ray& ray : rays) cos_half = std::min(cos_half, glm::dot(axis, ray.dir));
  if (std::isnan(axis.x + axis.y + axis.z)) cos_half = std::numeric_limits<double>::quiet_NaN();
}

}  // namespace

// The answers of camera_closest, ray by ray: every ray of the batch starts
// at the eye, so the objects its cell lists are among those whose spheres
// the batch's cone meets (a ray that meets a sphere points into the
// sphere's cone, and lies in the batch's), and a listed object its cell
// leaves out is one the ray cannot hit, whose plugin answers no hit. Each
// ray meets the unbounded objects, then the listed ones, in ascending ids
// and behind the same bounding-sphere test, as in camera_closest.
void EmbreeQuery::camera_closest_batch(std::span<const Ray> rays, Hit* hits) const {
  const bool buffered = views_ && views_->camera && std::ranges::all_of(rays, [&](const Ray& ray) {
    return ray.origin == views_->eye && std::isfinite(max_abs(ray.dir));
  });
  if (!buffered || rays.empty()) return ObjectQuery::camera_closest_batch(rays, hits);
  std::fill_n(hits, rays.size(), Hit{});
  for (int32_t id : views_->unbounded) consider_packets(scene_.objects[id], id, nullptr, rays, hits);
  glm::dvec3 axis;
  double cos_half;
  cone_of(rays, axis, cos_half);
  std::array<int32_t, kMaxViewObjects> listed;
  const size_t count = views_->camera->cone_candidates(axis, cos_half, listed.data());
  for (size_t k = 0; k < count; ++k) {
    const int32_t id = listed[k];
    consider_packets(scene_.objects[id], id, &views_->bound_of[size_t(id)], rays, hits);
  }
}

void EmbreeQuery::light_keys(size_t light, const RayLanes& rays, int32_t* keys) const {
  // The buffers' cells (embree_view_buffers.hpp); kNoCell where no buffer applies.
  if (views_ && light < views_->lights.size()) {
    if (const auto& point = views_->points[light]) return point->cells_toward(rays, keys);
    if (const auto& parallel = views_->parallels[light]) return parallel->cells_of(rays, keys);
  }
  std::fill_n(keys, rays.count, kNoCell);
}

EmbreeQuery::LightLists EmbreeQuery::light_lists(size_t light) const {
  LightLists lists;
  if (light < views_->points.size() && views_->points[light]) lists.cells = &views_->points[light]->cells();
  if (light < views_->parallels.size() && views_->parallels[light]) lists.cells = &views_->parallels[light]->cells();
  lists.unbounded = views_->unbounded;
  lists.bound_of = views_->bound_of.data();
  lists.objects = scene_.objects.data();
  return lists;
}

// The unbounded objects, then the cell's list: the first that blocks the ray.
[[gnu::always_inline]] inline int32_t EmbreeQuery::cell_occluder(const LightLists& lists, int32_t key, const Ray& ray,
                                                                 double tmax, KnownClear clear) {
  for (int32_t id : lists.unbounded)
    if (!clear.has(id) && blocks(lists.objects[id], ray, tmax)) return id;
  for (int32_t id : lists.cell(key)) {
    if (clear.has(id) || misses_bound(ray, tmax, lists.bound_of[size_t(id)])) continue;
    if (blocks(lists.objects[id], ray, tmax)) return id;
  }
  return kMissId;
}

int32_t EmbreeQuery::keyed_light_occluder(size_t light, const Ray& ray, double tmax, KnownClear clear,
                                          int32_t key) const {
  if (key == kNoCell) return occluder(ray, tmax);
  if (!(tmax > 0.0)) return kMissId;
  return cell_occluder(light_lists(light), key, ray, tmax, clear);
}

// keyed_light_occluder, ray by ray, in one loop: no call per ray (the
// shading's own bookkeeping per ray, a virtual call, this function's
// prologue) but the plugins'.
void EmbreeQuery::keyed_light_occluders(size_t light, const RayLanes& rays, const int32_t* keys, const int32_t* self,
                                        const uint8_t* cast, int32_t* blockers) const {
  // Without buffers every key is kNoCell.
  const LightLists lists = views_ ? light_lists(light) : LightLists{};
  for (size_t j = 0; j < rays.count; ++j) {
    int32_t blocker = kMissId;
    if (cast[j]) {
      const Ray ray{{rays.origin[0][j], rays.origin[1][j], rays.origin[2][j]},
                    {rays.dir[0][j], rays.dir[1][j], rays.dir[2][j]}};
      const double tmax = rays.tmax[j];
      const int32_t key = keys[j];
      if (key == kNoCell)
        blocker = occluder(ray, tmax);
      else if (tmax > 0.0)
        blocker = cell_occluder(lists, key, ray, tmax, {self[j], kMissId});
    }
    blockers[j] = blocker;
  }
}

int32_t EmbreeQuery::light_occluder(size_t light, const Ray& ray, double tmax, KnownClear clear) const {
  const RayLanes one{{&ray.origin.x, &ray.origin.y, &ray.origin.z}, {&ray.dir.x, &ray.dir.y, &ray.dir.z}, &tmax, 1};
  int32_t key = kNoCell;
  light_keys(light, one, &key);
  return keyed_light_occluder(light, ray, tmax, clear, key);
}

}  // namespace prism::embree
