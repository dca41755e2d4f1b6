#include "gpu_scene.hpp"

#include <cmath>
#include <cstring>

#include <limits>
#include <map>
#include <stdexcept>

#include "gpu_pack.hpp"
#include "prism/camera.hpp"
#include "prism/errors.hpp"
#include "prism/registry.hpp"

namespace prism::gpu {

size_t unrolled_objects_limit() {
  static const auto limit = size_t(env_number("PRISM_GPU_UNROLLED_OBJECTS", double(kUnrolledObjects), 0.0, 64.0));
  return limit;
}

namespace {

struct FeatureInfo {
  Feature feature;
  const char* name;
  const char* macro;
};

constexpr FeatureInfo kFeatures[] = {
    {Feature::PointLights, "point_lights", "PRISM_FEATURE_POINT_LIGHTS"},
    {Feature::DirectionalLights, "directional_lights", "PRISM_FEATURE_DIRECTIONAL_LIGHTS"},
    {Feature::LightSpheres, "light_spheres", "PRISM_FEATURE_LIGHT_SPHERES"},
    {Feature::Specular, "specular", "PRISM_FEATURE_SPECULAR"},
    {Feature::Reflection, "reflection", "PRISM_FEATURE_REFLECTION"},
    {Feature::Dielectrics, "dielectrics", "PRISM_FEATURE_DIELECTRICS"},
    {Feature::Absorption, "absorption", "PRISM_FEATURE_ABSORPTION"},
    {Feature::Textures, "textures", "PRISM_FEATURE_TEXTURES"},
    {Feature::Alpha, "alpha", "PRISM_FEATURE_ALPHA"},
    {Feature::Skybox, "skybox", "PRISM_FEATURE_SKYBOX"},
};

const FeatureInfo& info(Feature f) {
  for (const FeatureInfo& i : kFeatures)
    if (i.feature == f) return i;
  return kFeatures[0];
}

void store4(const glm::dvec3& v, double w, double out[4]) {
  out[0] = v.x;
  out[1] = v.y;
  out[2] = v.z;
  out[3] = w;
}

void store3f(const glm::dvec3& v, float out[3]) {
  out[0] = float(v.x);
  out[1] = float(v.y);
  out[2] = float(v.z);
}

// Float bounds that contain the double ones, so traversal never culls a true hit.
float round_down(double x) {
  float f = float(x);
  return double(f) > x ? std::nextafter(f, -std::numeric_limits<float>::infinity()) : f;
}
float round_up(double x) {
  float f = float(x);
  return double(f) < x ? std::nextafter(f, std::numeric_limits<float>::infinity()) : f;
}

bool has_transparent_texel(const Texture& texture) {
  for (const glm::vec4& t : texture.texels)
    if (t.a < 1.0f) return true;
  return false;
}

void texture_ref(const Scene& scene, const PackedScene& packed, int index, int32_t ref[4]) {
  ref[0] = index < 0 ? -1 : packed.texture_offset[size_t(index)];
  ref[1] = index < 0 ? 0 : scene.textures[size_t(index)].width;
  ref[2] = index < 0 ? 0 : scene.textures[size_t(index)].height;
  ref[3] = 0;
}

void note_material_features(const Material& m, bool transparent_texture, std::set<Feature>& out) {
  if (m.specular > 0) out.insert(Feature::Specular);
  if (m.dielectric()) {
    out.insert(Feature::Dielectrics);
    if (m.absorb != glm::dvec3(0.0)) out.insert(Feature::Absorption);
    return;  // a dielectric's own colour, texture and reflect are ignored
  }
  if (m.reflect > 0) out.insert(Feature::Reflection);
  if (m.texture >= 0) {
    out.insert(Feature::Textures);
    if (transparent_texture) out.insert(Feature::Alpha);
  }
}

// The kernel type index of each desc the scene uses: `type_order`'s first,
// then the rest in the order the BVH's leaves meet them.
struct TypeTable {
  std::vector<const PrismPrimitiveDesc*> types;
  std::map<const PrismPrimitiveDesc*, uint32_t> index;

  uint32_t of(const Object& object, size_t id) {
    auto [it, added] = index.try_emplace(object.desc, uint32_t(types.size()));
    if (added) {
      if (!object.desc->glsl_source || !object.desc->glsl_prefix)
        throw RuntimeError("objects[" + std::to_string(id) + "]: the " + object.desc->type_name +
                           " plugin has no GLSL intersector, so GPU backends cannot render it");
      types.push_back(object.desc);
    }
    return it->second;
  }
};

void seed_types(const Scene& scene, std::span<const PrismPrimitiveDesc* const> type_order, TypeTable& table) {
  if (type_order.empty()) return;
  std::set<const PrismPrimitiveDesc*> used;
  for (const Object& o : scene.objects) used.insert(o.desc);
  for (const PrismPrimitiveDesc* desc : type_order)
    if (used.count(desc) && desc->glsl_source && desc->glsl_prefix && !table.index.count(desc)) {
      table.index.emplace(desc, uint32_t(table.types.size()));
      table.types.push_back(desc);
    }
}

}  // namespace

namespace detail {

void pack_objects(const Scene& scene, std::span<const PrismPrimitiveDesc* const> type_order, PackedScene& out) {
  out.records.clear();
  out.objects.clear();
  out.nodes.clear();
  out.boxes.clear();
  out.bounded_ids.clear();
  TypeTable table;
  seed_types(scene, type_order, table);
  std::vector<uint32_t> unbounded;
  for (size_t id = 0; id < scene.objects.size(); ++id) {
    if (!scene.objects[id].bounded) {
      unbounded.push_back(uint32_t(id));
      continue;
    }
    out.bounded_ids.push_back(uint32_t(id));
    out.boxes.push_back(scene.objects[id].world_bounds);
  }
  out.bvh = build_bvh(out.boxes);
  std::vector<uint32_t> slots;
  for (uint32_t i : out.bvh.order) slots.push_back(out.bounded_ids[i]);
  slots.insert(slots.end(), unbounded.begin(), unbounded.end());
  out.slot_of.assign(scene.objects.size(), 0);
  for (uint32_t id : slots) {
    const Object& object = scene.objects[id];
    out.slot_of[id] = uint32_t(out.objects.size());
    out.objects.push_back(detail::object_entry(object, id, table.of(object, id), uint32_t(out.records.size())));
    const auto* record = static_cast<const double*>(object.record());
    out.records.insert(out.records.end(), record, record + object.desc->record_size / sizeof(double));
  }
  for (const BvhNode& n : out.bvh.nodes) out.nodes.push_back(detail::node_entry(n));
  out.types = std::move(table.types);
  out.bounded_objects = int(out.bounded_ids.size());
  out.bvh_depth = out.bvh.depth;
  out.unrolled = out.objects.size() <= unrolled_objects_limit();
}

void pack_textures(const Scene& scene, PackedScene& out) {
  out.texels.clear();
  out.texture_offset.clear();
  out.texture_alpha.clear();
  for (const Texture& t : scene.textures) {
    out.texture_offset.push_back(int32_t(out.texels.size()));
    out.texture_alpha.push_back(has_transparent_texel(t) ? 1 : 0);
    out.texels.insert(out.texels.end(), t.texels.begin(), t.texels.end());
  }
}

std::vector<GpuMaterial> pack_materials(const Scene& scene, const PackedScene& packed) {
  std::vector<GpuMaterial> out;
  for (const Material& m : scene.materials) {
    GpuMaterial g{};
    store3f(m.color, g.color);
    g.diffuse = float(m.diffuse);
    store3f(m.absorb, g.absorb);
    g.specular = float(m.specular);
    g.shininess = float(m.shininess);
    g.reflect = float(m.reflect);
    g.ior = float(m.ior);
    g.uv_scale[0] = float(m.uv_scale.x);
    g.uv_scale[1] = float(m.uv_scale.y);
    g.uv_offset[0] = float(m.uv_offset.x);
    g.uv_offset[1] = float(m.uv_offset.y);
    texture_ref(scene, packed, m.texture, g.texture);
    out.push_back(g);
  }
  return out;
}

std::vector<GpuLight> pack_lights(const Scene& scene) {
  std::vector<GpuLight> out;
  for (const Light& l : scene.lights) {
    GpuLight g{};
    bool directional = l.type == Light::Type::Directional;
    store4(directional ? l.direction : l.position, l.radius, g.position);
    store3f(l.color, g.color);
    g.intensity = float(l.intensity);
    g.linear = float(l.linear);
    g.quadratic = float(l.quadratic);
    g.directional = directional ? 1u : 0u;
    out.push_back(g);
  }
  return out;
}

void pack_environment(const Scene& scene, PackedScene& out) {
  GpuFrame& f = out.frame;
  store3f(scene.ambient, f.ambient);
  store3f(scene.shadow_ambient, f.shadow_ambient);
  store3f(scene.background.color, f.background);
  for (int face = 0; face < 6; ++face) texture_ref(scene, out, scene.background.cubemap[size_t(face)], f.cubemap[face]);
}

std::set<Feature> scene_features(const Scene& scene, const PackedScene& packed) {
  std::set<Feature> features;
  for (const Light& l : scene.lights) {
    features.insert(l.type == Light::Type::Directional ? Feature::DirectionalLights : Feature::PointLights);
    if (l.visible_sphere()) features.insert(Feature::LightSpheres);
  }
  if (scene.background.has_cubemap()) features.insert(Feature::Skybox);
  std::vector<bool> used(scene.materials.size(), false);
  for (const Object& o : scene.objects) used[size_t(o.material)] = true;
  for (size_t m = 0; m < used.size(); ++m) {
    if (!used[m]) continue;
    const Material& material = scene.materials[m];
    const bool transparent = material.texture >= 0 && packed.texture_alpha[size_t(material.texture)];
    note_material_features(material, transparent, features);
  }
  return features;
}

GpuObject object_entry(const Object& object, size_t id, uint32_t type, uint32_t record) {
  GpuObject g{};
  store4(object.center, 0.0, g.center);
  for (int c = 0; c < 3; ++c) store4(object.rotation[c], 0.0, g.columns[c]);
  g.rotated = object.has_rotation ? 1u : 0u;
  g.type = type;
  g.material = uint32_t(object.material);
  g.id = int32_t(id);
  g.record = record;
  return g;
}

GpuNode node_entry(const BvhNode& n, const glm::dvec3& anchor) {
  GpuNode g{};
  for (int a = 0; a < 3; ++a) {
    g.lo[a] = round_down(n.bounds.lo[a] - anchor[a]);
    g.hi[a] = round_up(n.bounds.hi[a] - anchor[a]);
  }
  g.first = n.first;
  g.count = n.count;
  return g;
}

void set_counts(PackedScene& out) {
  GpuFrame& f = out.frame;
  f.counts[0] = int32_t(out.objects.size());
  f.counts[1] = out.bounded_objects;
  f.counts[2] = int32_t(out.lights.size());
  f.counts[3] = int32_t(out.nodes.size());
}

}  // namespace detail

const std::vector<Feature>& all_features() {
  static const std::vector<Feature> features = [] {
    std::vector<Feature> v;
    for (const FeatureInfo& i : kFeatures) v.push_back(i.feature);
    return v;
  }();
  return features;
}

const char* feature_name(Feature f) { return info(f).name; }
std::string feature_macro(Feature f) { return info(f).macro; }

size_t PackedScene::buffer_bytes() const {
  const auto bytes = [](const auto& v) { return v.size() * sizeof(v[0]); };
  return bytes(records) + bytes(objects) + bytes(nodes) + bytes(materials) + bytes(lights) + bytes(texels);
}

PackedScene pack_scene(const Scene& scene, std::span<const PrismPrimitiveDesc* const> type_order) {
  PackedScene out;
  detail::pack_textures(scene, out);
  out.materials = detail::pack_materials(scene, out);
  out.lights = detail::pack_lights(scene);
  detail::pack_objects(scene, type_order, out);
  detail::pack_environment(scene, out);
  out.features = detail::scene_features(scene, out);
  detail::set_counts(out);
  return out;
}

std::vector<uint32_t> kernel_layout(const PackedScene& packed) {
  // The material count sizes the kernel's material block (KernelOptions::material_block).
  std::vector<uint32_t> layout{uint32_t(packed.lights.size()), uint32_t(packed.materials.size()), packed.unrolled ? 1u : 0u};
  if (!packed.unrolled) return layout;
  for (const GpuObject& o : packed.objects) layout.insert(layout.end(), {o.type, o.record, uint32_t(o.id), o.rotated});
  return layout;
}

SceneBuffer scene_buffer(const PackedScene& p, uint32_t binding) {
  if (p.float_world) {
    switch (binding) {
      case kBindRecords: return {p.records_f.data(), p.records_f.size(), sizeof(float), "object records"};
      case kBindObjects: return {p.objects_f.data(), p.objects_f.size(), sizeof(GpuObjectF), "objects"};
      case kBindNodes: return {p.nodes_f.data(), p.nodes_f.size(), sizeof(GpuNode), "BVH"};
      case kBindLights: return {p.lights_f.data(), p.lights_f.size(), sizeof(GpuLightF), "lights"};
      default: break;
    }
  }
  switch (binding) {
    case kBindRecords: return {p.records.data(), p.records.size(), sizeof(double), "object records"};
    case kBindObjects: return {p.objects.data(), p.objects.size(), sizeof(GpuObject), "objects"};
    case kBindNodes: return {p.nodes.data(), p.nodes.size(), sizeof(GpuNode), "BVH"};
    case kBindMaterials: return {p.materials.data(), p.materials.size(), sizeof(GpuMaterial), "materials"};
    case kBindLights: return {p.lights.data(), p.lights.size(), sizeof(GpuLight), "lights"};
    case kBindTexels: return {p.texels.data(), p.texels.size(), sizeof(glm::vec4), "texels"};
    default: throw std::invalid_argument("scene_buffer: binding " + std::to_string(binding) + " holds no scene data");
  }
}

int output_planes(const RenderSettings& settings) {
  const bool more = settings.aov_path || settings.aov_normal || settings.aov_albedo || settings.aov_depth;
  return more ? kMaxOutputPlanes : 1;
}

GpuFrame frame_for(const PackedScene& packed, const Camera& camera, const RenderSettings& settings) {
  GpuFrame f = packed.frame;
  store4(camera.position, 0.0, f.camera_position);
  store4(camera.forward, 0.0, f.camera_forward);
  store4(camera.right, 0.0, f.camera_right);
  store4(camera.up, 0.0, f.camera_up);
  const ImageSettings& s = settings.image;
  f.tan_half_fov = std::tan(glm::radians(camera.fov_y) * 0.5);
  f.aspect = double(s.width) / s.height;
  f.size[0] = s.width;
  f.size[1] = s.height;
  f.size[2] = s.spp;
  f.size[3] = s.max_depth;
  f.flags[0] = settings.aov_path ? 1 : 0;
  f.flags[2] = output_planes(settings) > 1 ? 1 : 0;
  return f;
}

namespace {

void relative4f(const double in[4], const glm::dvec3& anchor, float out[4]) {
  for (int a = 0; a < 3; ++a) out[a] = float(in[a] - anchor[a]);
  out[3] = float(in[3]);
}

void copy4f(const double in[4], float out[4]) {
  for (int a = 0; a < 4; ++a) out[a] = float(in[a]);
}

GpuObjectF float_object(const GpuObject& o, const glm::dvec3& anchor) {
  GpuObjectF f{};
  relative4f(o.center, anchor, f.center);
  for (int c = 0; c < 3; ++c) copy4f(o.columns[c], f.columns[c]);
  f.record = o.record;
  f.type = o.type;
  f.material = o.material;
  f.rotated = o.rotated;
  f.id = o.id;
  return f;
}

GpuLightF float_light(const GpuLight& l, const glm::dvec3& anchor) {
  GpuLightF f{};
  if (l.directional) copy4f(l.position, f.position);
  else relative4f(l.position, anchor, f.position);
  std::copy_n(l.color, 3, f.color);
  f.intensity = l.intensity;
  f.linear = l.linear;
  f.quadratic = l.quadratic;
  f.directional = l.directional;
  return f;
}

GpuFrameF float_frame(const GpuFrame& g, const glm::dvec3& anchor) {
  GpuFrameF f{};
  relative4f(g.camera_position, anchor, f.camera_position);
  copy4f(g.camera_forward, f.camera_forward);
  copy4f(g.camera_right, f.camera_right);
  copy4f(g.camera_up, f.camera_up);
  f.tan_half_fov = float(g.tan_half_fov);
  f.aspect = float(g.aspect);
  std::copy_n(g.ambient, 4, f.ambient);
  std::copy_n(g.shadow_ambient, 4, f.shadow_ambient);
  std::copy_n(g.background, 4, f.background);
  std::copy_n(g.size, 4, f.size);
  std::copy_n(g.counts, 4, f.counts);
  std::copy_n(g.flags, 4, f.flags);
  std::memcpy(f.cubemap, g.cubemap, sizeof f.cubemap);
  std::copy_n(g.anchor, 4, f.anchor);
  return f;
}

}  // namespace

void refresh_float_world(PackedScene& p) {
  if (!p.float_world) return;
  p.records_f.assign(p.records.begin(), p.records.end());
  p.objects_f.clear();
  for (const GpuObject& o : p.objects) p.objects_f.push_back(float_object(o, p.anchor));
  p.nodes_f.clear();
  for (const BvhNode& n : p.bvh.nodes) p.nodes_f.push_back(detail::node_entry(n, p.anchor));
  p.lights_f.clear();
  for (const GpuLight& l : p.lights) p.lights_f.push_back(float_light(l, p.anchor));
}

void set_world(PackedScene& p, bool float_world, const glm::dvec3& anchor) {
  p.float_world = float_world;
  p.anchor = float_world ? anchor : glm::dvec3(0);
  for (int a = 0; a < 3; ++a) p.frame.anchor[a] = float(p.anchor[a]);
  if (float_world) {
    refresh_float_world(p);
  } else {
    p.records_f.clear();
    p.objects_f.clear();
    p.nodes_f.clear();
    p.lights_f.clear();
  }
}

std::vector<unsigned char> frame_bytes(const PackedScene& packed, const GpuFrame& frame,
                                       const std::vector<glm::dvec2>& offsets) {
  std::vector<unsigned char> bytes;
  const auto append = [&](const void* data, size_t n) {
    const auto* b = static_cast<const unsigned char*>(data);
    bytes.insert(bytes.end(), b, b + n);
  };
  if (!packed.float_world) {
    append(&frame, sizeof frame);
    append(offsets.data(), offsets.size() * sizeof(glm::dvec2));
    return bytes;
  }
  const GpuFrameF f = float_frame(frame, packed.anchor);
  append(&f, sizeof f);
  for (const glm::dvec2& o : offsets) {
    const float pair[2] = {float(o.x), float(o.y)};
    append(pair, sizeof pair);
  }
  return bytes;
}

std::vector<glm::dvec2> sample_offsets(int spp) {
  std::vector<glm::dvec2> offsets;
  for (int k = 0; k < spp; ++k) offsets.push_back(sample_offset(k));
  return offsets;
}

}  // namespace prism::gpu
