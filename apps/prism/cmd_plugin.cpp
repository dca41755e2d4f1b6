// prism plugin fields [TYPE...] [--markdown]
// Prints the JSON fields of the named primitive plugins (default: every one
// found), from their own field tables; --markdown prints the table of
// docs/scene-format.md (plugin_fields.hpp).
//
// prism plugin check FILE.so [--object JSON] [--rays N] [-b BACKENDS]
// Loads one primitive plugin file, prints its descriptor (type, version,
// ABI version, fields, GLSL, refine), checks its packet entries against
// its scalar intersector lane by lane and measures its float entry against
// it (the stability suite's float caps), checks that its surface asked for
// no uv gives the same t, point and normal, then traces random rays at one object
// of its type through the reference backend (the plugin's own CPU
// intersector, in double) and through every other usable backend, in its own
// precision and, where it has a float path, in float (embree:
// the same intersector behind Embree's BVH and the plugin's bounds; the GPU
// backends: its GLSL intersector), and compares them. Exit 0 when every
// backend agrees within its caps, 1 when one does not, 2 for bad input (a
// file that is not a loadable plugin, an object its validation refuses).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <random>

#include <unistd.h>

#include <nlohmann/json.hpp>

#include "cli_common.hpp"
#include "commands.hpp"
#include "plugin_fields.hpp"
#include "plugin_packets.hpp"
#include "prism/errors.hpp"
#include "prism/scene_loader.hpp"
#include "prism/stats_keys.hpp"

namespace prism::cli {

namespace {

namespace fs = std::filesystem;

struct PluginCheckArgs {
  std::string file, object;
  std::vector<std::string> backends;
  int rays = 2000;
};

// Agreement a backend must reach with the reference: ids on 99.9 % of the
// rays and relative t p99 within 1e-9 for a double backend, 1e-4 for the
// others (the stability suite's caps for float32 paths).
constexpr double kMinIdAgreement = 0.999;
constexpr double kDoubleTCap = 1e-9;
constexpr double kGpuTCap = 1e-4;

std::string field_kind(const PrismField& f) {
  if (f.kind == PRISM_FIELD_NUMBER) return "number";
  const std::string n = std::to_string(f.count);
  return f.kind == PRISM_FIELD_ARRAY ? n + " numbers" : n + " numbers or null";
}

std::string field_range(const PrismField& f) {
  std::string text;
  char buffer[64];
  if (std::isfinite(f.min)) {
    std::snprintf(buffer, sizeof buffer, "%s %g", (f.flags & PRISM_FIELD_MIN_EXCLUSIVE) ? ">" : ">=", f.min);
    text += buffer;
  }
  if (std::isfinite(f.max)) {
    std::snprintf(buffer, sizeof buffer, "%s<= %g", text.empty() ? "" : ", ", f.max);
    text += buffer;
  }
  if (f.flags & PRISM_FIELD_LENGTH) text += std::string(text.empty() ? "" : ", ") + "|x| <= 1e7";
  if (f.flags & PRISM_FIELD_NONZERO) text += std::string(text.empty() ? "" : ", ") + "not all 0";
  return text;
}

void print_descriptor(const PrismPrimitiveDesc& d, const fs::path& file) {
  std::printf("%s %s (ABI %u) from %s\n", d.type_name, d.plugin_version, d.abi_version, file.c_str());
  std::printf("  %s; record %u bytes; refine: %s; GLSL: ", (d.flags & PRISM_PRIMITIVE_TRANSFORMABLE)
              ? "transformable (center, rotation)" : "not transformable", d.record_size, d.refine ? "yes" : "no");
  if (d.glsl_source)
    std::printf("yes (prefix %s, %zu bytes)\n", d.glsl_prefix ? d.glsl_prefix : "?", std::strlen(d.glsl_source));
  else
    std::printf("none (the GPU backends cannot draw it)\n");
  std::printf("  fields:\n");
  for (uint32_t i = 0; i < d.field_count; ++i) {
    const PrismField& f = d.fields[i];
    std::printf("    %-14s %s, %s%s%s: %s\n", f.name, field_kind(f).c_str(),
                (f.flags & PRISM_FIELD_REQUIRED) ? "required" : "optional", field_range(f).empty() ? "" : ", ",
                field_range(f).c_str(), f.doc ? f.doc : "");
  }
}

// An object of the plugin's type for the self-test: --object, or every
// required field filled in (numbers 1, 0.5, 0.25, ... in field order, so
// that "inner < outer"-style rules usually hold; arrays of 1s).
nlohmann::json test_object(const PrismPrimitiveDesc& d, const std::string& given) {
  nlohmann::json object;
  if (!given.empty()) {
    try {
      object = nlohmann::json::parse(given);
    } catch (const nlohmann::json::exception& e) {
      throw InputError(std::string("--object: not JSON: ") + e.what());
    }
    if (!object.is_object()) throw InputError("--object: must be a JSON object");
  }
  object["type"] = d.type_name;
  double next = 1.0;
  for (uint32_t i = 0; i < d.field_count; ++i) {
    const PrismField& f = d.fields[i];
    if (!(f.flags & PRISM_FIELD_REQUIRED) || object.contains(f.name)) continue;
    if (f.kind == PRISM_FIELD_NUMBER) {
      object[f.name] = std::isfinite(f.min) && f.min >= next ? f.min + next : next;
      next *= 0.5;
    } else {
      object[f.name] = std::vector<double>(f.count, 1.0);
    }
  }
  if ((d.flags & PRISM_PRIMITIVE_TRANSFORMABLE) && !object.contains("rotation")) {
    object["center"] = {0.1, -0.2, 0.3};
    object["rotation"] = {{"axis", {1, 2, 3}}, {"degrees", 30}};
  }
  return object;
}

// Rays from a sphere around the object's box (or a 4-unit box about the
// origin when it is unbounded) at points in that box grown 1.5 times: most
// of them hit, and some pass just outside the box, where bounds that are
// too small would make a BVH miss what the intersector hits.
std::vector<TraceQuery> test_rays(const Object& object, int count) {
  Box3 box = object.bounded ? object.world_bounds : Box3{glm::dvec3(-2), glm::dvec3(2)};
  const glm::dvec3 mid = 0.5 * (box.lo + box.hi), half = 0.5 * (box.hi - box.lo);
  const double reach = 3.0 * std::max({glm::length(half), 1e-3});
  std::mt19937_64 rng(20261201);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::vector<TraceQuery> rays;
  while (int(rays.size()) < count) {
    const glm::dvec3 on_sphere(unit(rng), unit(rng), unit(rng));
    const double len = glm::length(on_sphere);
    if (!(len > 0.1 && len <= 1.0)) continue;
    const glm::dvec3 origin = mid + reach * on_sphere / len;
    const glm::dvec3 target = mid + 1.5 * half * glm::dvec3(unit(rng), unit(rng), unit(rng));
    rays.push_back({origin, glm::normalize(target - origin), 0.0});
  }
  return rays;
}

struct Agreement {
  int rays = 0, same_id = 0, hits = 0;
  double t_p99 = 0, t_max = 0;
};

Agreement compare(const std::vector<TraceResult>& expected, const std::vector<TraceResult>& got) {
  Agreement a;
  std::vector<double> t_errors;
  for (size_t i = 0; i < expected.size() && i < got.size(); ++i) {
    ++a.rays;
    if (expected[i].id != got[i].id) continue;
    ++a.same_id;
    if (expected[i].id < 0) continue;
    ++a.hits;
    t_errors.push_back(std::abs(got[i].t - expected[i].t) / std::max(std::abs(expected[i].t), 1e-300));
  }
  if (!t_errors.empty()) {
    std::sort(t_errors.begin(), t_errors.end());
    a.t_p99 = t_errors[std::min(t_errors.size() - 1, size_t(std::ceil(0.99 * double(t_errors.size()))) - 1)];
    a.t_max = t_errors.back();
  }
  return a;
}

std::vector<TraceResult> trace_on(const BackendPlugin& plugin, const std::string& name, Precision wanted,
                                  const Scene& scene, const std::vector<TraceQuery>& rays, std::string* precision) {
  std::unique_ptr<Backend> backend = start_backend(plugin, name);
  backend->set_precision(wanted);
  backend->prepare(scene);
  std::vector<TraceResult> results = backend->trace(rays);
  const BackendStats stats = backend->stats();
  if (auto it = stats.info.find(info_key::kPrecision); it != stats.info.end()) *precision = it->second;
  return results;
}

// One backend in one precision against the reference's answers: prints a
// line and returns whether it is within its caps. A backend without a float
// path says so and passes.
bool check_backend(const BackendPlugin& plugin, const std::string& name, Precision wanted, const Scene& scene,
                   const std::vector<TraceQuery>& rays, const std::vector<TraceResult>& expected) {
  std::string precision;
  std::vector<TraceResult> got;
  try {
    got = trace_on(plugin, name, wanted, scene, rays, &precision);
  } catch (const InputError&) {
    if (wanted != Precision::float32) throw;
    std::printf("  %s: no float path (computes in double only)\n", name.c_str());
    return true;
  } catch (const RuntimeError& e) {
    std::printf("  %s: FAIL: %s\n", name.c_str(), e.what());
    return false;
  }
  const Agreement a = compare(expected, got);
  const double cap = precision == "double" ? kDoubleTCap : kGpuTCap;
  const double agreement = double(a.same_id) / double(std::max(1, a.rays));
  const bool pass = agreement >= kMinIdAgreement && a.t_p99 <= cap;
  std::printf("  %s (%s): ids agree on %.3f %% (cap %.1f %%), relative t p99 %.2g, max %.2g (cap p99 %g): %s\n",
              name.c_str(), precision.c_str(), 100.0 * agreement, 100.0 * kMinIdAgreement, a.t_p99, a.t_max, cap,
              pass ? "PASS" : "FAIL");
  return pass;
}

// The float entry against the double one: on the random rays held to the
// stability suite's float caps (misclassified <= 1 %, t p99 <= 1e-4:
// tests/stability/measure.hpp); on the rays from inside and the grazing
// rays, whose side of the surface is arbitrary to a rounding, reported.
// The bounding sphere's line of the self-test; false when it fails.
bool print_sphere_check(const Object& object, std::span<const TraceQuery> rays) {
  const char* whose = object.desc->bounding_sphere ? "the plugin's, or the box's if smaller" : "around the box";
  try {
    const PacketCheck sphere = check_bounding_sphere(object, rays);
    const bool pass = sphere.mismatches == 0;
    std::printf("  bounding sphere (%s): %s on %d hits%s%s\n", whose,
                pass ? "holds every hit point" : "FAIL: misses a hit point", sphere.rays, pass ? "" : ": ",
                sphere.first.c_str());
    return pass;
  } catch (const RuntimeError& e) {  // a sphere that is not finite, or of negative radius
    std::printf("  bounding sphere (%s): FAIL: %s\n", whose, e.what());
    return false;
  }
}

bool print_float_check(const FloatCheck& f) {
  if (!f.has_float) {
    std::printf("  float entry: the double intersector stands in (no float instantiation: a plugin written in the "
                "shared dialect gets one)\n");
    return true;
  }
  constexpr double kMisclassifiedPercentCap = 1.0, kTP99Cap = 1e-4;
  const FloatTally& r = f.random;
  const bool pass = r.misclassified_percent() <= kMisclassifiedPercentCap && r.t_p99 <= kTP99Cap;
  std::printf("  float entry: %s on %d random rays: misclassified %.2f %% (cap %g %%), relative t error p99 %.2g "
              "(cap %g), max %.2g\n",
              pass ? "within the float caps" : "FAIL: over the float caps", r.rays, r.misclassified_percent(),
              kMisclassifiedPercentCap, r.t_p99, kTP99Cap, r.t_max);
  std::printf("  float entry on %d rays from inside and grazing rays (reported): misclassified %.2f %%, relative t "
              "error p99 %.2g, max %.2g\n",
              f.stiff.rays, f.stiff.misclassified_percent(), f.stiff.t_p99, f.stiff.t_max);
  return pass;
}

int run_plugin_check(const PluginCheckArgs& args) {
  if (args.rays < 1 || args.rays > 10000000) throw InputError("--rays must be 1..10000000");
  std::string error;
  auto plugin = load_primitive_plugin(args.file, error);
  if (!plugin) throw InputError(args.file + ": not a usable primitive plugin: " + error);
  const PrismPrimitiveDesc& d = plugin->desc();
  print_descriptor(d, args.file);

  // The registry must find this very file by its type: put a link with the
  // conventional name in a folder searched first.
  const fs::path folder = fs::temp_directory_path() / ("prism-plugin-check-" + std::to_string(::getpid()));
  fs::create_directories(folder);
  struct Cleanup {
    fs::path folder;
    ~Cleanup() {
      std::error_code ec;
      fs::remove_all(folder, ec);
    }
  } cleanup{folder};
  fs::create_symlink(fs::absolute(args.file), folder / ("libprism_primitive_" + std::string(d.type_name) + ".so"));
  std::vector<fs::path> search = {folder};
  for (const fs::path& p : Registry::default_search_path()) search.push_back(p);
  Registry registry(search);

  const nlohmann::json object = test_object(d, args.object);
  const nlohmann::json scene_json = {{"prism", 1},
                                     {"camera", {{"position", {0, 0, 10}}, {"look_at", {0, 0, 0}}}},
                                     {"objects", nlohmann::json::array({object})}};
  Scene scene;
  try {
    scene = load_scene_from_string(scene_json.dump(), ".", registry, "the self-test scene");
  } catch (const InputError& e) {
    throw InputError(std::string(e.what()) + " (the self-test object " + object.dump() +
                     " is not valid: give one with --object)");
  }
  const std::vector<TraceQuery> rays = test_rays(scene.objects[0], args.rays);
  std::printf("self-test: %d rays at %s\n", args.rays, object.dump().c_str());

  std::string precision;
  auto reference_plugin = registry.backend("reference");
  std::vector<TraceResult> expected;
  try {
    expected = trace_on(*reference_plugin, "reference", Precision::float64, scene, rays, &precision);
  } catch (const RuntimeError& e) {  // the core refused what the plugin returned (a NaN, a hit out of range)
    std::printf("  reference: FAIL: %s\n", e.what());
    return 1;
  }
  const auto hits = std::count_if(expected.begin(), expected.end(), [](const TraceResult& r) { return r.id >= 0; });
  std::printf("  reference: %lld of %d rays hit (the plugin's CPU intersector, double)\n", (long long)hits, args.rays);
  if (hits == 0) std::printf("  warning: no ray hits this object; give another with --object\n");
  const PacketCheck packets = check_packet_entries(scene.objects[0], rays);
  bool all_pass = packets.mismatches == 0;
  std::printf("  packet entries: %s on %d lanes (with rays from inside and grazing rays)%s%s\n",
              all_pass ? "agree with intersect bit for bit" : "FAIL: disagree with intersect", packets.rays,
              all_pass ? "" : ": ", packets.first.c_str());
  all_pass = print_float_check(check_float_entry(scene.objects[0], rays)) && all_pass;
  const PacketCheck surfaces = check_surface_without_uv(scene.objects[0], rays);
  std::printf("  surface without uv: %s on %d hits%s%s\n",
              surfaces.mismatches == 0 ? "the same t, point and normal bit for bit" : "FAIL: differs", surfaces.rays,
              surfaces.mismatches == 0 ? "" : ": ", surfaces.first.c_str());
  all_pass = surfaces.mismatches == 0 && all_pass;
  if (scene.objects[0].bounded)
    all_pass = print_sphere_check(scene.objects[0], rays) && all_pass;
  else
    std::printf("  bounding sphere: none (unbounded)\n");

  std::vector<std::string> names = args.backends;
  if (names.empty()) {
    // Every backend found, less those that do not load or crash in a probe of their own.
    std::vector<std::string> found;
    for (const std::string& name : registry.backend_names_found())
      if (name != "reference") found.push_back(name);
    for (const auto& [name, probe] : registry.probe_backends(found)) {
      if (probe.error.empty())
        names.push_back(name);
      else
        std::printf("  %s: skipped: %s\n", name.c_str(), probe.error.c_str());
    }
  }
  for (const std::string& name : names) {
    auto backend_plugin = registry.backend(name);  // InputError when unknown
    const PrismBackendProbe probe = backend_plugin->probe();
    if (!probe.usable) {
      std::printf("  %s: skipped, cannot run here: %s\n", name.c_str(), probe.reason);
      continue;
    }
    // Its own precision, then its float instantiation where it has one.
    for (Precision wanted : {Precision::automatic, Precision::float32})
      all_pass = check_backend(*backend_plugin, name, wanted, scene, rays, expected) && all_pass;
  }
  return all_pass ? 0 : 1;
}

struct PluginFieldsArgs {
  std::vector<std::string> types;
  bool markdown = false;
};

int run_plugin_fields(const PluginFieldsArgs& args) {
  Registry registry;
  const std::vector<std::string> types = args.types.empty() ? registry.primitive_types_found() : args.types;
  std::vector<std::shared_ptr<const PrimitivePlugin>> plugins;
  for (const std::string& type : types) plugins.push_back(registry.primitive(type));  // InputError when unusable
  if (args.markdown) {
    std::vector<const PrismPrimitiveDesc*> descs;
    for (const auto& plugin : plugins) descs.push_back(&plugin->desc());
    std::fputs(fields_markdown(descs).c_str(), stdout);
    return 0;
  }
  for (const auto& plugin : plugins) {
    std::printf("%s %s (%s)\n", plugin->name().c_str(), plugin->desc().plugin_version, plugin->path().c_str());
    std::fputs(fields_text(plugin->desc()).c_str(), stdout);
  }
  return 0;
}

}  // namespace

Command add_plugin_command(CLI::App& app) {
  auto args = std::make_shared<PluginCheckArgs>();
  CLI::App* plugin = app.add_subcommand("plugin", "Primitive plugin tools");
  plugin->require_subcommand(1);
  CLI::App* check = plugin->add_subcommand(
      "check", "Print a primitive plugin's descriptor and test its CPU intersector against every backend");
  check->add_option("file", args->file, "The plugin (libprism_primitive_<type>.so)")->required();
  check->add_option("--object", args->object, "The object to test, as JSON (default: one built from the fields)");
  check->add_option("--rays", args->rays, "Random rays to trace (default 2000)");
  check->add_option("-b,--backend", args->backends, "Backends to compare with the reference (default: all found)")
      ->delimiter(',');
  auto fields_args = std::make_shared<PluginFieldsArgs>();
  CLI::App* fields =
      plugin->add_subcommand("fields", "Print the JSON fields of primitive plugins, from their field tables");
  fields->add_option("type", fields_args->types, "Primitive types (default: every plugin found)");
  fields->add_flag("--markdown", fields_args->markdown, "The table of docs/scene-format.md, in Markdown");
  return [args, fields_args, check] {
    return check->parsed() ? run_plugin_check(*args) : run_plugin_fields(*fields_args);
  };
}

}  // namespace prism::cli
