// The entries of a primitive plugin beside its scalar `intersect`, for
// `prism plugin check` and the tests that run it on every plugin built: the
// packet entries (intersect_packet, occluded_packet) and the occlusion test
// (occluded) lane by lane, bit for bit; the float entry (intersect_float) measured against it; `surface`
// without uv against `surface`, bit for bit.
#pragma once

#include <span>
#include <string>

#include "prism/backend.hpp"
#include "prism/scene.hpp"

namespace prism::cli {

struct PacketCheck {
  int rays = 0;        // rays asked, in packets with random active lanes and bounds
  int mismatches = 0;  // lanes whose packet answer differs from the scalar one
  std::string first;   // the first mismatch, described
};

// `rays` as given, plus a ray from inside and a grazing ray at each hit.
PacketCheck check_packet_entries(const Object& object, std::span<const TraceQuery> rays);

// `surface` asked for no uv (PRISM_HIT_SKIP_UV) against `surface` asked for
// everything, on the hits of the same rays: t, point and normal bit for bit
// (`rays` counts the hits).
PacketCheck check_surface_without_uv(const Object& object, std::span<const TraceQuery> rays);

// world_bounding_sphere (the plugin's bounding_sphere, or the sphere around
// its box) against the points `surface` gives on the hits of the same rays:
// each within the radius, up to a relative 1e-9 (`rays` counts the hits).
PacketCheck check_bounding_sphere(const Object& object, std::span<const TraceQuery> rays);

// The float entry against the double one, the double answer taken as the
// truth: on the random rays (`given`), and on the rays from inside and the
// grazing rays check_packet_entries adds. A grazing ray skims the surface
// exactly at a hit, so which side of it a rounding falls is arbitrary in
// any precision: those are reported apart.
struct FloatTally {
  int rays = 0;
  int misclassified = 0;  // hit in one precision and missed in the other
  double t_p99 = 0;       // relative t error of the rays both hit, 99th percentile
  double t_max = 0;
  double misclassified_percent() const { return rays > 0 ? 100.0 * misclassified / rays : 0.0; }
};
struct FloatCheck {
  bool has_float = false;  // false: intersect_float is `intersect` itself (no float instantiation)
  FloatTally random;       // the given rays
  FloatTally stiff;        // the rays from inside and the grazing rays
};
FloatCheck check_float_entry(const Object& object, std::span<const TraceQuery> rays);

}  // namespace prism::cli
