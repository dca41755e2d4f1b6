// Light buffers (embree_view_buffers.hpp) and why their lists are complete.
//
// POINT BUFFER. Seen from the apex X, a sphere (c, r) with d = |c - X| > r
// fills the cone of half-angle asin(r / d) around (c - X) / d. A cube-map
// cell is the set of directions through one square of a cube face; its cone
// (axis a, half-angle h) holds them all: h is the largest angle from a to
// the square's corners (the angle to a fixed axis is quasi-convex on the
// face plane, so its maximum over a square is at a corner), and cos h the
// smallest cosine a . c over the unit corner directions c, sin h from it.
// A direction v that meets the sphere lies in both cones, so the angle
// between the axes is at most h + asin(r / d): the test below, made in
// cosines (well conditioned, since h >= 0.01 rad) with a margin of 1e-12
// that covers the rounding of those cosines and sines (a few ulps of a
// unit dot product, over sin h >= 0.01 for the sine: ~1e-14) and a
// direction put into the cell next to its own by rounding. A sphere that
// holds the apex is listed in every cell.
//
// Reach. A ray that passes within `reach` of X, say at Y, with direction v,
// and then meets the object at P = Y + s v (s >= 0): P lies within `reach`
// of X + s v, the half-line from X along v, so that half-line meets the
// sphere grown by `reach`, and v lies in its cone. Every sphere is grown by
// reach before its cone is taken. A shadow ray toward a point light L
// starts at o = P + e n, goes along l = normalize(L - P) and stops at
// |L - o|; its end o + |L - o| l misses L by at most e (the offset's part
// across l), and it runs from there backwards along -l: the caller checks
// that miss against reach, ray by ray, and looks up -l.
//
// PARALLEL BUFFER. A ray o + t d (t > 0) along the light's exact direction
// d meets a sphere (c, r) only where its projection across d, the point
// (o . e1, o . e2), lies within r of (c . e1, c . e2): projecting onto the
// orthonormal e1, e2 shortens distances. In floating point, e1 and e2 are
// perpendicular to d and of unit length up to a few ulps, so the
// projections err by some 8 eps (|o| + |c| + t); with t <= |c - o| + r for
// any point inside the sphere, a margin of 1e-12 (|o| + |c| + r) is ample.
// The grid's origins are limited to `origin_limit_` (covers()), and every
// disc is grown by that margin for the largest |o| and |c|, then by a cell
// on each side when it is rasterised.

#include "embree_view_buffers.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <numbers>

namespace prism::embree {

namespace {

constexpr double kCosineMargin = 1e-12;
// Cells x objects tested to build a buffer: ~0.1 ms.
constexpr double kPointBudget = 2e5;
constexpr double kGridBudget = 2e5;

double max_abs(const glm::dvec3& v) { return std::max(std::max(std::abs(v.x), std::abs(v.y)), std::abs(v.z)); }

int resolution_for(double budget, double per_cell, size_t objects, int lo, int hi) {
  const double cells = budget / (per_cell * double(std::max<size_t>(objects, 1)));
  return std::clamp(int(std::sqrt(cells)), lo, hi);
}

// Cube-map resolutions: powers of two, so that the cells' cones are computed once per process.
constexpr int kMinCubeResolution = 4;
constexpr int kMaxCubeResolution = 32;
int cube_resolution(size_t objects) {
  const int fit = resolution_for(kPointBudget, 6, objects, kMinCubeResolution, kMaxCubeResolution);
  return int(std::bit_floor(unsigned(fit)));
}

// A direction's cube face: its largest component (axis, sign).
struct FaceFrame {
  int axis, u_axis, v_axis;
  double sign;
};

FaceFrame face_frame(int face) {
  const int axis = face / 2;
  return {axis, (axis + 1) % 3, (axis + 2) % 3, face % 2 == 0 ? 1.0 : -1.0};
}

glm::dvec3 face_direction(const FaceFrame& f, double u, double v) {
  glm::dvec3 d(0);
  d[f.axis] = f.sign;
  d[f.u_axis] = u;
  d[f.v_axis] = v;
  return glm::normalize(d);
}

using Cone = ApexCones::Cone;

Cone cell_cone(int face, int i, int j, int resolution) {
  const FaceFrame f = face_frame(face);
  const double step = 2.0 / resolution;
  const double u0 = -1 + step * i, u1 = u0 + step, v0 = -1 + step * j, v1 = v0 + step;
  const glm::dvec3 axis = face_direction(f, 0.5 * (u0 + u1), 0.5 * (v0 + v1));
  double cos_half = 1;
  for (double u : {u0, u1})
    for (double v : {v0, v1}) cos_half = std::min(cos_half, glm::dot(axis, face_direction(f, u, v)));
  return {axis, cos_half, std::sqrt(std::max(0.0, (1 - cos_half) * (1 + cos_half)))};
}

// The cones of every cell of a cube map, face by face, row by row.
std::vector<Cone> make_cell_cones(int resolution) {
  std::vector<Cone> cones;
  cones.reserve(size_t(6 * resolution * resolution));
  for (int face = 0; face < 6; ++face)
    for (int j = 0; j < resolution; ++j)
      for (int i = 0; i < resolution; ++i) cones.push_back(cell_cone(face, i, j, resolution));
  return cones;
}

// Made once per process, and only for the resolutions a scene uses.
template <int kResolution>
const std::vector<Cone>& cell_cones_at() {
  static const std::vector<Cone> cones = make_cell_cones(kResolution);
  return cones;
}

const std::vector<Cone>& cell_cones(int resolution) {
  static_assert(kMinCubeResolution == 4 && kMaxCubeResolution == 32, "one case per resolution");
  switch (resolution) {
    case 4: return cell_cones_at<4>();
    case 8: return cell_cones_at<8>();
    case 16: return cell_cones_at<16>();
    default: return cell_cones_at<32>();
  }
}

// A sphere's cone seen from `apex`, the sphere grown by `reach`.
Cone sphere_cone(const glm::dvec3& apex, const BoundSphere& s, double reach) {
  const glm::dvec3 to = s.center - apex;
  const double d = glm::length(to);
  const double r = (s.radius + reach) * (1 + 1e-12);
  if (!(d > r)) return {glm::dvec3(0), -1, 0, true};
  return {to / d, std::sqrt((d - r) * (d + r)) / d, r / d};
}

// Whether two cones share a direction (conservatively).
bool cones_meet(const Cone& cell, const Cone& object) {
  if (object.everywhere) return true;
  // cos(h1 + h2); when h1 + h2 >= pi every direction qualifies.
  const double sum_sin = cell.sin_half * object.cos_half + cell.cos_half * object.sin_half;
  const double cos_sum = cell.cos_half * object.cos_half - cell.sin_half * object.sin_half;
  if (sum_sin <= 0 && cos_sum < 0) return true;
  return glm::dot(cell.axis, object.axis) >= cos_sum - kCosineMargin;
}

}  // namespace

CellLists::CellLists(const std::vector<std::vector<int32_t>>& cells) {
  for (const auto& cell : cells) {
    ids_.insert(ids_.end(), cell.begin(), cell.end());
    end_cell();
  }
}

ApexCones::ApexCones(const glm::dvec3& apex, std::span<const BoundSphere> spheres, double reach)
    : apex_(apex), reach_(reach) {
  cones_.reserve(spheres.size());
  ids_.reserve(spheres.size());
  for (const BoundSphere& s : spheres) {
    cones_.push_back(sphere_cone(apex, s, reach));
    ids_.push_back(s.id);
  }
}

// The cell cones' argument, with the batch's cone for the cell's: a
// direction that meets a sphere lies in both cones. The caller's cone may be
// far narrower than a cell's (a tile of a large image), where its cosine
// is ill-conditioned, so it is widened by 1e-9 in cosine first (over 1e-8
// rad for any half-angle under ~0.1 rad, against a cosine's rounding of a
// few ulps); past 60 degrees every sphere is listed.
size_t ApexCones::cone_candidates(const glm::dvec3& axis, double cos_half, int32_t* out) const {
  const double c = cos_half - 1e-9;
  const bool wide = !(c > 0.5);
  const Cone cone{axis, c, std::sqrt(std::max(0.0, (1 - c) * (1 + c)))};
  size_t count = 0;
  for (size_t k = 0; k < cones_.size(); ++k)
    if (wide || cones_meet(cone, cones_[k])) out[count++] = ids_[k];
  return count;
}

PointBuffer::PointBuffer(const glm::dvec3& apex, std::span<const BoundSphere> spheres, double reach)
    : cones_(apex, spheres, reach), resolution_(cube_resolution(spheres.size())) {
  // Cell by cell, so each list is filled in place (ascending when `spheres` is).
  for (const Cone& cell : cell_cones(resolution_)) {
    for (size_t k = 0; k < spheres.size(); ++k)
      if (cones_meet(cell, cones_.cones()[k])) cells_.add(spheres[k].id);
    cells_.end_cell();
  }
}

namespace {

// The cell of direction (x, y, z) in a cube map of `resolution` cells a
// face edge, written with selects, not branches, so that a loop over rays
// runs in the vector unit's lanes.
[[gnu::always_inline]] inline int32_t cube_cell(double x, double y, double z, int32_t resolution) {
  // The major axis (ties to x, then y), then u = the next one, v = the one after.
  const double ax = std::abs(x), ay = std::abs(y), az = std::abs(z);
  const bool on_x = (ax >= ay) & (ax >= az), on_y = !on_x & (ay >= az);
  const double major = on_x ? ax : on_y ? ay : az;
  const double u = on_x ? y : on_y ? z : x, v = on_x ? z : on_y ? x : y;
  const double along = on_x ? x : on_y ? y : z;  // its sign picks the face (in doubles, so GCC vectorizes)
  const int32_t face = int32_t((on_x ? 0.0 : on_y ? 2.0 : 4.0) + (along < 0 ? 1.0 : 0.0));
  // One division for both coordinates: c * (1 / major) may differ from
  // c / major by an ulp, which moves only a direction within ~1e-16 of a
  // cell's edge into the next cell, and the lists' cosine margin (the top)
  // covers that. Clamped before the conversion to an integer (a NaN to 0),
  // which truncates as the clamp of the truncation would.
  const double inverse = 1.0 / major, last = double(resolution - 1);
  auto index = [&](double c) {
    const double f = (c * inverse + 1) * 0.5 * resolution;
    return int32_t(f > 0 ? (f < last ? f : last) : 0.0);
  };
  return (face * resolution + index(v)) * resolution + index(u);
}

// The lane loops below, compiled for SSE2 and for AVX2 (chosen at run time,
// as the box filter's are): every lane computes the scalar expressions, so
// either gives the same cells.

// A shadow ray ends at origin + tmax dir, within the offset of its point
// light: within reach of the apex when |end - apex| plus its rounding is at
// most reach, compared in squares (no square root). The factor 1 - 2^-50
// keeps the squares' own rounding (a few ulps) on the safe side, so no ray
// the buffer cannot vouch for is taken.
[[gnu::always_inline]] inline void toward_lanes(const RayLanes& rays, glm::dvec3 apex, double reach, int32_t resolution,
                                                int32_t* cells) {
  const double apex_size = max_abs(apex);
  const double *const x = rays.origin[0], *const y = rays.origin[1], *const z = rays.origin[2];
  const double *const u = rays.dir[0], *const v = rays.dir[1], *const w = rays.dir[2], *const tmax = rays.tmax;
  const size_t count = rays.count;
  for (size_t j = 0; j < count; ++j) {
    const double ox = x[j], oy = y[j], oz = z[j];
    const double dx = u[j], dy = v[j], dz = w[j], t = tmax[j];
    const double ex = ox + t * dx - apex.x, ey = oy + t * dy - apex.y, ez = oz + t * dz - apex.z;
    const double origin_size = std::max(std::max(std::abs(ox), std::abs(oy)), std::abs(oz));
    const double slack = reach - 0x1p-48 * (origin_size + t + apex_size);
    const bool near = (slack > 0) & (ex * ex + ey * ey + ez * ez <= slack * slack * (1 - 0x1p-50));
    const int32_t cell = cube_cell(-dx, -dy, -dz, resolution);
    cells[j] = near ? cell : kNoCell;
  }
}

void toward_lanes2(const RayLanes& rays, glm::dvec3 apex, double reach, int32_t resolution, int32_t* cells) {
  toward_lanes(rays, apex, reach, resolution, cells);
}

bool runs_avx2() {
#if defined(__x86_64__)
  static const bool avx2 = __builtin_cpu_supports("avx2");
  return avx2;
#else
  return false;
#endif
}

#if defined(__x86_64__)
[[gnu::target("avx2")]] void toward_lanes4(const RayLanes& rays, glm::dvec3 apex, double reach, int32_t resolution,
                                           int32_t* cells) {
  toward_lanes(rays, apex, reach, resolution, cells);
}
#endif

}  // namespace

std::vector<int> lane_widths() {
  std::vector<int> widths = {2};
  if (runs_avx2()) widths.push_back(4);
  return widths;
}

void PointBuffer::cells_toward(const RayLanes& rays, int32_t* cells, int width) const {
#if defined(__x86_64__)
  if (width == 4 || (width == 0 && runs_avx2())) return toward_lanes4(rays, apex(), reach(), resolution_, cells);
#endif
  toward_lanes2(rays, apex(), reach(), resolution_, cells);
}

ParallelBuffer::ParallelBuffer(const glm::dvec3& dir, std::span<const BoundSphere> spheres, double extent) : dir_(dir) {
  const glm::dvec3 d = glm::normalize(dir);
  const glm::dvec3 helper = std::abs(d.x) < 0.6 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
  across_[0] = glm::normalize(glm::cross(d, helper));
  across_[1] = glm::normalize(glm::cross(d, across_[0]));
  origin_limit_ = 1e3 * (1 + extent);
  double far = origin_limit_;
  for (const BoundSphere& s : spheres) far = std::max(far, max_abs(s.center) + s.radius);
  const double margin = 1e-12 * 4 * far;  // (|o| + |c| + r), each at most `far` per component, sqrt(3) < 2
  std::vector<glm::dvec3> discs;  // (u, v, radius)
  glm::dvec2 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
  for (const BoundSphere& s : spheres) {
    const glm::dvec3 disc(glm::dot(s.center, across_[0]), glm::dot(s.center, across_[1]), s.radius + margin);
    discs.push_back(disc);
    lo = glm::min(lo, glm::dvec2(disc) - disc.z);
    hi = glm::max(hi, glm::dvec2(disc) + disc.z);
  }
  if (spheres.empty()) return;
  resolution_ = resolution_for(kGridBudget, 1, spheres.size(), 4, 128);
  lo_ = lo;
  cell_ = std::max(hi.x - lo.x, hi.y - lo.y) / resolution_;
  inverse_cell_ = 1.0 / cell_;
  if (!(cell_ > 0) || !std::isfinite(cell_) || !std::isfinite(inverse_cell_)) {
    resolution_ = 0;
    return;
  }
  std::vector<std::vector<int32_t>> cells(size_t(resolution_) * size_t(resolution_));
  auto index = [&](double c, double corner) { return std::clamp(int(std::floor((c - corner) / cell_)), 0, resolution_ - 1); };
  for (size_t k = 0; k < discs.size(); ++k) {
    const glm::dvec3& disc = discs[k];
    // One cell more on each side: the lookup's rounding at a cell's edge.
    const int i0 = std::max(index(disc.x - disc.z, lo_.x) - 1, 0), i1 = std::min(index(disc.x + disc.z, lo_.x) + 1, resolution_ - 1);
    const int j0 = std::max(index(disc.y - disc.z, lo_.y) - 1, 0), j1 = std::min(index(disc.y + disc.z, lo_.y) + 1, resolution_ - 1);
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) cells[size_t(j) * size_t(resolution_) + size_t(i)].push_back(spheres[k].id);
  }
  for (auto& list : cells) std::ranges::sort(list);
  cells_ = CellLists(cells);
}

namespace {

// A directional light's grid (ParallelBuffer): what grid_lanes needs of it.
struct Grid {
  glm::dvec3 dir, across[2];
  glm::dvec2 lo;
  double inverse_cell, origin_limit;
  int32_t resolution;
};

[[gnu::always_inline]] inline void grid_lanes(const RayLanes& rays, const Grid& grid, int32_t* cells) {
  // Multiplied by the inverse cell size: an ulp off the division, covered
  // by the cell each list has on every side. A point outside the grid (and
  // its rounding) lies in no disc. Truncated, not floored: the two differ
  // only on (-0.5, 0), where both clamp to cell 0.
  const int32_t resolution = grid.resolution;
  const double limit = double(resolution) + 0.5, last = double(resolution - 1);
  const glm::dvec3 d = grid.dir, a = grid.across[0], b = grid.across[1];
  const glm::dvec2 lo = grid.lo;
  const double inverse_cell = grid.inverse_cell, origin_limit = grid.origin_limit;
  const double *const x = rays.origin[0], *const y = rays.origin[1], *const z = rays.origin[2];
  const double *const dx = rays.dir[0], *const dy = rays.dir[1], *const dz = rays.dir[2];
  const size_t count = rays.count;
  for (size_t j = 0; j < count; ++j) {
    const double ox = x[j], oy = y[j], oz = z[j];
    const bool along = (dx[j] == d.x) & (dy[j] == d.y) & (dz[j] == d.z);
    const bool covered = std::max(std::max(std::abs(ox), std::abs(oy)), std::abs(oz)) <= origin_limit;
    const double u = (ox * a.x + oy * a.y + oz * a.z - lo.x) * inverse_cell;
    const double v = (ox * b.x + oy * b.y + oz * b.z - lo.y) * inverse_cell;
    const bool inside = (resolution > 0) & (u >= -0.5) & (v >= -0.5) & (u < limit) & (v < limit);
    const double i = u > 0 ? (u < last ? u : last) : 0.0, k = v > 0 ? (v < last ? v : last) : 0.0;
    const int32_t cell = int32_t(k) * resolution + int32_t(i);
    cells[j] = !(along & covered) ? kNoCell : inside ? cell : kNoCandidates;
  }
}

void grid_lanes2(const RayLanes& rays, const Grid& grid, int32_t* cells) { grid_lanes(rays, grid, cells); }

#if defined(__x86_64__)
[[gnu::target("avx2")]] void grid_lanes4(const RayLanes& rays, const Grid& grid, int32_t* cells) {
  grid_lanes(rays, grid, cells);
}
#endif

}  // namespace

void ParallelBuffer::cells_of(const RayLanes& rays, int32_t* cells, int width) const {
  const Grid grid{dir_, {across_[0], across_[1]}, lo_, inverse_cell_, origin_limit_, resolution_};
#if defined(__x86_64__)
  if (width == 4 || (width == 0 && runs_avx2())) return grid_lanes4(rays, grid, cells);
#endif
  grid_lanes2(rays, grid, cells);
}

}  // namespace prism::embree
