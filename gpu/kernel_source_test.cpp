// The kernel generator leaves out what a scene does not use: intersectors of
// absent primitive types and features the scene never needs.
#include <gtest/gtest.h>

#include <algorithm>
#include <regex>
#include <set>
#include <sstream>

#include "kernel_source.hpp"
#include "prism/errors.hpp"
#include "prism/scene_loader.hpp"
#include "prism/sdk/shared_source.hpp"

namespace prism::gpu {
namespace {

bool has(const std::vector<std::string>& v, const std::string& s) { return std::find(v.begin(), v.end(), s) != v.end(); }

Scene load(Registry& registry, const std::string& json) { return load_scene_from_string(json, ".", registry); }

const char* kSpheresOnly = R"({"prism": 1, "camera": {"position": [0, 0, 5], "look_at": [0, 0, 0]},
  "objects": [{"type": "sphere", "radius": 1}, {"type": "sphere", "center": [2, 0, 0], "radius": 0.5}]})";

TEST(KernelSource, SphereOnlySceneCarriesNoTorusCode) {
  Registry registry;
  Scene scene = load(registry, kSpheresOnly);
  PackedScene packed = pack_scene(scene);
  KernelSource kernel = generate_kernel(packed, {});
  EXPECT_NE(kernel.text.find("sphere_intersect"), std::string::npos);
  // The torus plugin's GLSL names all start with its prefix.
  for (const char* symbol : {"torus_", "TORUS_", "quadric_", "box_", "plane_", "ring_", "cylinder_", "cone_"})
    EXPECT_EQ(kernel.text.find(symbol), std::string::npos) << symbol;
  EXPECT_EQ(kernel.features, std::vector<std::string>{"primitive:sphere"});
}

TEST(KernelSource, OnlyTheFeaturesUsedAreDefined) {
  Registry registry;
  Scene scene = load(registry, R"({"prism": 1, "camera": {"position": [0, 0, 5], "look_at": [0, 0, 0]},
    "materials": {"glass": {"ior": 1.5, "absorb": [0.1, 0, 0]}, "shiny": {"specular": 0.5}},
    "lights": [{"type": "point", "position": [0, 5, 0], "radius": 0.1}],
    "objects": [{"type": "sphere", "radius": 1, "material": "glass"},
                {"type": "sphere", "radius": 1, "center": [3, 0, 0], "material": "shiny"}]})");
  KernelSource kernel = generate_kernel(pack_scene(scene), {});
  for (const char* f : {"point_lights", "light_spheres", "dielectrics", "absorption", "specular"})
    EXPECT_TRUE(has(kernel.features, f)) << f;
  for (const char* f : {"directional_lights", "reflection", "textures", "alpha", "skybox"})
    EXPECT_FALSE(has(kernel.features, f)) << f;
  EXPECT_NE(kernel.text.find("#define PRISM_FEATURE_DIELECTRICS 1"), std::string::npos);
  EXPECT_EQ(kernel.text.find("#define PRISM_FEATURE_TEXTURES"), std::string::npos);
}

TEST(KernelSource, ForcedFeaturesCompileEverythingIn) {
  Registry registry;
  Scene scene = load(registry, kSpheresOnly);
  KernelOptions options;
  options.all_features = true;
  KernelSource kernel = generate_kernel(pack_scene(scene), options);
  for (Feature f : all_features()) EXPECT_NE(kernel.text.find("#define " + feature_macro(f) + " 1"), std::string::npos);
}

// An unrolled kernel tests an object without rotation without multiplying
// by the identity (as the CPU's to_local skips it), a rotated one with it.
TEST(KernelSource, UnrolledObjectsSkipTheIdentityRotation) {
  Registry registry;
  Scene scene = load(registry, R"({"prism": 1, "camera": {"position": [0, 0, 5], "look_at": [0, 0, 0]},
    "objects": [{"type": "sphere", "radius": 1},
                {"type": "box", "half_size": [1, 1, 1], "center": [3, 0, 0], "rotation": {"axis": [0, 1, 0], "degrees": 30}}]})");
  PackedScene packed = pack_scene(scene);
  ASSERT_TRUE(packed.unrolled);
  const std::string text = generate_kernel(packed, {}).text;
  const auto calls = [&](const char* pattern) { return std::regex_search(text, std::regex(pattern)); };
  EXPECT_TRUE(calls(R"(sphere_intersect\(\d+u, prism_to_local_unrotated\()"));
  EXPECT_TRUE(calls(R"(box_intersect\(\d+u, prism_to_local\()"));
  EXPECT_FALSE(calls(R"(box_intersect\(\d+u, prism_to_local_unrotated\()"));
  EXPECT_TRUE(calls(R"(sphere_surface\(\d+u, prism_to_local_unrotated\()"));
  EXPECT_TRUE(calls(R"(box_surface\(\d+u, prism_to_local\()"));
  EXPECT_TRUE(calls(R"(each = prism_to_world_unrotated\(0u)"));
  EXPECT_TRUE(calls(R"(each = prism_to_world\(1u)"));
}

// Texels through a buffer texture when the backend says they fit, else
// through the storage buffer.
TEST(KernelSource, TexelSamplerIsDefinedOnlyWhenAsked) {
  Registry registry;
  PackedScene packed = pack_scene(load(registry, kSpheresOnly));
  KernelOptions options;
  EXPECT_EQ(generate_kernel(packed, options).text.find("#define PRISM_TEXEL_SAMPLER"), std::string::npos);
  options.texel_sampler = true;
  EXPECT_NE(generate_kernel(packed, options).text.find("#define PRISM_TEXEL_SAMPLER 1\n"), std::string::npos);
}

// Materials in a uniform block sized by the scene's material count (the
// default material included) when the backend says they fit.
TEST(KernelSource, MaterialBlockIsSizedByTheMaterials) {
  Registry registry;
  PackedScene packed = pack_scene(load(registry, R"({"prism": 1, "camera": {"position": [0, 0, 5], "look_at": [0, 0, 0]},
    "materials": {"red": {"color": [1, 0, 0]}, "blue": {"color": [0, 0, 1]}},
    "objects": [{"type": "sphere", "radius": 1, "material": "red"}, {"type": "sphere", "radius": 1, "center": [2, 0, 0], "material": "blue"}]})"));
  ASSERT_EQ(packed.materials.size(), 3u);
  KernelOptions options;
  EXPECT_EQ(generate_kernel(packed, options).text.find("#define PRISM_MATERIAL_BLOCK"), std::string::npos);
  options.material_block = true;
  const std::string text = generate_kernel(packed, options).text;
  EXPECT_NE(text.find("#define PRISM_MATERIAL_BLOCK 1\n#define PRISM_MATERIAL_COUNT 3\n"), std::string::npos);
}

TEST(KernelSource, TraceKernelLeavesShadingOut) {
  Registry registry;
  Scene scene = load(registry, kSpheresOnly);
  KernelOptions options;
  options.trace = true;
  KernelSource kernel = generate_kernel(pack_scene(scene), options);
  EXPECT_NE(kernel.text.find("#define PRISM_MODE_TRACE 1"), std::string::npos);
  EXPECT_EQ(kernel.text.find("===== gpu/shading.glsl"), std::string::npos);
  EXPECT_EQ(kernel.text.find("vec3 prism_local_light("), std::string::npos);
}

// The counterpart of TraceKernelLeavesShadingOut: a render kernel has the
// shading section that test looks for by name, so that test cannot pass by a
// misspelt section title.
TEST(KernelSource, RenderKernelHasShadingSection) {
  Registry registry;
  Scene scene = load(registry, kSpheresOnly);
  KernelSource kernel = generate_kernel(pack_scene(scene), KernelOptions{});
  EXPECT_NE(kernel.text.find("===== gpu/shading.glsl"), std::string::npos);
}

// A float world: the world and the plugins' float instantiation, defined
// before the prelude reads them; a double world defines neither.
TEST(KernelSource, FloatWorldDefinesRealFloatBeforeThePrelude) {
  Registry registry;
  Scene scene = load(registry, kSpheresOnly);
  PackedScene packed = pack_scene(scene);
  set_world(packed, true, glm::dvec3(1, 2, 3));
  const std::string text = generate_kernel(packed, KernelOptions{}).text;
  const size_t prelude = text.find("===== core/glsl/prelude.glsl");
  ASSERT_NE(prelude, std::string::npos);
  for (const char* define : {"#define PRISM_REAL_FLOAT 1", "#define PRISM_WORLD_FLOAT 1"}) {
    ASSERT_NE(text.find(define), std::string::npos) << define;
    EXPECT_LT(text.find(define), prelude) << define;
  }
  set_world(packed, false);
  const std::string double_text = generate_kernel(packed, KernelOptions{}).text;
  EXPECT_EQ(double_text.find("PRISM_REAL_FLOAT 1"), std::string::npos);
  EXPECT_EQ(double_text.find("PRISM_WORLD_FLOAT 1"), std::string::npos);
}

// A plugin whose GLSL is not in the shared dialect has no float
// instantiation (ABI 4: intersect_float is intersect): a float kernel is
// refused by name instead of failing to compile.
TEST(KernelSource, FloatKernelNamesAPluginWithoutAFloatInstantiation) {
  Registry registry;
  Scene scene = load(registry, kSpheresOnly);
  PackedScene packed = pack_scene(scene);
  ASSERT_EQ(packed.types.size(), 1u);
  PrismPrimitiveDesc double_only = *packed.types[0];
  double_only.intersect_float = double_only.intersect;
  packed.types[0] = &double_only;
  set_world(packed, true, glm::dvec3(0));
  try {
    generate_kernel(packed, KernelOptions{});
    FAIL() << "a float kernel was generated";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("primitive plugin 'sphere' has no float instantiation"), std::string::npos)
        << e.what();
  }
  set_world(packed, false);
  EXPECT_NO_THROW(generate_kernel(packed, KernelOptions{}));
}

// The one parser of `// prism:require` lines (kernel generator,
// plugin_testing.hpp and scripts/check_plugin_glsl.sh all use it).
TEST(RequiredModules, LinesOfTheirOwnInOrderEachOnce) {
  const auto found = sdk::required_modules(
      "// the quadric: see // prism:require roots in prose\n// prism:require quadric\n"
      "//\n// prism:require roots  \r\n// prism:require quadric\nbool f();\n");
  EXPECT_EQ(found.problem, "");
  EXPECT_EQ(found.modules, (std::vector<std::string>{"quadric", "roots"}));
}

TEST(RequiredModules, AMalformedDirectiveIsAProblemNotAComment) {
  for (const char* text : {"// prism:require\n", "// prism:require quad-ric\n", "// prism:requirequadric\n",
                           "// prism:require quadric roots\n"})
    EXPECT_NE(sdk::required_modules(text).problem, "") << text;
  EXPECT_TRUE(sdk::required_modules("// prism:require quadric roots\n").modules.empty());
}

TEST(KernelSource, HashIsFnv1a64) {
  // FNV-1a 64 test vectors (Fowler/Noll/Vo reference values).
  EXPECT_EQ(hash_hex(""), "cbf29ce484222325");
  EXPECT_EQ(hash_hex("a"), "af63dc4c8601ec8c");
}

// A compiler error inside a plugin's section is blamed on that plugin, with
// the line counted in the plugin's own source; elsewhere nothing is blamed.
TEST(KernelSource, CompileErrorsAreBlamedOnThePluginTheyAreIn) {
  Registry registry;
  const std::string text = generate_kernel(pack_scene(load(registry, kSpheresOnly)), {}).text;
  const size_t marker = text.find("// ===== plugin sphere ");
  ASSERT_NE(marker, std::string::npos);
  const long marker_line = 1 + long(std::count(text.begin(), text.begin() + long(marker), '\n'));
  const std::string line = std::to_string(marker_line + 3);
  const std::string blame = "the GLSL of primitive plugin 'sphere' (line 3 of its source)";
  EXPECT_EQ(blame_compile_error(text, "0:" + line + "(7): error: syntax error"), blame);     // Mesa
  EXPECT_EQ(blame_compile_error(text, "ERROR: kernel:" + line + ": 'x' : syntax error"), blame);  // glslang
  EXPECT_EQ(blame_compile_error(text, "0:3(1): error: in the header"), "");
  EXPECT_EQ(blame_compile_error(text, "error without a line"), "");
}

// Writes of a vector component at a computed index (`v[i] = ...` with v a
// vector): NVIDIA's OpenGL compiler cannot link them in a double kernel
// (C9999 __setVectorIndex). Reads are fine. Returns each offending line.
std::vector<std::string> vector_writes_at_computed_index(const std::string& text) {
  std::set<std::string> vectors;
  // Vectors, not arrays of them (`vec4 pixels[]`).
  const std::regex declaration(R"(\b(?:w?real[234]|[dbiu]?vec[234]|wvec[234])\s+(\w+)\b(?!\s*\[))");
  for (auto it = std::sregex_iterator(text.begin(), text.end(), declaration); it != std::sregex_iterator(); ++it)
    vectors.insert((*it)[1]);
  std::vector<std::string> found;
  // A variable, not a struct's member (`q.c[i]`, an array).
  const std::regex write(R"((?:^|[^.\w])(\w+)\s*\[([^\]]+)\]\s*[-+*/]?=[^=])");
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    std::smatch m;
    for (std::string rest = line; std::regex_search(rest, m, write); rest = m.suffix().str()) {
      const bool literal_index = std::regex_match(m[2].str(), std::regex(R"(\s*\d+u?\s*)"));
      if (vectors.count(m[1]) && !literal_index) found.push_back(line);
    }
  }
  return found;
}

TEST(KernelPortability, TheCheckFindsAVectorWriteAtAComputedIndex) {
  const std::string text = "real3 p = q;\nfor (int i = 0; i < 3; ++i) p[i] = 0.0;\nreal3 n; n[2] = 1.0;\nreal c[10];\n"
                           "c[i] = 1.0;\nreal x = p[i];\nn[a] += 2.0;\n";
  const std::vector<std::string> found = vector_writes_at_computed_index(text);
  ASSERT_EQ(found.size(), 2u);
  EXPECT_NE(found[0].find("p[i] = 0.0"), std::string::npos);
  EXPECT_NE(found[1].find("n[a] += 2.0"), std::string::npos);
}

// Every built-in primitive's GLSL, the modules and the kernel, in both worlds.
TEST(KernelPortability, NoKernelWritesAVectorComponentAtAComputedIndex) {
  Registry registry;
  for (const char* file : {"scenes/showcase.json", "scenes/conformance/quadric.json", "scenes/conformance/far_camera.json"}) {
    Scene scene = load_scene(std::string(PRISM_SOURCE_DIR) + "/" + file, registry);
    KernelOptions options;
    options.all_features = true;
    for (bool trace : {false, true}) {
      options.trace = trace;
      const std::vector<std::string> found = vector_writes_at_computed_index(generate_kernel(pack_scene(scene), options).text);
      EXPECT_TRUE(found.empty()) << file << ": " << (found.empty() ? "" : found[0]);
    }
  }
}

}  // namespace
}  // namespace prism::gpu
