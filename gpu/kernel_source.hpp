// The kernel generator: assembles one compute shader from the core GLSL
// library, only the primitive plugins' intersectors a scene uses, the shared
// scene/shading/kernel sources, and only the PRISM_FEATURE_* switches the
// scene needs. Both GPU backends call it; only `api_glue` differs.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "gpu_scene.hpp"

namespace prism::gpu {

// The prime the render kernel scrambles its work groups by (group k renders
// block k * P mod n; PRISM_GROUP_SCRAMBLE in gpu/kernel.glsl): above any
// group count, so the map is one to one.
constexpr uint32_t kGroupScramblePrime = 104729;

struct KernelOptions {
  bool trace = false;         // the `prism trace` kernel instead of the renderer
  bool all_features = false;  // compile every feature in, whatever the scene uses
  // Backend glue placed after the defines: must define PRISM_TILE_ORIGIN (an
  // ivec4: x0, y0, tile width, tile height; for trace x is the first ray).
  std::string api_glue;
  // Texels through a buffer texture (samplerBuffer; the glue defines its
  // binding as PRISM_BINDING_TEXEL_SAMPLER) instead of the storage buffer:
  // a CPU driver gathers a texel fetch as a vector, but reads a storage
  // buffer at a per-lane index lane by lane. The backend sets it when the
  // texels fit the device's texel-buffer limit.
  bool texel_sampler = false;
  // Materials in a uniform block (the glue defines its binding as
  // PRISM_BINDING_MATERIAL_BLOCK) instead of the storage buffer: a CPU
  // driver gathers a uniform read at a per-lane index as a vector. The
  // backend sets it when the materials fit its uniform-block limit.
  bool material_block = false;
  int local_size_x = 8;
  int local_size_y = 8;
};

struct KernelSource {
  std::string text;
  std::vector<std::string> features;  // what `--stats` reports as kernel_features
};

KernelSource generate_kernel(const PackedScene& scene, const KernelOptions& options);

// Names the part of a generate_kernel() text that a compiler's first error
// (`log`: Mesa's "0:LINE(COL)", glslang's "ERROR: kernel:LINE:") points into:
// "the GLSL of primitive plugin 'torus' (line 12 of its source)", or "" when
// the error is outside every plugin's section or the log has no line.
std::string blame_compile_error(const std::string& source, const std::string& log);

// Whether PRISM_KERNEL_FEATURES=all asks for every feature (the test of the
// generator's specialisation renders the same scene both ways).
bool all_features_forced();

// FNV-1a 64-bit: program cache keys and cache-file checksums.
uint64_t fnv1a64(const char* data, size_t size);
// fnv1a64 of `text` as 16 hex digits.
std::string hash_hex(const std::string& text);

}  // namespace prism::gpu
