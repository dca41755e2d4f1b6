// The layout fingerprint of the backend boundary: one 64-bit value, computed
// at compile time in the translation unit that asks for it, from what a
// backend and the core must agree on to share C++ objects:
//  - sizeof, alignof and every member's offset and size of each type that
//    crosses the boundary (the scene model, the settings, images, trace
//    queries and results, stats, scene changes, the descriptor itself, the
//    exceptions thrown across it);
//  - sizeof and alignof of the standard library and glm types they are made
//    of, as used;
//  - the compiler (GCC or Clang) and its major version, the standard library
//    (libstdc++ and its release, or libc++ and its version) and its ABI
//    switches, __cplusplus;
//  - PRISM_BACKEND_ABI_VERSION and PRISM_PRIMITIVE_ABI_VERSION.
// A backend's descriptor carries the value its own compilation saw
// (backend_desc); the registry refuses a backend whose value differs from
// the core's. It cannot see a change that keeps every size and offset (a
// reordered virtual function, an inline function that behaves differently):
// PRISM_BACKEND_ABI_VERSION is bumped for those. docs/architecture.md, "The
// backend boundary".
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "prism/backend.hpp"
#include "prism/cancel.hpp"
#include "prism/cpu_render.hpp"
#include "prism/errors.hpp"
#include "prism/geometry.hpp"
#include "prism/layout_fingerprint.hpp"
#include "prism/primitive_abi.h"
#include "prism/registry.hpp"
#include "prism/scene.hpp"

namespace prism {

namespace toolchain {

// The compiler: 1 GCC, 2 Clang, 0 another (Clang defines __GNUC__ too).
#if defined(__clang__)
inline constexpr uint64_t kCompiler = 2;
inline constexpr uint64_t kCompilerMajor = __clang_major__;
#elif defined(__GNUC__)
inline constexpr uint64_t kCompiler = 1;
inline constexpr uint64_t kCompilerMajor = __GNUC__;
#else
inline constexpr uint64_t kCompiler = 0;
inline constexpr uint64_t kCompilerMajor = 0;
#endif

// The standard library: 1 libstdc++ (its major release; its dual string ABI
// and debug mode), 2 libc++ (its version), 0 another. The major release and
// not the release date (__GLIBCXX__): a point release keeps every layout,
// and a plugin built after a distribution's compiler update should still load.
#if defined(_LIBCPP_VERSION)
inline constexpr uint64_t kStandardLibrary = 2;
inline constexpr uint64_t kStandardLibraryVersion = _LIBCPP_VERSION;
#elif defined(_GLIBCXX_RELEASE)
inline constexpr uint64_t kStandardLibrary = 1;
inline constexpr uint64_t kStandardLibraryVersion = _GLIBCXX_RELEASE;
#else
inline constexpr uint64_t kStandardLibrary = 0;
inline constexpr uint64_t kStandardLibraryVersion = 0;
#endif

#if defined(_GLIBCXX_USE_CXX11_ABI)
inline constexpr uint64_t kCxx11StringAbi = _GLIBCXX_USE_CXX11_ABI;
#else
inline constexpr uint64_t kCxx11StringAbi = 0;
#endif

#if defined(_GLIBCXX_DEBUG)
inline constexpr uint64_t kDebugContainers = 1;
#else
inline constexpr uint64_t kDebugContainers = 0;
#endif

}  // namespace toolchain

// offsetof on a type that is not standard-layout (one holding a
// std::function, say) is conditionally supported; GCC and Clang support it
// and warn. The offsets are what the fingerprint is for.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Winvalid-offsetof"

// A type's size and alignment; a member's offset and size.
#define PRISM_LAYOUT_TYPE(...) uint64_t(sizeof(__VA_ARGS__)), uint64_t(alignof(__VA_ARGS__))
#define PRISM_LAYOUT_MEMBER(T, m) uint64_t(offsetof(T, m)), uint64_t(sizeof(T::m))

// Evaluated where it is called (consteval): in a backend, its own view; in
// the core, the core's. Never a symbol that one could take from the other.
consteval uint64_t backend_layout_fingerprint() {
  return layout_fingerprint({
      // What compiled it.
      toolchain::kCompiler, toolchain::kCompilerMajor, toolchain::kStandardLibrary,
      toolchain::kStandardLibraryVersion, toolchain::kCxx11StringAbi, toolchain::kDebugContainers,
      uint64_t(__cplusplus), PRISM_BACKEND_ABI_VERSION, PRISM_PRIMITIVE_ABI_VERSION,
      // The standard library and glm types the boundary's types are made of.
      PRISM_LAYOUT_TYPE(void*), PRISM_LAYOUT_TYPE(long double), PRISM_LAYOUT_TYPE(std::string),
      PRISM_LAYOUT_TYPE(std::vector<float>), PRISM_LAYOUT_TYPE(std::vector<std::string>),
      PRISM_LAYOUT_TYPE(std::function<void(double)>), PRISM_LAYOUT_TYPE(std::filesystem::path),
      PRISM_LAYOUT_TYPE(std::map<std::string, uint64_t>), PRISM_LAYOUT_TYPE(std::map<std::string, double>),
      PRISM_LAYOUT_TYPE(std::map<std::string, std::string>), PRISM_LAYOUT_TYPE(std::shared_ptr<const RotationExt>),
      PRISM_LAYOUT_TYPE(std::shared_ptr<const PrimitivePlugin>), PRISM_LAYOUT_TYPE(std::unique_ptr<Backend>),
      PRISM_LAYOUT_TYPE(std::optional<PixelRect>), PRISM_LAYOUT_TYPE(std::optional<Camera>),
      PRISM_LAYOUT_TYPE(std::span<const TraceQuery>), PRISM_LAYOUT_TYPE(std::runtime_error),
      PRISM_LAYOUT_TYPE(glm::vec4), PRISM_LAYOUT_TYPE(glm::dvec2), PRISM_LAYOUT_TYPE(glm::dvec3),
      PRISM_LAYOUT_TYPE(glm::dmat3), PRISM_LAYOUT_TYPE(RotationExt),
      // The scene model (prism/scene.hpp).
      PRISM_LAYOUT_TYPE(Texture), PRISM_LAYOUT_MEMBER(Texture, name), PRISM_LAYOUT_MEMBER(Texture, path),
      PRISM_LAYOUT_MEMBER(Texture, width), PRISM_LAYOUT_MEMBER(Texture, height), PRISM_LAYOUT_MEMBER(Texture, texels),
      PRISM_LAYOUT_MEMBER(Texture, codes), PRISM_LAYOUT_MEMBER(Texture, code_values),
      PRISM_LAYOUT_TYPE(Material), PRISM_LAYOUT_MEMBER(Material, name), PRISM_LAYOUT_MEMBER(Material, color),
      PRISM_LAYOUT_MEMBER(Material, texture), PRISM_LAYOUT_MEMBER(Material, uv_scale),
      PRISM_LAYOUT_MEMBER(Material, uv_offset), PRISM_LAYOUT_MEMBER(Material, diffuse),
      PRISM_LAYOUT_MEMBER(Material, specular), PRISM_LAYOUT_MEMBER(Material, shininess),
      PRISM_LAYOUT_MEMBER(Material, reflect), PRISM_LAYOUT_MEMBER(Material, ior), PRISM_LAYOUT_MEMBER(Material, absorb),
      PRISM_LAYOUT_TYPE(Light), PRISM_LAYOUT_MEMBER(Light, type), PRISM_LAYOUT_MEMBER(Light, position),
      PRISM_LAYOUT_MEMBER(Light, direction), PRISM_LAYOUT_MEMBER(Light, color), PRISM_LAYOUT_MEMBER(Light, intensity),
      PRISM_LAYOUT_MEMBER(Light, linear), PRISM_LAYOUT_MEMBER(Light, quadratic), PRISM_LAYOUT_MEMBER(Light, radius),
      PRISM_LAYOUT_TYPE(Box3), PRISM_LAYOUT_MEMBER(Box3, lo), PRISM_LAYOUT_MEMBER(Box3, hi),
      PRISM_LAYOUT_TYPE(Object), PRISM_LAYOUT_MEMBER(Object, plugin), PRISM_LAYOUT_MEMBER(Object, desc),
      PRISM_LAYOUT_MEMBER(Object, material), PRISM_LAYOUT_MEMBER(Object, center),
      PRISM_LAYOUT_MEMBER(Object, rotation), PRISM_LAYOUT_MEMBER(Object, has_rotation),
      PRISM_LAYOUT_MEMBER(Object, rotation_ext), PRISM_LAYOUT_MEMBER(Object, record_size),
      PRISM_LAYOUT_MEMBER(Object, record_inline), PRISM_LAYOUT_MEMBER(Object, record_heap),
      PRISM_LAYOUT_MEMBER(Object, bounded), PRISM_LAYOUT_MEMBER(Object, world_bounds),
      PRISM_LAYOUT_TYPE(Camera), PRISM_LAYOUT_MEMBER(Camera, position), PRISM_LAYOUT_MEMBER(Camera, forward),
      PRISM_LAYOUT_MEMBER(Camera, right), PRISM_LAYOUT_MEMBER(Camera, up), PRISM_LAYOUT_MEMBER(Camera, fov_y),
      PRISM_LAYOUT_TYPE(ImageSettings), PRISM_LAYOUT_MEMBER(ImageSettings, width),
      PRISM_LAYOUT_MEMBER(ImageSettings, height), PRISM_LAYOUT_MEMBER(ImageSettings, spp),
      PRISM_LAYOUT_MEMBER(ImageSettings, max_depth),
      PRISM_LAYOUT_TYPE(Background), PRISM_LAYOUT_MEMBER(Background, color), PRISM_LAYOUT_MEMBER(Background, cubemap),
      PRISM_LAYOUT_TYPE(Scene), PRISM_LAYOUT_MEMBER(Scene, source), PRISM_LAYOUT_MEMBER(Scene, camera),
      PRISM_LAYOUT_MEMBER(Scene, image), PRISM_LAYOUT_MEMBER(Scene, background), PRISM_LAYOUT_MEMBER(Scene, ambient),
      PRISM_LAYOUT_MEMBER(Scene, shadow_ambient), PRISM_LAYOUT_MEMBER(Scene, textures),
      PRISM_LAYOUT_MEMBER(Scene, materials), PRISM_LAYOUT_MEMBER(Scene, lights), PRISM_LAYOUT_MEMBER(Scene, objects),
      PRISM_LAYOUT_MEMBER(Scene, plugins),
      // The primitive plugins' types a backend calls through Object::desc.
      PRISM_LAYOUT_TYPE(PrismPrimitiveDesc), PRISM_LAYOUT_TYPE(PrismRay), PRISM_LAYOUT_TYPE(PrismHit),
      PRISM_LAYOUT_TYPE(PrismRayPacket),
      // The backend interface (prism/backend.hpp).
      PRISM_LAYOUT_TYPE(PixelRect), PRISM_LAYOUT_MEMBER(PixelRect, x), PRISM_LAYOUT_MEMBER(PixelRect, y),
      PRISM_LAYOUT_MEMBER(PixelRect, width), PRISM_LAYOUT_MEMBER(PixelRect, height),
      PRISM_LAYOUT_TYPE(RenderSettings), PRISM_LAYOUT_MEMBER(RenderSettings, image),
      PRISM_LAYOUT_MEMBER(RenderSettings, region), PRISM_LAYOUT_MEMBER(RenderSettings, camera),
      PRISM_LAYOUT_MEMBER(RenderSettings, aov_id), PRISM_LAYOUT_MEMBER(RenderSettings, aov_path),
      PRISM_LAYOUT_MEMBER(RenderSettings, aov_depth), PRISM_LAYOUT_MEMBER(RenderSettings, aov_normal),
      PRISM_LAYOUT_MEMBER(RenderSettings, aov_albedo),
      PRISM_LAYOUT_MEMBER(RenderSettings, progress), PRISM_LAYOUT_MEMBER(RenderSettings, rays_traced),
      PRISM_LAYOUT_MEMBER(RenderSettings, profile),
      PRISM_LAYOUT_TYPE(Image), PRISM_LAYOUT_MEMBER(Image, width), PRISM_LAYOUT_MEMBER(Image, height),
      PRISM_LAYOUT_MEMBER(Image, rgb), PRISM_LAYOUT_MEMBER(Image, id), PRISM_LAYOUT_MEMBER(Image, path),
      PRISM_LAYOUT_MEMBER(Image, depth), PRISM_LAYOUT_MEMBER(Image, normal), PRISM_LAYOUT_MEMBER(Image, albedo),
      PRISM_LAYOUT_TYPE(TraceQuery), PRISM_LAYOUT_MEMBER(TraceQuery, origin), PRISM_LAYOUT_MEMBER(TraceQuery, dir),
      PRISM_LAYOUT_MEMBER(TraceQuery, tmin),
      PRISM_LAYOUT_TYPE(TraceResult), PRISM_LAYOUT_MEMBER(TraceResult, t), PRISM_LAYOUT_MEMBER(TraceResult, id),
      PRISM_LAYOUT_MEMBER(TraceResult, normal),
      PRISM_LAYOUT_TYPE(BackendStats), PRISM_LAYOUT_MEMBER(BackendStats, kernel_features),
      PRISM_LAYOUT_MEMBER(BackendStats, rays), PRISM_LAYOUT_MEMBER(BackendStats, rays_by_kind),
      PRISM_LAYOUT_MEMBER(BackendStats, ms), PRISM_LAYOUT_MEMBER(BackendStats, counters),
      PRISM_LAYOUT_MEMBER(BackendStats, info),
      PRISM_LAYOUT_TYPE(SceneChanges), PRISM_LAYOUT_MEMBER(SceneChanges, objects),
      PRISM_LAYOUT_MEMBER(SceneChanges, objects_added_or_removed), PRISM_LAYOUT_MEMBER(SceneChanges, materials),
      PRISM_LAYOUT_MEMBER(SceneChanges, lights), PRISM_LAYOUT_MEMBER(SceneChanges, textures),
      PRISM_LAYOUT_MEMBER(SceneChanges, environment),
      PRISM_LAYOUT_TYPE(Backend),
      // The CPU backends' path into the core's renderer (prism/cpu_render.hpp, prism/geometry.hpp).
      PRISM_LAYOUT_TYPE(ObjectQuery), PRISM_LAYOUT_TYPE(Ray), PRISM_LAYOUT_MEMBER(Ray, origin),
      PRISM_LAYOUT_MEMBER(Ray, dir), PRISM_LAYOUT_TYPE(Hit), PRISM_LAYOUT_MEMBER(Hit, t), PRISM_LAYOUT_MEMBER(Hit, id),
      PRISM_LAYOUT_MEMBER(Hit, prim), PRISM_LAYOUT_TYPE(RayLanes), PRISM_LAYOUT_MEMBER(RayLanes, origin),
      PRISM_LAYOUT_MEMBER(RayLanes, dir), PRISM_LAYOUT_MEMBER(RayLanes, tmax), PRISM_LAYOUT_MEMBER(RayLanes, count),
      // The descriptor and probe.
      PRISM_LAYOUT_TYPE(PrismBackendProbe), PRISM_LAYOUT_MEMBER(PrismBackendProbe, usable),
      PRISM_LAYOUT_MEMBER(PrismBackendProbe, reason),
      PRISM_LAYOUT_TYPE(PrismBackendDesc), PRISM_LAYOUT_MEMBER(PrismBackendDesc, abi_version),
      PRISM_LAYOUT_MEMBER(PrismBackendDesc, desc_size), PRISM_LAYOUT_MEMBER(PrismBackendDesc, layout_fingerprint),
      PRISM_LAYOUT_MEMBER(PrismBackendDesc, name), PRISM_LAYOUT_MEMBER(PrismBackendDesc, version),
      PRISM_LAYOUT_MEMBER(PrismBackendDesc, speed_rank), PRISM_LAYOUT_MEMBER(PrismBackendDesc, probe),
      PRISM_LAYOUT_MEMBER(PrismBackendDesc, create),
      // What a backend throws into the core, and the core's classes a backend may hold.
      PRISM_LAYOUT_TYPE(InputError), PRISM_LAYOUT_TYPE(RuntimeError), PRISM_LAYOUT_TYPE(Cancelled),
      PRISM_LAYOUT_TYPE(PrimitivePlugin), PRISM_LAYOUT_TYPE(BackendPlugin), PRISM_LAYOUT_TYPE(Registry),
  });
}

#undef PRISM_LAYOUT_TYPE
#undef PRISM_LAYOUT_MEMBER
#pragma GCC diagnostic pop

// A backend plugin's descriptor, its first three members filled in as the
// plugin is compiled:
//   extern "C" PRISM_EXPORT const PrismBackendDesc* prism_backend_entry(void) {
//     static constexpr PrismBackendDesc desc = prism::backend_desc("mine", "1.0.0", 20, probe, create);
//     return &desc;
//   }
consteval PrismBackendDesc backend_desc(const char* name, const char* version, int speed_rank,
                                        void (*probe)(PrismBackendProbe*), Backend* (*create)()) {
  return {PRISM_BACKEND_ABI_VERSION, sizeof(PrismBackendDesc), backend_layout_fingerprint(), name, version,
          speed_rank, probe, create};
}

}  // namespace prism
