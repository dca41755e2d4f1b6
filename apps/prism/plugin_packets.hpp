// The packet entries of a primitive plugin (intersect_packet,
// occluded_packet) against its scalar `intersect`, lane by lane, for
// `prism plugin check` and the tests that run it on every plugin built.
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

}  // namespace prism::cli
