// libFuzzer target: the bytes as scene JSON through prism::load_scene_from_string,
// with the in-tree primitive plugins. InputError is the expected answer to
// bad input; any other exception, a crash, a sanitizer report, a hang, a
// leak, or an accepted scene that breaks what the loader promises its
// backends (finite values, unit and orthogonal camera basis, unit light
// directions, rotations that are rotations, finite object bounds) is a bug.
// Relative texture paths resolve against scenes/conformance, so the seeds
// from scenes/ load their textures and cube maps.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "prism/errors.hpp"
#include "prism/scene_loader.hpp"

namespace {

[[noreturn]] void broken(const std::string& what) {
  std::fprintf(stderr, "fuzz_scene_loader: accepted scene: %s\n", what.c_str());
  std::abort();
}

bool finite(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
bool unit(const glm::dvec3& v) { return finite(v) && std::abs(glm::length(v) - 1) <= 1e-9; }
bool orthogonal(const glm::dvec3& a, const glm::dvec3& b) { return std::abs(glm::dot(a, b)) <= 1e-9; }

void check_camera(const prism::Camera& c) {
  if (!finite(c.position)) broken("camera position not finite");
  if (!unit(c.forward) || !unit(c.right) || !unit(c.up)) broken("camera basis not unit");
  if (!orthogonal(c.forward, c.right) || !orthogonal(c.forward, c.up) || !orthogonal(c.right, c.up))
    broken("camera basis not orthogonal");
  if (!(c.fov_y > 0 && c.fov_y < 180)) broken("camera fov_y out of (0, 180)");
}

void check_light(const prism::Light& l, size_t i) {
  const std::string where = "lights[" + std::to_string(i) + "]: ";
  if (!finite(l.position) || !finite(l.color) || !std::isfinite(l.intensity)) broken(where + "not finite");
  if (l.type == prism::Light::Type::Directional && !unit(l.direction)) broken(where + "direction not unit");
}

void check_object(const prism::Object& o, size_t i) {
  const std::string where = "objects[" + std::to_string(i) + "]: ";
  if (!finite(o.center)) broken(where + "center not finite");
  const glm::dmat3& R = o.rotation;
  if (!unit(R[0]) || !unit(R[1]) || !unit(R[2]) || !orthogonal(R[0], R[1]) || !orthogonal(R[0], R[2]) ||
      !orthogonal(R[1], R[2]))
    broken(where + "rotation not orthonormal");
  if (!o.bounded) return;
  const prism::Box3& b = o.world_bounds;
  if (!finite(b.lo) || !finite(b.hi) || !(b.lo.x <= b.hi.x && b.lo.y <= b.hi.y && b.lo.z <= b.hi.z))
    broken(where + "bounds not a finite box");
}

void check_scene(const prism::Scene& scene) {
  check_camera(scene.camera);
  for (size_t i = 0; i < scene.lights.size(); ++i) check_light(scene.lights[i], i);
  for (size_t i = 0; i < scene.objects.size(); ++i) check_object(scene.objects[i], i);
}

// One registry for the whole run, as in `prism render`: each plugin is
// loaded once, not once per input.
prism::Registry& registry() {
  static prism::Registry registry({PRISM_PLUGIN_DIR});
  return registry;
}

}  // namespace

// Every in-tree plugin is loaded up front and stays loaded: libFuzzer keeps
// the coverage counters of a loaded library, and unloading one (a plugin
// opened and then refused) would leave it clearing unmapped memory.
extern "C" int LLVMFuzzerInitialize(int*, char***) {
  for (const std::string& type : registry().primitive_types_found()) registry().primitive(type);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    check_scene(prism::load_scene_from_string(text, PRISM_SOURCE_DIR "/scenes/conformance", registry(), "fuzz.json"));
  } catch (const prism::InputError&) {
  }
  return 0;
}
