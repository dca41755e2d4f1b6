// Candidate lists for the rays most of a frame consists of. Camera rays all
// start at one point; the shadow rays toward a point light all end within a
// hair of one point; those toward a directional light all run along one
// direction. For each, a buffer built once lists every bounded object such
// a ray could meet, by the ray's direction (a cube map around the point) or
// by where it starts (a grid across the light's direction): Haines and
// Greenberg's light buffer (1986). The plugins then test only those
// objects, in double, and Embree is not called. The lists are conservative,
// so every answer equals the full query's; embree_view_buffers.cpp gives
// the argument.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

namespace prism::embree {

// A world-space sphere that holds object `id`.
struct BoundSphere {
  glm::dvec3 center{0};
  double radius = 0;
  int32_t id = 0;
};


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

// Rays that pass within `reach` of `apex` and go on in a direction (or come
// from it): a cube map of directions seen from the apex.
class PointBuffer {
 public:
  PointBuffer(const glm::dvec3& apex, std::span<const BoundSphere> spheres, double reach);
  const glm::dvec3& apex() const { return apex_; }
  double reach() const { return reach_; }
  // Every object whose sphere meets a half-line that starts within `reach`
  // of the apex and runs along `dir` (unit length).
  std::span<const int32_t> candidates(const glm::dvec3& dir) const { return cells_[cell_of(dir)]; }

 private:
  size_t cell_of(const glm::dvec3& dir) const;
  glm::dvec3 apex_;
  double reach_;
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
  // Whether origin is near enough for the lists' margin (see the .cpp).
  bool covers(const glm::dvec3& origin) const;
  // Every object whose sphere meets the half-line origin + t * dir(), t > 0.
  std::span<const int32_t> candidates(const glm::dvec3& origin) const;

 private:
  glm::dvec3 dir_;
  glm::dvec3 across_[2];  // unit, perpendicular to dir_ and to each other
  double origin_limit_ = 0;
  glm::dvec2 lo_{0};      // the grid's corner
  double cell_ = 1;       // its cells' side
  double inverse_cell_ = 1;
  int resolution_ = 0;    // cells per side
  CellLists cells_;
  std::span<const int32_t> none_;
};

}  // namespace prism::embree
