// The keys of BackendStats' maps (prism/backend.hpp), each spelt once. A
// backend writes stats.counters[counter::kSceneBytes], never a string: a
// misspelt name does not compile, where a misspelt string would silently add
// a key that no reader looks for. The spellings are part of `--stats`'s JSON.
#pragma once

namespace prism {

// BackendStats::rays_by_kind. The kinds every backend counts while it
// renders, in the order it counts them (the CPU shader's RayKind, the GPU
// kernels' counters), and the rays of Backend::trace.
inline constexpr const char* kRayKindNames[] = {"camera", "shadow", "reflect", "refract", "alpha", "shade1"};
namespace ray_kind {
inline constexpr const char* kTrace = "trace";
}  // namespace ray_kind

// BackendStats::ms: phase times, milliseconds.
namespace ms_key {
inline constexpr const char* kBuild = "build";      // prepare(): acceleration structures, uploads
inline constexpr const char* kUpdate = "update";    // update()
inline constexpr const char* kCompile = "compile";  // GPU kernels generated, built and first run
inline constexpr const char* kRender = "render";    // render() and trace()
// RenderSettings::profile: "profile.<phase>", summed over threads.
inline constexpr const char* kProfilePrefix = "profile.";
// A profile phase timed on a GPU ("profile.device: kernel"): it overlaps the
// host's phases, so it is not part of their sum.
inline constexpr const char* kDevicePhasePrefix = "device: ";
}  // namespace ms_key

// BackendStats::counters.
namespace counter {
// Cumulative, kept by every backend so that callers and tests can see what
// prepare() and update() did.
inline constexpr const char* kPrepares = "prepares";                  // prepare() calls
inline constexpr const char* kUpdates = "updates";                    // update() calls
inline constexpr const char* kObjectsUploaded = "objects_uploaded";   // object records (re)read or (re)sent
inline constexpr const char* kBvhBuilds = "bvh_builds";               // acceleration structures built from scratch
inline constexpr const char* kBvhRefits = "bvh_refits";               // ... refitted in place
inline constexpr const char* kKernelBuilds = "kernel_builds";         // GPU kernels generated and built
// What the backend holds for the scene now, bytes.
inline constexpr const char* kSceneBytes = "scene_bytes";
// GPU backends: the device's largest storage buffer, bytes.
inline constexpr const char* kMaxStorageBufferBytes = "max_storage_buffer_bytes";
// OpenGL: driver calls made to build kernels (none on a program cache hit).
inline constexpr const char* kGlCompileShaderCalls = "gl_compile_shader_calls";
inline constexpr const char* kGlLinkProgramCalls = "gl_link_program_calls";
// Vulkan: where kernel build time goes, and the validation layer's messages.
inline constexpr const char* kGlslangCompileCalls = "glslang_compile_calls";
inline constexpr const char* kGlslangMs = "glslang_ms";
inline constexpr const char* kPipelineCreateMs = "pipeline_create_ms";
inline constexpr const char* kFirstDispatchMs = "first_dispatch_ms";
inline constexpr const char* kVulkanValidationMessages = "vulkan_validation_messages";
}  // namespace counter

// BackendStats::info.
namespace info_key {
inline constexpr const char* kDevice = "device";                      // GPU backends: the driver's description
inline constexpr const char* kPrecision = "precision";                // "double", or what is float
inline constexpr const char* kPrecisionObjects = "precision_objects";  // GPU backends: which objects need double, and why
inline constexpr const char* kPrecisionWarning = "precision_warning";  // Vulkan without double: what float costs here
inline constexpr const char* kValidation = "validation";              // Vulkan: "on" or "off"
inline constexpr const char* kProgramCache = "program_cache";         // GPU backends: hit or miss
inline constexpr const char* kProgramCacheFile = "program_cache_file";
}  // namespace info_key

}  // namespace prism
