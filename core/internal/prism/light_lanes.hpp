// The local lighting of many shading points at once: the format's ambient,
// diffuse and Phong terms (core/src/shading.cpp has the rest of the
// shading), light by light across a batch of points held as structure of
// arrays, so that the arithmetic runs in the vector unit's lanes. Each lane
// computes exactly the scalar expressions, operation for operation and in
// the same order (IEEE addition, multiplication, division and square root
// round the same in a lane as alone, and nothing is contracted), so the
// result does not depend on the width: LightLanes.EveryWidthGivesTheScalarBits.
// The shadow rays and pow() stay scalar (Shader::light_batch).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "prism/cpu_render.hpp"
#include "prism/scene.hpp"

namespace prism {

class LightLanes {
 public:
  static constexpr size_t kCapacity = 64;  // points per batch: every array of a batch fits the first-level cache

  struct Point {
    glm::dvec3 position, n;  // n: the normal facing the incoming ray
    glm::dvec3 origin;       // of its shadow rays: position + epsilon * n
    glm::dvec3 color;        // the material colour times the texel
    glm::dvec3 dir;          // the incoming ray's direction
    double diffuse, specular, shininess;
    int32_t self;  // the object its shadow rays cannot meet (left_behind), or kMissId
  };

  size_t size() const { return size_; }
  bool full() const { return size_ == kCapacity; }
  void clear() { size_ = 0; }
  // Adds a point, its sum starting at ambient x colour; returns its index.
  size_t add(const Point& p, const glm::dvec3& ambient);

  // Computes light `light`'s terms for every point (Arrays: l, energy,
  // distance, ndl, diffuse, highlight), and sets blocked and phong to 0.
  void light_terms(const Light& light);
  // Adds the light's contribution to every point with ndl > 0:
  // energy x visibility x (diffuse + phong), visibility shadow_ambient where
  // blocked and 1 elsewhere. The caller sets blocked and phong first.
  void accumulate(const glm::dvec3& shadow_ambient);
  glm::dvec3 sum(size_t j) const { return {a_.sum[0][j], a_.sum[1][j], a_.sum[2][j]}; }

  // The lane widths this processor runs (2, and 4 where it has AVX2), and
  // the width in use (0: the widest).
  static std::vector<int> widths();
  void use_width(int width) { width_ = width; }

  // The lanes, field by field: the kernels in light_lanes.cpp, and the
  // shadow rays and pow() (Shader::light_batch), read and write them.
  template <class T>
  using Lanes = std::array<T, kCapacity>;
  struct Arrays {
    // Inputs.
    std::array<Lanes<double>, 3> p, n, o, c, d;  // position, n, shadow origin, colour, ray direction
    Lanes<double> kd, specular, shininess;
    Lanes<int32_t> self;
    // One light's terms.
    std::array<Lanes<double>, 3> l, energy, diffuse;
    Lanes<double> distance, ndl, highlight;
    Lanes<double> blocked, phong;  // blocked: 1 or 0
    Lanes<int32_t> key;            // what the query looked up for the shadow ray (ObjectQuery::light_keys)
    // What the lights add up to.
    std::array<Lanes<double>, 3> sum;
  };
  Arrays& arrays() { return a_; }
  const Arrays& arrays() const { return a_; }
  // The points' shadow rays toward the light of the last light_terms().
  RayLanes shadow_rays() const {
    return {{a_.o[0].data(), a_.o[1].data(), a_.o[2].data()}, {a_.l[0].data(), a_.l[1].data(), a_.l[2].data()},
            a_.distance.data(), size_};
  }

 private:
  size_t size_ = 0;
  int width_ = 0;
  Arrays a_;
};

}  // namespace prism
