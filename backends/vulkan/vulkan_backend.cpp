// The Vulkan backend: the scene-specialised GLSL kernel (gpu/),
// compiled to SPIR-V at run time with glslang, run as a compute pipeline on
// the chosen Vulkan 1.2 device. Scene data and the BVH sit in device-local
// storage buffers; the image is rendered tile by tile, each tile's pixels
// and ray counters copied to a staging buffer and read back before the next.
// A live update copies only the changed ranges in, through one staging buffer.
#include <algorithm>
#include <array>
#include <cstdio>
#include <cstring>
#include <memory>
#include <optional>

#include "gpu_dispatch.hpp"
#include "gpu_limits.hpp"
#include "precision.hpp"
#include "gpu_scene.hpp"
#include "gpu_update.hpp"
#include "kernel_source.hpp"
#include "prism/backend.hpp"
#include "prism/backend_fingerprint.hpp"
#include "prism/cancel.hpp"
#include "prism/errors.hpp"
#include "prism/status.hpp"
#include "vk_buffer.hpp"
#include "vk_context.hpp"
#include "vk_pipeline.hpp"

namespace prism {
namespace {

using gpu::GpuFrame;
using gpu::GpuTraceRay;
using gpu::ms_since;

// The Vulkan glue for the shared kernel: the tile origin is a push constant.
constexpr const char* kApiGlue =
    "layout(push_constant) uniform PrismPush { ivec4 tile; } prism_push;\n"
    "#define PRISM_TILE_ORIGIN prism_push.tile\n"
    "#define PRISM_BINDING_TEXEL_SAMPLER 8\n"
    "#define PRISM_BINDING_MATERIAL_BLOCK 9\n";
static_assert(vk::kTexelViewBinding == 8 && vk::kMaterialBlockBinding == 9, "the glue's bindings");

constexpr VkBufferUsageFlags kStorage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;

// A kernel's pipeline (null until built) and the descriptor set that binds
// the buffers to it (kept when an update drops the pipeline).
// A render's buffers, kept from one render to the next (allocating them is
// a good part of a frame on a GPU) and grown when a frame needs more: the
// frame's constants and their staging copy, the tile output and its
// host-visible readback copy.
struct FrameBuffers {
  vk::Buffer frame, frame_staging, output, readback;

  void reserve(const vk::Context& context, size_t frame_bytes, size_t output_bytes) {
    if (frame.size() < frame_bytes) {
      frame = vk::Buffer(context, frame_bytes, kStorage | VK_BUFFER_USAGE_TRANSFER_DST_BIT, vk::Memory::Device,
                         "allocation of the frame constants");
      frame_staging = vk::Buffer(context, frame_bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, vk::Memory::Staging,
                                 "allocation of the frame constants");
    }
    if (output.size() < output_bytes) {
      output = vk::Buffer(context, output_bytes, kStorage | VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                          vk::Memory::Device, "allocation of the tile output");
      readback = vk::Buffer(context, output_bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, vk::Memory::Staging,
                            "allocation of the readback buffer");
    }
  }
};

struct Kernel {
  VkPipeline pipeline = VK_NULL_HANDLE;
  VkDescriptorSet descriptors = VK_NULL_HANDLE;
};

// Everything a prepared scene holds on the device.
struct DeviceScene {
  gpu::PackedScene packed;
  std::array<vk::Buffer, gpu::kSceneBufferCount> buffers;  // by binding
  // The texel buffer as texels, when they fit maxTexelBufferElements: the
  // kernels then read them through it (gpu::KernelOptions::texel_sampler).
  vk::TexelView texels;
  // The materials' bytes when the kernels read them as a uniform block (they
  // fit maxUniformBufferRange; gpu::KernelOptions::material_block), else 0.
  VkDeviceSize material_block = 0;
  Kernel render, trace;
};

class VulkanBackend : public Backend {
 public:
  VulkanBackend()
      : context_(std::make_unique<vk::Context>()),
        commands_(std::make_unique<vk::Commands>(*context_)),
        layout_(std::make_unique<vk::PipelineLayout>(*context_)) {
    stats_.info[info_key::kDevice] = context_->description();
    stats_.info[info_key::kValidation] = context_->validation() ? "on" : "off";
    stats_.counters[counter::kMaxStorageBufferBytes] = double(context_->properties().limits.maxStorageBufferRange);
    gpu::start_counters(stats_);
    create_descriptor_pool();
  }

  // A prepared scene is packed again in the world the new precision asks for.
  void set_precision(Precision precision) override {
    if (precision == precision_) return;
    precision_ = precision;
    if (scene_ && scene_model_) prepare(*scene_model_);
  }

  // A float world for `trace` is anchored where its rays start.
  void anchor_at(std::span<const TraceQuery> rays) {
    if (!scene_->packed.float_world) return;
    const glm::dvec3 anchor = gpu::trace_anchor(rays);
    if (anchor == scene_->packed.anchor) return;
    trace_anchor_ = anchor;
    prepare(*scene_model_);
  }

  // `prism trace` asks for arbitrary rays, a render for the camera's: with
  // automatic precision the two may want different worlds (gpu/precision.hpp).
  void use_world_for(bool tracing) {
    if (tracing == tracing_) return;
    tracing_ = tracing;
    if (scene_ && scene_model_ && world_for(*scene_model_).float_world != scene_->packed.float_world)
      prepare(*scene_model_);
  }

  // The world choice for `scene`: every world is float on a device without double.
  gpu::WorldChoice world_for(const Scene& scene) const {
    return gpu::choose_world(scene, precision_, tracing_, context_->has_float64());
  }

  ~VulkanBackend() override {
    release_scene();
    if (timestamps_ && !context_->abandoned()) context_->api().vkDestroyQueryPool(context_->device(), timestamps_, nullptr);
    if (!context_->abandoned()) context_->api().vkDestroyDescriptorPool(context_->device(), pool_, nullptr);
  }

  void prepare(const Scene& scene) override {
    auto start = std::chrono::steady_clock::now();
    scene_model_ = &scene;
    release_scene();
    reset_descriptor_pool();
    auto s = std::make_unique<DeviceScene>();
    s->packed = gpu::pack_scene(scene);
    gpu::WorldChoice world = world_for(scene);
    if (world.float_world && tracing_ && trace_anchor_) world.anchor = *trace_anchor_;
    gpu::set_world(s->packed, world.float_world, world.anchor);
    stats_.info[info_key::kPrecision] = world.description;
    stats_.info[info_key::kPrecisionObjects] = world.objects;
    if (world.warning.empty()) {
      stats_.info.erase(info_key::kPrecisionWarning);
    } else {
      stats_.info[info_key::kPrecisionWarning] = world.warning;
      if (world.warning != last_warning_) notify_status("vulkan: warning: " + world.warning);
    }
    last_warning_ = world.warning;
    const gpu::PackedScene& p = s->packed;
    check_limits(p, scene.source);
    for (uint32_t b = 0; b < gpu::kSceneBufferCount; ++b) s->buffers[b] = upload(gpu::scene_buffer(p, b));
    view_texels(*s);
    choose_material_block(*s);
    stats_.counters[counter::kSceneBytes] = double(p.buffer_bytes());
    gpu::count_prepare(stats_, p);
    scene_ = std::move(s);
    stats_.ms[ms_key::kBuild] = ms_since(start);
    check_validation("scene upload");
  }

  // Packs what changed in place and copies only that in; the pipelines are
  // kept unless the kernel's primitive types or features changed. A failure
  // leaves nothing prepared (the next render asks for a prepare).
  void update(const Scene& scene, const SceneChanges& changes) override {
    if (!scene_ || &scene != scene_model_) return prepare(scene);
    auto start = std::chrono::steady_clock::now();
    try {
      gpu::PackedScene& p = scene_->packed;
      const gpu::PackedUpdate u = gpu::update_packed_scene(p, scene, changes);
      check_limits(p, scene.source);
      std::vector<vk::BufferWrite> writes;
      for (uint32_t b = 0; b < gpu::kSceneBufferCount; ++b) {
        const gpu::SceneBuffer source = gpu::scene_buffer(p, b);
        if (u.buffers[b].whole && source.bytes() > scene_->buffers[b].size()) {
          scene_->buffers[b] = upload(source);
          continue;
        }
        for (const gpu::ByteRange& r : gpu::byte_ranges(source, u.buffers[b]))
          writes.push_back({&scene_->buffers[b], r.offset, r.data, r.size});
      }
      vk::write_storage(*context_, *commands_, writes, "update of the scene");
      const bool sampled = bool(scene_->texels), block = scene_->material_block != 0;
      view_texels(*scene_);
      choose_material_block(*scene_);
      if (u.kernel || sampled != bool(scene_->texels) || block != (scene_->material_block != 0)) drop_pipelines();
      stats_.counters[counter::kSceneBytes] = double(p.buffer_bytes());
      gpu::count_update(stats_, u);
    } catch (...) {
      release_scene();
      throw;
    }
    stats_.ms[ms_key::kUpdate] = ms_since(start);
    check_validation("scene update");
  }

  Image render(const RenderSettings& settings) override {
    use_world_for(false);
    const Kernel& kernel = kernel_for(false);
    auto start = std::chrono::steady_clock::now();
    gpu::FrameProfile profile(settings.profile);
    const ImageSettings& s = settings.image;
    const GpuFrame frame = gpu::frame_for(scene_->packed, settings.camera.value_or(scene_model_->camera), settings);
    const std::vector<unsigned char> frame_bytes = gpu::frame_bytes(scene_->packed, frame, gpu::sample_offsets(s.spp));
    const gpu::TileBudget budget = tile_budget();
    auto [tw, th] = gpu::tile_size(s, budget);
    const int planes = gpu::output_planes(settings);
    frame_buffers_.reserve(*context_, frame_bytes.size(), gpu::output_bytes(size_t(tw) * th, planes));
    std::memcpy(frame_buffers_.frame_staging.mapped(), frame_bytes.data(), frame_bytes.size());
    bind(kernel, frame_buffers_.frame, frame_buffers_.output);

    Image image;  // made while the first tile renders
    const char* readback = static_cast<const char*>(frame_buffers_.readback.mapped());
    const auto* header = reinterpret_cast<const uint32_t*>(readback);
    const auto* pixels = reinterpret_cast<const float*>(readback + gpu::kOutputHeaderBytes);
    const std::vector<gpu::Tile> tiles = gpu::tiles_of(settings, budget);
    const uint64_t rays_before = stats_.rays;  // the counters add up over calls; the progress is this call's
    const bool timed = settings.profile && timestamps();
    for (size_t t = 0; t < tiles.size(); ++t) {
      throw_if_cancelled();  // between dispatches: a request stops the run within one tile
      const gpu::Tile& tile = tiles[t];
      commands_->submit("rendering", [&](VkCommandBuffer cb) {
        if (t == 0) record_frame_upload(cb, frame_bytes.size());
        record_tile(cb, kernel, tile, gpu::output_bytes(size_t(tile.width) * tile.height, planes), timed);
      });
      if (t == 0) {
        profile.end_setup();
        image = gpu::blank_image(settings);
        profile.end_allocation();
      }
      commands_->wait("rendering");
      profile.end_wait(timed ? kernel_ms() : -1.0);
      gpu::store_tile(image, settings, pixels, tile);
      gpu::add_ray_counters(stats_, header);
      profile.end_store();
      report_progress(settings, double(t + 1) / double(tiles.size()), stats_.rays - rays_before);
    }
    profile.add_to(stats_);
    stats_.ms[ms_key::kRender] += ms_since(start);
    check_validation("rendering");
    return image;
  }

  std::vector<TraceResult> trace(std::span<const TraceQuery> rays) override {
    use_world_for(true);
    anchor_at(rays);
    const Kernel& kernel = kernel_for(true);
    auto start = std::chrono::steady_clock::now();
    GpuFrame frame = gpu::frame_for(scene_->packed, scene_model_->camera, RenderSettings{});
    std::vector<TraceResult> results(rays.size());
    for (size_t first = 0; first < rays.size(); first += gpu::kTraceRaysPerDispatch) {
      throw_if_cancelled();  // between dispatches: a request stops the run within one tile
      const size_t n = std::min(gpu::kTraceRaysPerDispatch, rays.size() - first);
      frame.flags[1] = int32_t(n);
      const std::vector<unsigned char> frame_bytes = gpu::frame_bytes(scene_->packed, frame, {});
      vk::Buffer frame_buffer = vk::upload_storage(*context_, *commands_, frame_bytes.data(), frame_bytes.size(),
                                                   "upload of the frame constants");
      const std::vector<unsigned char> io = gpu::trace_records(scene_->packed, rays.subspan(first, n));
      const VkDeviceSize bytes = io.size();
      vk::Buffer staging(*context_, bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                         vk::Memory::Staging, "allocation of the ray staging buffer");
      std::memcpy(staging.mapped(), io.data(), bytes);
      vk::Buffer records(*context_, bytes, kStorage | VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                         vk::Memory::Device, "allocation of the ray buffer");
      bind(kernel, frame_buffer, records);
      commands_->run("tracing", [&](VkCommandBuffer cb) { record_trace(cb, kernel, staging, records, n); });
      gpu::read_trace_records(scene_->packed, {static_cast<const unsigned char*>(staging.mapped()), size_t(bytes)},
                              std::span(results).subspan(first, n));
    }
    stats_.rays += rays.size();
    stats_.rays_by_kind[ray_kind::kTrace] += rays.size();
    stats_.ms[ms_key::kRender] += ms_since(start);
    check_validation("tracing");
    return results;
  }

  BackendStats stats() const override {
    BackendStats s = stats_;
    if (context_->validation())
      s.counters[counter::kVulkanValidationMessages] = double(context_->validation_message_count());
    return s;
  }

 private:
  const vk::Api& api() const { return context_->api(); }

  // A scene too large for this device is refused before any upload (InputError: exit status 2).
  void check_limits(const gpu::PackedScene& p, const std::string& source) const {
    gpu::check_buffer_limits(p, source, context_->properties().limits.maxStorageBufferRange,
                             "this Vulkan device's maxStorageBufferRange");
  }

  vk::Buffer upload(const gpu::SceneBuffer& source) {
    return vk::upload_storage(*context_, *commands_, source.data, source.bytes(), std::string("upload of the ") + source.name);
  }

  // The texel view of `s`'s texel buffer (made again: the buffer may be
  // new), or none when the texels exceed the device's texel-buffer limit.
  void view_texels(DeviceScene& s) {
    s.texels = vk::TexelView();
    if (gpu::texel_buffer_allowed() && s.packed.texels.size() <= context_->properties().limits.maxTexelBufferElements)
      s.texels = vk::TexelView(*context_, s.buffers[gpu::kBindTexels], s.packed.texels.size(), "the texel buffer's view");
  }

  void choose_material_block(DeviceScene& s) {
    const VkDeviceSize bytes = gpu::scene_buffer(s.packed, gpu::kBindMaterials).bytes();
    const bool fits = bytes > 0 && bytes <= context_->properties().limits.maxUniformBufferRange;
    s.material_block = gpu::material_block_allowed() && fits ? bytes : 0;
  }

  // Every command waits for its fence, so no pipeline is in use here.
  void drop_pipelines() {
    for (Kernel* kernel : {&scene_->render, &scene_->trace}) {
      if (kernel->pipeline && !context_->abandoned()) api().vkDestroyPipeline(context_->device(), kernel->pipeline, nullptr);
      kernel->pipeline = VK_NULL_HANDLE;
    }
  }

  void release_scene() {
    if (scene_) drop_pipelines();
    scene_.reset();
  }

  // One descriptor set per kernel (render and trace), reallocated per scene.
  void create_descriptor_pool() {
    const VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 2 * gpu::kBindingCount},
                                          {VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER, 2},
                                          {VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 2}};
    auto info = vk::make<VkDescriptorPoolCreateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO);
    info.maxSets = 2;
    info.poolSizeCount = 3;
    info.pPoolSizes = sizes;
    vk::check(api().vkCreateDescriptorPool(context_->device(), &info, nullptr, &pool_), "descriptor pool creation");
  }

  void reset_descriptor_pool() {
    api().vkDestroyDescriptorPool(context_->device(), pool_, nullptr);
    pool_ = VK_NULL_HANDLE;
    create_descriptor_pool();
  }

  // The render or trace kernel, generated, compiled and warmed up on first use.
  const Kernel& kernel_for(bool trace) {
    if (!scene_) throw RuntimeError("vulkan backend: render or trace before prepare");
    Kernel& slot = trace ? scene_->trace : scene_->render;
    if (slot.pipeline) return slot;
    gpu::KernelOptions options = gpu::kernel_options(trace, kApiGlue);
    options.texel_sampler = bool(scene_->texels);
    options.material_block = scene_->material_block != 0;
    const gpu::KernelSource source = gpu::generate_kernel(scene_->packed, options);
    vk::PipelineStats build;
    slot.pipeline = vk::build_pipeline(*context_, *layout_, source.text, build);
    if (!slot.descriptors) slot.descriptors = allocate_descriptors();
    stats_.counters[counter::kKernelBuilds] += 1;
    auto start = std::chrono::steady_clock::now();
    warm_up(slot);
    stats_.kernel_features = source.features;
    stats_.ms[ms_key::kCompile] += build.ms + ms_since(start);
    stats_.counters[counter::kGlslangCompileCalls] += build.glslang_compile_calls;
    // Where compile time goes: glslang, the driver's pipeline creation, and
    // the first dispatch (where a JIT driver such as lavapipe generates code).
    stats_.counters[counter::kGlslangMs] += build.glslang_ms;
    stats_.counters[counter::kPipelineCreateMs] += build.driver_ms;
    stats_.counters[counter::kFirstDispatchMs] += ms_since(start);
    stats_.info[info_key::kProgramCache] = build.cache;
    if (!build.cache_file.empty()) stats_.info[info_key::kProgramCacheFile] = build.cache_file.string();
    check_validation("kernel build");
    return slot;
  }

  VkDescriptorSet allocate_descriptors() {
    VkDescriptorSetLayout sets = layout_->sets();
    auto info = vk::make<VkDescriptorSetAllocateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO);
    info.descriptorPool = pool_;
    info.descriptorSetCount = 1;
    info.pSetLayouts = &sets;
    VkDescriptorSet set = VK_NULL_HANDLE;
    vk::check(api().vkAllocateDescriptorSets(context_->device(), &info, &set), "descriptor set allocation");
    return set;
  }

  // Points the kernel's eight buffer bindings at the scene, the frame and
  // the output, its texel binding at the texel view where there is one, and
  // its material block at the materials where they fit one.
  void bind(const Kernel& kernel, const vk::Buffer& frame, const vk::Buffer& output) {
    const vk::Buffer* buffers[gpu::kBindingCount] = {};
    for (uint32_t b = 0; b < gpu::kSceneBufferCount; ++b) buffers[b] = &scene_->buffers[b];
    buffers[gpu::kBindFrame] = &frame;
    buffers[gpu::kBindOutput] = &output;
    VkDescriptorBufferInfo infos[gpu::kBindingCount];
    VkWriteDescriptorSet writes[vk::kLayoutBindingCount];
    uint32_t count = 0;
    const auto add_write = [&](uint32_t binding, VkDescriptorType type) -> VkWriteDescriptorSet& {
      VkWriteDescriptorSet& w = writes[count++];
      w = vk::make<VkWriteDescriptorSet>(VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET);
      w.dstSet = kernel.descriptors;
      w.dstBinding = binding;
      w.descriptorCount = 1;
      w.descriptorType = type;
      return w;
    };
    for (uint32_t b = 0; b < gpu::kBindingCount; ++b) {
      infos[b] = {buffers[b]->handle(), 0, VK_WHOLE_SIZE};
      add_write(b, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER).pBufferInfo = &infos[b];
    }
    const VkBufferView texel_view = scene_->texels.handle();
    if (scene_->texels) add_write(vk::kTexelViewBinding, VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER).pTexelBufferView = &texel_view;
    const VkDescriptorBufferInfo material_info{scene_->buffers[gpu::kBindMaterials].handle(), 0, scene_->material_block};
    if (scene_->material_block)
      add_write(vk::kMaterialBlockBinding, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER).pBufferInfo = &material_info;
    api().vkUpdateDescriptorSets(context_->device(), count, writes, 0, nullptr);
  }

  void dispatch(VkCommandBuffer cb, const Kernel& kernel, const int32_t tile[4], uint32_t groups_x, uint32_t groups_y) {
    api().vkCmdBindPipeline(cb, VK_PIPELINE_BIND_POINT_COMPUTE, kernel.pipeline);
    api().vkCmdBindDescriptorSets(cb, VK_PIPELINE_BIND_POINT_COMPUTE, layout_->handle(), 0, 1, &kernel.descriptors, 0,
                                  nullptr);
    api().vkCmdPushConstants(cb, layout_->handle(), VK_SHADER_STAGE_COMPUTE_BIT, 0, 4 * sizeof(int32_t), tile);
    api().vkCmdDispatch(cb, groups_x, groups_y, 1);
  }

  // The frame's constants from their staging buffer, before the first tile reads them.
  void record_frame_upload(VkCommandBuffer cb, size_t bytes) {
    const vk::Api& vk = api();
    const VkBufferCopy region{0, 0, bytes};
    vk.vkCmdCopyBuffer(cb, frame_buffers_.frame_staging.handle(), frame_buffers_.frame.handle(), 1, &region);
    vk::barrier(vk, cb, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                VK_ACCESS_SHADER_READ_BIT);
  }

  // Clear the counters, render the tile, copy what it wrote (`used` bytes) to the readback buffer.
  void record_tile(VkCommandBuffer cb, const Kernel& kernel, const gpu::Tile& tile, VkDeviceSize used, bool timed) {
    const vk::Api& vk = api();
    const vk::Buffer& output = frame_buffers_.output;
    // The previous tile's copy back reads the output: the clear waits for it.
    vk::barrier(vk, cb, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
                VK_ACCESS_TRANSFER_WRITE_BIT);
    vk.vkCmdFillBuffer(cb, output.handle(), 0, gpu::kOutputHeaderBytes, 0);
    vk::barrier(vk, cb, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
    const int32_t origin[4] = {tile.x0, tile.y0, tile.width, tile.height};
    if (timed) {
      vk.vkCmdResetQueryPool(cb, timestamps_, 0, 2);
      vk.vkCmdWriteTimestamp(cb, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, timestamps_, 0);
    }
    dispatch(cb, kernel, origin, uint32_t(tile.width + gpu::kRenderLocalSize - 1) / gpu::kRenderLocalSize,
             uint32_t(tile.height + gpu::kRenderLocalSize - 1) / gpu::kRenderLocalSize);
    if (timed) vk.vkCmdWriteTimestamp(cb, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, timestamps_, 1);
    copy_back(cb, output, frame_buffers_.readback, used);
  }

  // A pool of two timestamps around a tile's dispatch, made on first use
  // (`bench --profile`): false where the queue does not count time.
  bool timestamps() {
    if (timestamps_) return true;
    if (context_->timestamp_bits() == 0) return false;
    auto info = vk::make<VkQueryPoolCreateInfo>(VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO);
    info.queryType = VK_QUERY_TYPE_TIMESTAMP;
    info.queryCount = 2;
    return api().vkCreateQueryPool(context_->device(), &info, nullptr, &timestamps_) == VK_SUCCESS;
  }

  // The last tile's dispatch on the device, from its two timestamps.
  double kernel_ms() const {
    uint64_t ticks[2] = {};
    api().vkGetQueryPoolResults(context_->device(), timestamps_, 0, 2, sizeof ticks, ticks, sizeof(uint64_t),
                                VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT);
    const uint32_t bits = context_->timestamp_bits();
    const uint64_t mask = bits >= 64 ? ~uint64_t(0) : (uint64_t(1) << bits) - 1;
    return double((ticks[1] - ticks[0]) & mask) * double(context_->properties().limits.timestampPeriod) * 1e-6;
  }

  // This device's tile budget: a CPU device's small tiles or a GPU's large ones.
  gpu::TileBudget tile_budget() const {
    const VkPhysicalDeviceProperties& p = context_->properties();
    const size_t lights = std::max(scene_->packed.lights.size(), scene_->packed.lights_f.size());
    return gpu::tile_budget(p.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU, p.limits.maxStorageBufferRange, int(lights));
  }

  void record_trace(VkCommandBuffer cb, const Kernel& kernel, const vk::Buffer& staging, const vk::Buffer& records,
                    size_t n) {
    const vk::Api& vk = api();
    const VkBufferCopy region{0, 0, n * gpu::trace_record_bytes(scene_->packed)};
    vk.vkCmdCopyBuffer(cb, staging.handle(), records.handle(), 1, &region);
    vk::barrier(vk, cb, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
    const int32_t origin[4] = {0, 0, 0, 0};
    dispatch(cb, kernel, origin, uint32_t((n + gpu::kTraceLocalSize - 1) / gpu::kTraceLocalSize), 1);
    copy_back(cb, records, staging, region.size);
  }

  // The compute results to host-visible memory, visible to the host once the fence signals.
  void copy_back(VkCommandBuffer cb, const vk::Buffer& from, const vk::Buffer& to, VkDeviceSize size) {
    const vk::Api& vk = api();
    vk::barrier(vk, cb, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
                VK_ACCESS_TRANSFER_READ_BIT);
    const VkBufferCopy region{0, 0, size};
    vk.vkCmdCopyBuffer(cb, from.handle(), to.handle(), 1, &region);
    vk::barrier(vk, cb, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_HOST_BIT,
                VK_ACCESS_HOST_READ_BIT);
  }

  // Drivers may generate machine code at the first dispatch (lavapipe JITs
  // then): one empty dispatch (a zero-sized tile, every invocation returns
  // at once) puts that cost in `compile`, where it belongs, not in `render`.
  void warm_up(const Kernel& kernel) {
    const GpuFrame empty{};
    vk::Buffer frame = vk::upload_storage(*context_, *commands_, &empty, sizeof empty, "kernel warm-up");
    vk::Buffer output(*context_, gpu::kOutputHeaderBytes + sizeof(GpuTraceRay), kStorage, vk::Memory::Device,
                      "kernel warm-up");
    bind(kernel, frame, output);
    commands_->run("kernel warm-up", [&](VkCommandBuffer cb) {
      const int32_t origin[4] = {0, 0, 0, 0};
      dispatch(cb, kernel, origin, 1, 1);
    });
  }

  // With validation on, any message fails the operation: the suite promises
  // zero validation messages in every render and trace.
  void check_validation(const char* what) const {
    if (!context_->validation()) return;
    const std::vector<std::string> messages = context_->validation_messages();
    if (messages.size() == reported_) return;
    std::string text = "Vulkan validation reported " + std::to_string(messages.size() - reported_) + " message(s) during " + what + ":";
    for (size_t i = reported_; i < messages.size(); ++i) text += "\n  " + messages[i];
    reported_ = messages.size();
    throw RuntimeError(text);
  }

  std::unique_ptr<vk::Context> context_;
  std::unique_ptr<vk::Commands> commands_;
  std::unique_ptr<vk::PipelineLayout> layout_;
  VkDescriptorPool pool_ = VK_NULL_HANDLE;
  std::unique_ptr<DeviceScene> scene_;
  FrameBuffers frame_buffers_;
  VkQueryPool timestamps_ = VK_NULL_HANDLE;
  const Scene* scene_model_ = nullptr;
  mutable size_t reported_ = 0;
  BackendStats stats_;
  Precision precision_ = Precision::automatic;
  std::string last_warning_;  // said once, not at every prepare of the same scene
  bool tracing_ = false;  // the prepared world is for `trace`
  std::optional<glm::dvec3> trace_anchor_;  // a float world's anchor for `trace`: its rays' origins
};

void probe(PrismBackendProbe* out) {
  probe_by_starting(out, [] { return vk::Context().description(); });
}

Backend* create() { return new VulkanBackend(); }

constexpr PrismBackendDesc kDesc = backend_desc("vulkan", "1.0.0", 45, probe, create);

}  // namespace
}  // namespace prism

extern "C" PRISM_EXPORT const PrismBackendDesc* prism_backend_entry(void) { return &prism::kDesc; }
