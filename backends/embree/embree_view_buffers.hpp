// Candidate lists for the rays most of a frame consists of. Camera rays all
// start at one point; the shadow rays toward a point light all end within a
// hair of one point; those toward a directional light all run along one
// direction. For each, a buffer built once lists every bounded object such
// a ray could meet, by the ray's direction (each object's cone of
// directions from the eye; a cube map of them around a point light) or by
// where it starts (a grid across the light's direction): Haines and
// Greenberg's light buffer (1986). The plugins then test only those
// objects, in double, and Embree is not called. The lists are conservative,
// so every answer equals the full query's; embree_view_buffers.cpp gives
// the argument.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "prism/cpu_render.hpp"

namespace prism::embree {

// What a buffer's lane lookups (cells_of) give a ray besides a cell: the
// buffer cannot vouch for it (the full query answers it), or the ray can
// meet no listed object (only the unbounded ones).
constexpr int32_t kNoCell = ObjectQuery::kUnkeyed;  // the full query answers
constexpr int32_t kNoCandidates = -2;

// A world-space sphere that holds object `id`.
struct BoundSphere {
  glm::dvec3 center{0};
  double radius = 0;
  int32_t id = 0;
};


// The lane widths the buffers' lookups run at on this processor: 2 (SSE2),
// and 4 where it has AVX2.
std::vector<int> lane_widths();

// Object ids per cell, each cell's ascending, in one array.
class CellLists {
 public:
  CellLists() = default;
  explicit CellLists(const std::vector<std::vector<int32_t>>& cells);
  // Filling cell by cell: the ids of the next cell, then end_cell().
  void add(int32_t id) { ids_.push_back(id); }
  void end_cell() { start_.push_back(uint32_t(ids_.size())); }
  std::span<const int32_t> operator[](size_t cell) const {
    return {ids_.data() + start_[cell], ids_.data() + start_[cell + 1]};
  }

 private:
  std::vector<uint32_t> start_{0};
  std::vector<int32_t> ids_;
};

// The objects' spheres, each grown by `reach`, as cones of directions seen
// from `apex`: which objects a bundle of rays from (within reach of) the
// apex may meet. The camera's rays need no more than this: a tile's rays
// are a narrow cone, tested against each object's (cone_candidates).
class ApexCones {
 public:
  ApexCones(const glm::dvec3& apex, std::span<const BoundSphere> spheres, double reach);
  const glm::dvec3& apex() const { return apex_; }
  double reach() const { return reach_; }
  // Every object whose sphere (grown by reach) a half-line from within reach
  // of the apex can meet along a direction within the cone around `axis`
  // (unit) whose half-angle has cosine `cos_half`: the lists a batch of
  // rays through one tile of an image shares. Written to `out` (room for
  // every object), ascending when the spheres are; returns how many.
  size_t cone_candidates(const glm::dvec3& axis, double cos_half, int32_t* out) const;

  // A cone of directions: axis, and the cosine and sine of its half-angle;
  // `everywhere` for a sphere that holds the apex (its cone is every direction).
  struct Cone {
    glm::dvec3 axis{0};
    double cos_half = 1, sin_half = 0;
    bool everywhere = false;
  };
  const std::vector<Cone>& cones() const { return cones_; }  // by position in `spheres`

 private:
  glm::dvec3 apex_;
  double reach_;
  std::vector<Cone> cones_;
  std::vector<int32_t> ids_;
};

// Rays that pass within `reach` of `apex` and go on in a direction (or come
// from it): a cube map of directions seen from the apex, each cell listing
// the objects whose cones (ApexCones) meet the cell's.
class PointBuffer {
 public:
  PointBuffer(const glm::dvec3& apex, std::span<const BoundSphere> spheres, double reach);
  const glm::dvec3& apex() const { return cones_.apex(); }
  double reach() const { return cones_.reach(); }
  // Rays that end near the apex (shadow rays toward a point light there),
  // all at once: cells[j] is the cell of ray j's reversed direction, whose
  // list holds every object the ray may meet, or kNoCell where its end lies
  // too far from the apex for the lists ("Reach" in the .cpp).
  // `width`: the lanes (2, or 4 with AVX2; 0: the widest the processor
  // runs); every width gives the same cells.
  void cells_toward(const RayLanes& rays, int32_t* cells, int width = 0) const;
  const CellLists& cells() const { return cells_; }  // cell k's list: cells()[k]

 private:
  ApexCones cones_;
  int resolution_;  // cells per face edge
  CellLists cells_;
};

// Rays along one direction (exactly `dir`): a grid over the plane across it,
// for origins up to 1000 (1 + extent) per coordinate, `extent` the scene's
// largest |coordinate|.
class ParallelBuffer {
 public:
  ParallelBuffer(const glm::dvec3& dir, std::span<const BoundSphere> spheres, double extent);
  const glm::dvec3& dir() const { return dir_; }
  // Rays along dir() all at once: cells[j] is the cell whose list holds
  // every object whose sphere meets ray j (origin + t dir, t > 0), or
  // kNoCandidates where no sphere can, or kNoCell where the ray does not run
  // along dir() or starts too far for the lists' margin (see the .cpp).
  void cells_of(const RayLanes& rays, int32_t* cells, int width = 0) const;
  const CellLists& cells() const { return cells_; }  // cell k's list: cells()[k]

 private:
  glm::dvec3 dir_;
  glm::dvec3 across_[2];  // unit, perpendicular to dir_ and to each other
  double origin_limit_ = 0;
  glm::dvec2 lo_{0};      // the grid's corner
  double cell_ = 1;       // its cells' side
  double inverse_cell_ = 1;
  int resolution_ = 0;    // cells per side
  CellLists cells_;
};

}  // namespace prism::embree
