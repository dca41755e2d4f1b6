// Engine and Renderer (prism/api.hpp). A Renderer remembers which scene its
// backend was prepared with and the scene's revision then; before each
// render it hands the backend only the parts stamped later (SceneChanges).
#include <algorithm>

#include "api_state.hpp"
#include "prism/errors.hpp"
#include "prism/image_io.hpp"
#include "prism/registry.hpp"
#include "prism/scene_loader.hpp"

namespace prism {

// ---- Engine

Engine::Engine() : registry_(std::make_unique<Registry>()) {}
Engine::Engine(std::vector<std::filesystem::path> plugin_path)
    : registry_(std::make_unique<Registry>(std::move(plugin_path))) {}
Engine::~Engine() = default;

std::vector<std::string> Engine::primitive_types() const { return registry_->primitive_types_found(); }
std::vector<std::string> Engine::backends() const { return registry_->backend_names_found(); }
std::string Engine::auto_backend() const { return pick_auto_backend(*registry_); }

// ---- Renderer

struct Renderer::Impl {
  OpenedBackend opened;
  uint64_t scene_serial = 0;  // 0: not prepared
  uint64_t seen_revision = 0;
};

Renderer::Renderer(Engine& engine, const std::string& backend, Precision precision)
    : impl_(std::make_unique<Impl>(Impl{open_backend(engine.registry(), backend)})) {
  impl_->opened.backend->set_precision(precision);
}
Renderer::~Renderer() = default;

const std::string& Renderer::backend_name() const { return impl_->opened.name; }

namespace {

// What changed in `s` after revision `seen`.
SceneChanges changes_since(const LiveScene::State& s, uint64_t seen) {
  SceneChanges changes;
  changes.objects_added_or_removed = s.structure_stamp > seen;
  if (!changes.objects_added_or_removed)
    for (size_t i = 0; i < s.object_stamp.size(); ++i)
      if (s.object_stamp[i] > seen) changes.objects.push_back(uint32_t(i));
  changes.materials = s.materials_stamp > seen;
  changes.lights = s.lights_stamp > seen;
  changes.textures = s.textures_stamp > seen;
  changes.environment = s.environment_stamp > seen;
  return changes;
}

RenderSettings settings_for(const Scene& scene) {
  RenderSettings settings;
  settings.image = scene.image;
  settings.camera = scene.camera;
  return settings;
}

}  // namespace

void Renderer::sync(const LiveScene& scene) {
  const LiveScene::State& s = scene.state();
  Backend& backend = *impl_->opened.backend;
  if (impl_->scene_serial != s.serial) {
    impl_->scene_serial = 0;  // a prepare that throws leaves the renderer unprepared
    backend.prepare(s.scene);
    impl_->scene_serial = s.serial;
  } else if (s.revision > impl_->seen_revision) {
    const SceneChanges changes = changes_since(s, impl_->seen_revision);
    if (changes.any()) {
      impl_->scene_serial = 0;  // likewise for an update
      backend.update(s.scene, changes);
      impl_->scene_serial = s.serial;
    }
  }
  impl_->seen_revision = s.revision;
}

Image Renderer::render(const LiveScene& scene) { return render(scene, RenderOptions{}); }

Image Renderer::render(const LiveScene& scene, const RenderOptions& options) {
  RenderSettings settings = settings_for(scene.scene());
  settings.image.width = options.width.value_or(settings.image.width);
  settings.image.height = options.height.value_or(settings.image.height);
  settings.image.spp = options.spp.value_or(settings.image.spp);
  settings.image.max_depth = options.max_depth.value_or(settings.image.max_depth);
  check_image_settings(settings.image, "render().");
  settings.aov_id = options.aov_id;
  settings.aov_path = options.aov_path;
  settings.aov_depth = options.aov_depth;
  settings.aov_normal = options.aov_normal;
  settings.aov_albedo = options.aov_albedo;
  sync(scene);
  return impl_->opened.backend->render(settings);
}

void Renderer::render_into(const LiveScene& scene, std::span<float> rgb) {
  const ImageSettings& image = scene.scene().image;
  const size_t needed = size_t(image.width) * size_t(image.height) * 3;
  if (rgb.size() != needed)
    throw InputError("render_into(): the buffer holds " + std::to_string(rgb.size()) + " floats; a " +
                     std::to_string(image.width) + "x" + std::to_string(image.height) + " image needs " +
                     std::to_string(needed));
  const Image rendered = render(scene);
  std::ranges::copy(rendered.rgb, rgb.begin());
}

void Renderer::render_to_file(const LiveScene& scene, const std::filesystem::path& file) {
  check_output_path(file, {".png", ".exr"});
  write_image(render(scene), file);
}

std::vector<TraceResult> Renderer::trace(const LiveScene& scene, std::span<const TraceQuery> rays) {
  sync(scene);
  return impl_->opened.backend->trace(rays);
}

UpdateCounters Renderer::counters() const {
  const BackendStats stats = impl_->opened.backend->stats();
  const auto count = [&](const char* name) {
    auto it = stats.counters.find(name);
    return it == stats.counters.end() ? uint64_t(0) : uint64_t(it->second);
  };
  return {count(counter::kPrepares),   count(counter::kUpdates),    count(counter::kObjectsUploaded),
          count(counter::kBvhBuilds),  count(counter::kBvhRefits),  count(counter::kKernelBuilds)};
}

BackendStats Renderer::stats() const { return impl_->opened.backend->stats(); }

}  // namespace prism
