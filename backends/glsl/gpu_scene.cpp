#include "gpu_scene.hpp"

#include <cmath>
#include <cstring>
#include <limits>
#include <map>

#include "prism/camera.hpp"
#include "prism/errors.hpp"
#include "prism/registry.hpp"

namespace prism::gpu {

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

struct Packer {
  const Scene& scene;
  PackedScene out;
  std::vector<int32_t> texture_offset;  // per scene texture: first texel
  std::map<const PrismPrimitiveDesc*, uint32_t> type_index;

  void pack_textures() {
    for (const Texture& t : scene.textures) {
      texture_offset.push_back(int32_t(out.texels.size()));
      out.texels.insert(out.texels.end(), t.texels.begin(), t.texels.end());
    }
  }

  void texture_ref(int index, int32_t ref[4]) {
    ref[0] = index < 0 ? -1 : texture_offset[size_t(index)];
    ref[1] = index < 0 ? 0 : scene.textures[size_t(index)].width;
    ref[2] = index < 0 ? 0 : scene.textures[size_t(index)].height;
    ref[3] = 0;
  }

  void pack_materials() {
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
      texture_ref(m.texture, g.texture);
      out.materials.push_back(g);
    }
  }

  void note_material_features(const Material& m) {
    if (m.specular > 0) out.features.insert(Feature::Specular);
    if (m.dielectric()) {
      out.features.insert(Feature::Dielectrics);
      if (m.absorb != glm::dvec3(0.0)) out.features.insert(Feature::Absorption);
      return;  // a dielectric's own colour, texture and reflect are ignored
    }
    if (m.reflect > 0) out.features.insert(Feature::Reflection);
    if (m.texture >= 0) {
      out.features.insert(Feature::Textures);
      if (has_transparent_texel(scene.textures[size_t(m.texture)])) out.features.insert(Feature::Alpha);
    }
  }

  void pack_lights() {
    for (const Light& l : scene.lights) {
      GpuLight g{};
      bool directional = l.type == Light::Type::Directional;
      store4(directional ? l.direction : l.position, l.radius, g.position);
      store3f(l.color, g.color);
      g.intensity = float(l.intensity);
      g.linear = float(l.linear);
      g.quadratic = float(l.quadratic);
      g.directional = directional ? 1u : 0u;
      out.lights.push_back(g);
      out.features.insert(directional ? Feature::DirectionalLights : Feature::PointLights);
      if (l.visible_sphere()) out.features.insert(Feature::LightSpheres);
    }
  }

  uint32_t type_of(const Object& object, size_t id) {
    auto [it, added] = type_index.try_emplace(object.desc, uint32_t(out.types.size()));
    if (added) {
      if (!object.desc->glsl_source || !object.desc->glsl_prefix)
        throw RuntimeError("objects[" + std::to_string(id) + "]: the " + object.desc->type_name +
                           " plugin has no GLSL intersector, so GPU backends cannot render it");
      out.types.push_back(object.desc);
    }
    return it->second;
  }

  GpuObject pack_object(size_t id) {
    const Object& object = scene.objects[id];
    GpuObject g{};
    store4(object.center, 0.0, g.center);
    for (int c = 0; c < 3; ++c) store4(object.rotation[c], 0.0, g.columns[c]);
    g.rotated = object.has_rotation ? 1u : 0u;
    g.type = type_of(object, id);
    g.material = uint32_t(object.material);
    g.id = int32_t(id);
    g.record = uint32_t(out.records.size());
    const auto* record = static_cast<const double*>(object.record());
    out.records.insert(out.records.end(), record, record + object.desc->record_size / sizeof(double));
    note_material_features(scene.materials[size_t(object.material)]);
    return g;
  }

  void pack_objects() {
    std::vector<Box3> boxes;
    std::vector<size_t> bounded, unbounded;
    for (size_t id = 0; id < scene.objects.size(); ++id) {
      (scene.objects[id].bounded ? bounded : unbounded).push_back(id);
      if (scene.objects[id].bounded) boxes.push_back(scene.objects[id].world_bounds);
    }
    Bvh bvh = build_bvh(boxes);
    for (uint32_t i : bvh.order) out.objects.push_back(pack_object(bounded[i]));
    for (size_t id : unbounded) out.objects.push_back(pack_object(id));
    for (const BvhNode& n : bvh.nodes) {
      GpuNode g{};
      for (int a = 0; a < 3; ++a) {
        g.lo[a] = round_down(n.bounds.lo[a]);
        g.hi[a] = round_up(n.bounds.hi[a]);
      }
      g.first = n.first;
      g.count = n.count;
      out.nodes.push_back(g);
    }
    out.bounded_objects = int(bounded.size());
    out.bvh_depth = bvh.depth;
  }

  void pack_background() {
    GpuFrame& f = out.frame;
    store3f(scene.ambient, f.ambient);
    store3f(scene.shadow_ambient, f.shadow_ambient);
    store3f(scene.background.color, f.background);
    for (int face = 0; face < 6; ++face) texture_ref(scene.background.cubemap[size_t(face)], f.cubemap[face]);
    if (scene.background.has_cubemap()) out.features.insert(Feature::Skybox);
  }
};

}  // namespace

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

PackedScene pack_scene(const Scene& scene) {
  Packer p{scene, {}, {}, {}};
  p.pack_textures();
  p.pack_materials();
  p.pack_lights();
  p.pack_objects();
  p.pack_background();
  GpuFrame& f = p.out.frame;
  f.counts[0] = int32_t(p.out.objects.size());
  f.counts[1] = p.out.bounded_objects;
  f.counts[2] = int32_t(p.out.lights.size());
  f.counts[3] = int32_t(p.out.nodes.size());
  return std::move(p.out);
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
  return f;
}

std::vector<glm::dvec2> sample_offsets(int spp) {
  std::vector<glm::dvec2> offsets;
  for (int k = 0; k < spp; ++k) offsets.push_back(sample_offset(k));
  return offsets;
}

}  // namespace prism::gpu
