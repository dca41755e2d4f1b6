#include "kernel_source.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <regex>
#include <set>
#include <sstream>
#include <string_view>

#include "core_glsl_modules.hpp"
#include "kernel.glsl.hpp"
#include "prism/errors.hpp"
#include "prism/sdk/shared_source.hpp"
#include "scene.glsl.hpp"
#include "shading.glsl.hpp"

namespace prism::gpu {

namespace {

std::string_view core_module(std::string_view name) {
  for (const CoreGlslModule& m : kCoreGlslModules)
    if (name == m.name) return m.text;
  return {};
}

void append_section(std::ostringstream& out, const std::string& title, std::string_view text) {
  out << "\n// ===== " << title << " =====\n" << text;
  if (!text.empty() && text.back() != '\n') out << '\n';
}

// prism_intersect_type / prism_surface_type: a branch per primitive type present.
std::string type_dispatch(const PackedScene& scene) {
  std::ostringstream o;
  const size_t n = scene.types.size();
  o << "bool prism_intersect_type(uint type, uint rec, PrismRay ray, real tmin, real tmax, out PrismHit hit) {\n";
  for (size_t i = 0; i < n; ++i) {
    const std::string call = std::string(scene.types[i]->glsl_prefix) + "_intersect(rec, ray, tmin, tmax, hit);\n";
    if (i + 1 < n) o << "  if (type == " << i << "u) return " << call;
    else o << "  return " << call;
  }
  if (n == 0) o << "  prism_clear_hit(hit);\n  return false;\n";
  o << "}\n\nvoid prism_surface_type(uint type, uint rec, PrismRay ray, PrismHit hit, out PrismSurface s) {\n";
  for (size_t i = 0; i < n; ++i) {
    const std::string call = std::string(scene.types[i]->glsl_prefix) + "_surface(rec, ray, hit, s);\n";
    if (i + 1 < n) o << "  if (type == " << i << "u) {\n    " << call << "    return;\n  }\n";
    else o << "  " << call;
  }
  if (n == 0) o << "  s.point = real3(R(0.0));\n  s.normal = real3(R(0.0));\n  s.uv = real2(R(0.0));\n";
  o << "}\n";
  return o.str();
}

// prism_test_every_object (gpu/scene.glsl, PRISM_UNROLLED_OBJECTS): each
// object's intersector called with its slot, record and id as constants,
// and without the rotation for an object that has none.
std::string unrolled_objects(const PackedScene& scene) {
  const auto suffix = [&](size_t slot) { return scene.objects[slot].rotated ? "" : "_unrotated"; };
  std::ostringstream o;
  o << "bool prism_test_every_object(PrismWorldRay ray, wreal tmin, wreal tmax, bool any_hit, inout PrismClosest "
       "best) {\n  PrismHit h;\n";
  for (size_t slot = 0; slot < scene.objects.size(); ++slot) {
    const GpuObject& object = scene.objects[slot];
    const char* prefix = scene.types[object.type]->glsl_prefix;
    o << "  if (" << prefix << "_intersect(" << object.record << "u, prism_to_local" << suffix(slot) << "(" << slot
      << "u, ray), real(tmin), real(any_hit ? tmax : best.t), h) && prism_take_hit(any_hit, " << object.id << ", "
      << slot << "u, h, best))\n    return true;\n";
  }
  o << "  return false;\n}\n\n";
  // The hit's surface and material, object by object: every object's
  // surface is formed and the hit's kept (constant offsets are read once for
  // all lanes; the hit's slot differs from lane to lane).
  o << "PrismWorldSurface prism_world_surface(PrismWorldRay ray, PrismClosest c) {\n  PrismWorldSurface s, each;\n"
       "  PrismSurface local;\n";
  for (size_t slot = 0; slot < scene.objects.size(); ++slot) {
    const GpuObject& object = scene.objects[slot];
    o << "  " << scene.types[object.type]->glsl_prefix << "_surface(" << object.record << "u, prism_to_local"
      << suffix(slot) << "(" << slot << "u, ray), c.hit, local);\n  each = prism_to_world" << suffix(slot) << "(" << slot
      << "u, ray, local);\n  if (c.object == " << slot
      << "u) s = each;\n";
  }
  o << "  return s;\n}\n";
  return o.str();
}

// prism_fill_caches (gpu/scene.glsl, "Caches"): every number an unrolled
// kernel's object tests read, copied once at its start; and the lights.
std::string cache_fill(const PackedScene& scene) {
  std::ostringstream o;
  o << "void prism_fill_caches() {\n  prism_copy_frame();\n";
  if (scene.unrolled) {
    for (size_t slot = 0; slot < scene.objects.size(); ++slot)
      o << "  prism_object_cache[" << slot << "] = prism_objects[" << slot << "];\n";
    for (size_t i = 0; i < scene.records.size(); ++i)
      o << "  prism_record_cache[" << i << "] = prism_records[" << i << "];\n";
  }
  if (!scene.lights.empty() && scene.lights.size() <= kLightsByConstant)
    for (size_t k = 0; k < scene.lights.size(); ++k) o << "  prism_light_cache[" << k << "] = prism_lights[" << k << "];\n";
  o << "}\n";
  return o.str();
}

void append_defines(std::ostringstream& out, const PackedScene& scene, const std::vector<Feature>& features,
                    const KernelOptions& options) {
  const std::pair<const char*, Binding> bindings[] = {
      {"PRISM_BINDING_RECORDS", kBindRecords}, {"PRISM_BINDING_OBJECTS", kBindObjects},
      {"PRISM_BINDING_NODES", kBindNodes},     {"PRISM_BINDING_MATERIALS", kBindMaterials},
      {"PRISM_BINDING_LIGHTS", kBindLights},   {"PRISM_BINDING_TEXELS", kBindTexels},
      {"PRISM_BINDING_FRAME", kBindFrame},     {"PRISM_BINDING_OUTPUT", kBindOutput}};
  for (const auto& [name, value] : bindings) out << "#define " << name << ' ' << value << '\n';
  out << "#define PRISM_LOCAL_SIZE_X " << options.local_size_x << '\n';
  out << "#define PRISM_LOCAL_SIZE_Y " << options.local_size_y << '\n';
  out << "#define PRISM_GROUP_SCRAMBLE " << kGroupScramblePrime << "u\n";
  if (options.trace) out << "#define PRISM_MODE_TRACE 1\n";
  if (options.texel_sampler) out << "#define PRISM_TEXEL_SAMPLER 1\n";
  if (options.material_block)
    out << "#define PRISM_MATERIAL_BLOCK 1\n#define PRISM_MATERIAL_COUNT " << std::max<size_t>(scene.materials.size(), 1) << "\n";
  if (scene.float_world) out << "#define PRISM_WORLD_FLOAT 1\n";
  if (scene.float_world) out << "#define PRISM_REAL_FLOAT 1\n";
  if (scene.unrolled) {
    out << "#define PRISM_UNROLLED_OBJECTS 1\n";
    out << "#define PRISM_OBJECT_COUNT " << std::max<size_t>(scene.objects.size(), 1) << "\n";
    out << "#define PRISM_RECORD_COUNT " << std::max<size_t>(scene.records.size(), 1) << "\n";
  }
  // The light count is part of the kernel (prism_light, gpu/scene.glsl).
  out << "#define PRISM_LIGHT_COUNT " << scene.lights.size() << "\n";
  out << "#define PRISM_LIGHTS_BY_CONSTANT " << kLightsByConstant << "\n";
  for (Feature f : features) out << "#define " << feature_macro(f) << " 1\n";
}

// A float kernel needs every plugin's GLSL written in the shared dialect: a
// plugin without a float instantiation (ABI 4 marks it by an intersect_float
// that is its double intersect) has double-only GLSL.
void require_float_instantiations(const PackedScene& scene) {
  for (const PrismPrimitiveDesc* type : scene.types)
    if (type->intersect_float == type->intersect)
      throw InputError(std::string("--precision float: primitive plugin '") + type->type_name +
                       "' has no float instantiation (its intersector is not written in the shared dialect); "
                       "use --precision double");
}

}  // namespace

bool all_features_forced() {
  const char* value = std::getenv("PRISM_KERNEL_FEATURES");
  return value && std::strcmp(value, "all") == 0;
}

KernelSource generate_kernel(const PackedScene& scene, const KernelOptions& options) {
  KernelSource result;
  std::vector<Feature> features;
  for (Feature f : all_features())
    if (options.all_features || scene.features.count(f)) features.push_back(f);
  for (Feature f : features) result.features.push_back(feature_name(f));
  for (const PrismPrimitiveDesc* type : scene.types) result.features.push_back(std::string("primitive:") + type->type_name);

  if (scene.float_world) require_float_instantiations(scene);
  std::ostringstream out;
  out << "#version 450\n// Generated by Prism's kernel generator (gpu/kernel_source.cpp).\n";
  append_defines(out, scene, features, options);
  out << options.api_glue << '\n';
  append_section(out, "core/glsl/prelude.glsl", core_module("prelude"));
  append_section(out, "prism/sdk/modules/library.shared.glsl", core_module("library"));
  std::set<std::string> spliced;
  for (const PrismPrimitiveDesc* type : scene.types) {
    const sdk::RequiredModules required = sdk::required_modules(type->glsl_source);
    if (!required.problem.empty())
      throw RuntimeError(std::string("the ") + type->type_name + " plugin's GLSL has a " + required.problem);
    for (const std::string& module : required.modules) {
      if (!spliced.insert(module).second) continue;
      std::string_view text = core_module(module);
      if (text.empty())
        throw RuntimeError(std::string("the ") + type->type_name + " plugin's GLSL requires the core module '" +
                           module + "', which this Prism does not have");
      append_section(out, "core module " + module, text);
    }
  }
  for (const PrismPrimitiveDesc* type : scene.types)
    append_section(out, std::string("plugin ") + type->type_name + " " + type->plugin_version, type->glsl_source);
  append_section(out, "primitive type dispatch (generated)", type_dispatch(scene));
  append_section(out, "gpu/scene.glsl", kSceneGlsl);
  if (scene.unrolled) append_section(out, "every object (generated)", unrolled_objects(scene));
  append_section(out, "caches (generated)", cache_fill(scene));
  if (!options.trace) append_section(out, "gpu/shading.glsl", kShadingGlsl);
  append_section(out, "gpu/kernel.glsl", kKernelGlsl);
  result.text = out.str();
  return result;
}

std::string blame_compile_error(const std::string& source, const std::string& log) {
  std::smatch match;
  if (!std::regex_search(log, match, std::regex(R"((^|\s)\w+:(\d+)[(:])"))) return "";
  const long error_line = std::stol(match[2].str());
  // The section of the line: the last "// ===== title =====" marker above it.
  const std::string marker = "// ===== ", plugin = "plugin ";
  std::istringstream in(source);
  std::string line, title;
  long marker_line = 0;
  for (long number = 1; number <= error_line && std::getline(in, line); ++number) {
    if (line.rfind(marker, 0) != 0) continue;
    title = line.substr(marker.size(), line.rfind(" =====") - marker.size());
    marker_line = number;
  }
  if (title.rfind(plugin, 0) != 0) return "";
  const std::string name = title.substr(plugin.size(), title.find(' ', plugin.size()) - plugin.size());
  return "the GLSL of primitive plugin '" + name + "' (line " + std::to_string(error_line - marker_line) +
         " of its source)";
}

uint64_t fnv1a64(const char* data, size_t size) {
  uint64_t h = 14695981039346656037ull;
  for (size_t i = 0; i < size; ++i) {
    h ^= static_cast<unsigned char>(data[i]);
    h *= 1099511628211ull;
  }
  return h;
}

std::string hash_hex(const std::string& text) {
  const uint64_t h = fnv1a64(text.data(), text.size());
  char buffer[17];
  std::snprintf(buffer, sizeof buffer, "%016llx", static_cast<unsigned long long>(h));
  return buffer;
}

}  // namespace prism::gpu
