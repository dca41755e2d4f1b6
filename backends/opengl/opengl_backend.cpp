// The OpenGL backend: the scene-specialised GLSL kernel (gpu/) run
// as a GL 4.5 compute shader in a headless EGL context. Work is dispatched
// in tiles small enough that no dispatch trips a desktop driver's watchdog;
// each tile's pixels and ray counters are read back before the next. A live
// update rewrites only the changed ranges of the scene buffers in place.
#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <memory>
#include <optional>

#include "egl_context.hpp"
#include "gl_buffers.hpp"
#include "gl_program.hpp"
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

namespace prism {
namespace {

using gpu::GpuFrame;
using gpu::GpuTraceRay;

using gpu::kTraceLocalSize;
using gpu::kTraceRaysPerDispatch;
using gpu::ms_since;

// A GL 4.5 glue for the shared kernel: the tile origin is a plain uniform.
constexpr const char* kApiGlue =
    "layout(location = 0) uniform ivec4 prism_tile;\n"
    "#define PRISM_TILE_ORIGIN prism_tile\n"
    "#define PRISM_BINDING_TEXEL_SAMPLER 0\n"   // texture unit 0
    "#define PRISM_BINDING_MATERIAL_BLOCK 0\n";  // uniform block binding 0

void check_gl(const char* what) {
  GLenum error = glGetError();
  if (error == GL_NO_ERROR) return;
  char code[16];
  std::snprintf(code, sizeof code, "0x%04x", error);
  std::string reason = error == GL_OUT_OF_MEMORY ? "out of memory" : std::string("GL error ") + code;
  throw RuntimeError(std::string("OpenGL failed during ") + what + ": " + reason);
}

// Everything that lives in the GL context; destroyed with the context current.
struct GpuState {
  gpu::PackedScene packed;
  std::array<gl::Buffer, gpu::kSceneBufferCount> buffers;  // by binding
  GLuint render_program = 0, trace_program = 0;
  // Kernels read the texels through a buffer texture over the texel buffer
  // (KernelOptions::texel_sampler) when they fit GL_MAX_TEXTURE_BUFFER_SIZE.
  bool texel_sampler = false;
  GLuint texel_texture = 0;
  // ... and the materials through a uniform block when they fit GL_MAX_UNIFORM_BLOCK_SIZE.
  bool material_block = false;

  ~GpuState() {
    drop_programs();
    if (texel_texture) glDeleteTextures(1, &texel_texture);
  }
  void drop_programs() {
    if (render_program) glDeleteProgram(render_program);
    if (trace_program) glDeleteProgram(trace_program);
    render_program = trace_program = 0;
  }
  void bind_scene() const {
    for (uint32_t b = 0; b < gpu::kSceneBufferCount; ++b) buffers[b].bind(b);
    if (material_block) glBindBufferBase(GL_UNIFORM_BUFFER, 0, buffers[gpu::kBindMaterials].id());
    if (!texel_sampler) return;
    glTextureBuffer(texel_texture, GL_RGBA32F, buffers[gpu::kBindTexels].id());  // the buffer may have been made again
    glBindTextureUnit(0, texel_texture);
  }
  // Whether the texels fit a buffer texture and the materials a uniform block
  // here; programs built the other way are dropped.
  void choose_scene_reads() {
    GLint max_texels = 0;
    glGetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &max_texels);
    const bool fits = gpu::texel_buffer_allowed() && max_texels > 0 && packed.texels.size() <= size_t(max_texels);
    if (fits != texel_sampler) drop_programs();
    texel_sampler = fits;
    GLint64 max_block = 0;
    glGetInteger64v(GL_MAX_UNIFORM_BLOCK_SIZE, &max_block);
    const gpu::SceneBuffer materials = gpu::scene_buffer(packed, gpu::kBindMaterials);
    const bool block = gpu::material_block_allowed() && materials.bytes() <= uint64_t(std::max<GLint64>(max_block, 0));
    if (block != material_block) drop_programs();
    material_block = block;
    if (texel_sampler && !texel_texture) glCreateTextures(GL_TEXTURE_BUFFER, 1, &texel_texture);
  }
  // Sends what `writes` names of scene buffer `b`, making the buffer again when it no longer fits.
  void write(uint32_t b, const gpu::BufferWrites& writes) {
    const gpu::SceneBuffer source = gpu::scene_buffer(packed, b);
    if (writes.whole && source.bytes() > buffers[b].bytes()) {
      buffers[b] = gl::Buffer(source.data, source.bytes());
      return;
    }
    for (const gpu::ByteRange& r : gpu::byte_ranges(source, writes)) buffers[b].write(r.offset, r.size, r.data);
  }
};

template <class T>
gl::Buffer buffer_of(const std::vector<T>& v) {
  return gl::Buffer(v.data(), v.size() * sizeof(T));
}

// A render's buffers, kept from one render to the next and grown when a
// frame needs more: the frame's constants, and two tile slots (an output and
// the host's readback copy of it), so that one tile renders while the host
// stores the other.
struct FrameBuffers {
  struct Slot {
    gl::Buffer output;
    gl::ReadbackBuffer readback;
  };
  gl::Buffer frame;
  Slot slots[2];

  void reserve(size_t frame_bytes, size_t output_bytes) {
    if (frame.bytes() < frame_bytes) frame = gl::Buffer(nullptr, frame_bytes);
    for (Slot& slot : slots) {
      if (slot.output.bytes() >= output_bytes) continue;
      slot.output = gl::Buffer(nullptr, output_bytes);
      slot.readback = gl::ReadbackBuffer(output_bytes);
    }
  }
};

class OpenGLBackend : public Backend {
 public:
  OpenGLBackend() : context_(std::make_unique<gl::EglContext>()) {
    stats_.info[info_key::kDevice] = context_->description();
    gpu::start_counters(stats_);
  }

  // A prepared scene is packed again in the world the new precision asks for.
  void set_precision(Precision precision) override {
    if (precision == precision_) return;
    precision_ = precision;
    if (state_ && scene_) prepare(*scene_);
  }

  // A float world for `trace` is anchored where its rays start.
  void anchor_at(std::span<const TraceQuery> rays) {
    if (!state_->packed.float_world) return;
    const glm::dvec3 anchor = gpu::trace_anchor(rays);
    if (anchor == state_->packed.anchor) return;
    trace_anchor_ = anchor;
    prepare(*scene_);
  }

  // `prism trace` asks for arbitrary rays, a render for the camera's: with
  // automatic precision the two may want different worlds (gpu/precision.hpp).
  void use_world_for(bool tracing) {
    if (tracing == tracing_) return;
    tracing_ = tracing;
    if (state_ && scene_ && gpu::choose_world(*scene_, precision_, tracing).float_world != state_->packed.float_world)
      prepare(*scene_);
  }

  ~OpenGLBackend() override {
    gl::EglContext::Current current(*context_);
    state_.reset();
    frame_buffers_ = {};
  }

  void prepare(const Scene& scene) override {
    gl::EglContext::Current current(*context_);
    auto start = std::chrono::steady_clock::now();
    scene_ = &scene;
    state_.reset();
    auto state = std::make_unique<GpuState>();
    state->packed = gpu::pack_scene(scene);
    gpu::WorldChoice world = gpu::choose_world(scene, precision_, tracing_);
    if (world.float_world && tracing_ && trace_anchor_) world.anchor = *trace_anchor_;
    gpu::set_world(state->packed, world.float_world, world.anchor);
    stats_.info[info_key::kPrecision] = world.description;
    stats_.info[info_key::kPrecisionObjects] = world.objects;
    const gpu::PackedScene& p = state->packed;
    check_limits(p, scene.source);
    for (uint32_t b = 0; b < gpu::kSceneBufferCount; ++b) {
      const gpu::SceneBuffer source = gpu::scene_buffer(p, b);
      state->buffers[b] = gl::Buffer(source.data, source.bytes());
    }
    state->choose_scene_reads();
    glFinish();
    check_gl("scene upload");
    stats_.counters[counter::kSceneBytes] = double(p.buffer_bytes());
    gpu::count_prepare(stats_, p);
    state_ = std::move(state);
    stats_.ms[ms_key::kBuild] = ms_since(start);
  }

  // Packs what changed in place and sends only that; the programs are kept
  // unless the kernel's primitive types or features changed. A failure
  // leaves nothing prepared (the next render asks for a prepare).
  void update(const Scene& scene, const SceneChanges& changes) override {
    if (!state_ || &scene != scene_) return prepare(scene);
    gl::EglContext::Current current(*context_);
    auto start = std::chrono::steady_clock::now();
    try {
      gpu::PackedScene& p = state_->packed;
      const gpu::PackedUpdate u = gpu::update_packed_scene(p, scene, changes);
      check_limits(p, scene.source);
      for (uint32_t b = 0; b < gpu::kSceneBufferCount; ++b) state_->write(b, u.buffers[b]);
      if (u.kernel) state_->drop_programs();
      state_->choose_scene_reads();
      glFinish();
      check_gl("scene update");
      stats_.counters[counter::kSceneBytes] = double(p.buffer_bytes());
      gpu::count_update(stats_, u);
    } catch (...) {
      state_.reset();
      throw;
    }
    stats_.ms[ms_key::kUpdate] = ms_since(start);
  }

  Image render(const RenderSettings& settings) override {
    use_world_for(false);
    gl::EglContext::Current current(*context_);
    GLuint program = program_for(false);
    auto start = std::chrono::steady_clock::now();
    const ImageSettings& s = settings.image;
    GpuFrame frame = gpu::frame_for(state_->packed, settings.camera.value_or(scene_->camera), settings);
    gpu::FrameProfile profile(settings.profile);
    const std::vector<unsigned char> frame_bytes = gpu::frame_bytes(state_->packed, frame, gpu::sample_offsets(s.spp));
    const gpu::TileBudget budget = tile_budget();
    auto [tw, th] = gpu::tile_size(s, budget);
    const int planes = gpu::output_planes(settings);
    frame_buffers_.reserve(frame_bytes.size(), gpu::output_bytes(size_t(tw) * th, planes));
    frame_buffers_.frame.write(0, frame_bytes.size(), frame_bytes.data());
    state_->bind_scene();
    frame_buffers_.frame.bind(gpu::kBindFrame);
    glUseProgram(program);

    const std::vector<gpu::Tile> tiles = gpu::tiles_of(settings, budget);
    gl::TimerPair timers[2] = {gl::TimerPair(settings.profile), gl::TimerPair(settings.profile)};
    // Tile t renders in slot t % 2 and is copied to its readback buffer;
    // the next tile is already under way while the host stores this one.
    const auto issue = [&](size_t t) {
      throw_if_cancelled();  // between dispatches: a request stops the run within one tile
      const gpu::Tile& tile = tiles[t];
      FrameBuffers::Slot& slot = frame_buffers_.slots[t % 2];
      const uint32_t zero[gpu::kRayCounterCount] = {};
      slot.output.write(0, sizeof zero, zero);
      slot.output.bind(gpu::kBindOutput);
      glUniform4i(0, tile.x0, tile.y0, tile.width, tile.height);
      timers[t % 2].start();
      glDispatchCompute(GLuint((tile.width + gpu::kRenderLocalSize - 1) / gpu::kRenderLocalSize),
                        GLuint((tile.height + gpu::kRenderLocalSize - 1) / gpu::kRenderLocalSize), 1);
      timers[t % 2].stop();
      slot.readback.start_copy(slot.output, gpu::output_bytes(size_t(tile.width) * tile.height, planes));
    };
    for (size_t t = 0; t < std::min<size_t>(2, tiles.size()); ++t) issue(t);
    profile.end_setup();
    Image image = gpu::blank_image(settings);  // while the first tiles render
    profile.end_allocation();
    const uint64_t rays_before = stats_.rays;  // the counters add up over calls; the progress is this call's
    for (size_t t = 0; t < tiles.size(); ++t) {
      FrameBuffers::Slot& slot = frame_buffers_.slots[t % 2];
      slot.readback.wait();
      check_gl("rendering");
      profile.end_wait(timers[t % 2].ms());
      const auto* readback = static_cast<const char*>(slot.readback.data());
      gpu::store_tile(image, settings, reinterpret_cast<const float*>(readback + gpu::kOutputHeaderBytes), tiles[t]);
      gpu::add_ray_counters(stats_, reinterpret_cast<const uint32_t*>(readback));
      profile.end_store();
      report_progress(settings, double(t + 1) / double(tiles.size()), stats_.rays - rays_before);
      if (t + 2 < tiles.size()) issue(t + 2);
    }
    profile.add_to(stats_);
    stats_.ms[ms_key::kRender] += ms_since(start);
    return image;
  }

  std::vector<TraceResult> trace(std::span<const TraceQuery> rays) override {
    use_world_for(true);
    anchor_at(rays);
    gl::EglContext::Current current(*context_);
    GLuint program = program_for(true);
    auto start = std::chrono::steady_clock::now();
    RenderSettings settings;
    GpuFrame frame = gpu::frame_for(state_->packed, scene_->camera, settings);
    std::vector<TraceResult> results(rays.size());
    state_->bind_scene();
    glUseProgram(program);
    for (size_t first = 0; first < rays.size(); first += kTraceRaysPerDispatch) {
      throw_if_cancelled();  // between dispatches: a request stops the run within one tile
      const size_t n = std::min(kTraceRaysPerDispatch, rays.size() - first);
      frame.flags[1] = int32_t(n);
      gl::Buffer frame_buffer = frame_buffer_for(frame, {});
      std::vector<unsigned char> io = gpu::trace_records(state_->packed, rays.subspan(first, n));
      gl::Buffer io_buffer = buffer_of(io);
      frame_buffer.bind(gpu::kBindFrame);
      io_buffer.bind(gpu::kBindOutput);
      glUniform4i(0, 0, 0, 0, 0);
      glDispatchCompute(GLuint((n + kTraceLocalSize - 1) / kTraceLocalSize), 1, 1);
      glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
      io_buffer.read(0, io.size(), io.data());
      check_gl("tracing");
      gpu::read_trace_records(state_->packed, io, std::span(results).subspan(first, n));
    }
    stats_.rays += rays.size();
    stats_.rays_by_kind[ray_kind::kTrace] += rays.size();
    stats_.ms[ms_key::kRender] += ms_since(start);
    return results;
  }

  BackendStats stats() const override { return stats_; }

 private:
  // A scene too large for this driver is refused before any upload (InputError: exit status 2).
  void check_limits(const gpu::PackedScene& p, const std::string& source) {
    GLint64 max_block = 0;
    glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &max_block);
    if (max_block <= 0) return;  // the query failed: the upload's own error is all there is
    stats_.counters[counter::kMaxStorageBufferBytes] = double(max_block);
    gpu::check_buffer_limits(p, source, uint64_t(max_block), "this OpenGL driver's GL_MAX_SHADER_STORAGE_BLOCK_SIZE");
  }

  // The render or trace program, generated and built on first use.
  GLuint program_for(bool trace) {
    if (!state_) throw RuntimeError("opengl backend: render or trace before prepare");
    GLuint& program = trace ? state_->trace_program : state_->render_program;
    if (program) return program;
    gpu::KernelOptions options = gpu::kernel_options(trace, kApiGlue);
    options.texel_sampler = state_->texel_sampler;
    options.material_block = state_->material_block;
    gpu::KernelSource kernel = gpu::generate_kernel(state_->packed, options);
    gl::ProgramStats build;
    program = gl::build_program(kernel.text, context_->driver_identity(), build);
    auto start = std::chrono::steady_clock::now();
    warm_up(program);
    stats_.kernel_features = kernel.features;
    stats_.ms[ms_key::kCompile] += build.ms + ms_since(start);
    stats_.counters[counter::kKernelBuilds] += 1;
    stats_.counters[counter::kGlCompileShaderCalls] += build.compile_calls;
    stats_.counters[counter::kGlLinkProgramCalls] += build.link_calls;
    stats_.info[info_key::kProgramCache] = build.cache;
    if (!build.cache_file.empty()) stats_.info[info_key::kProgramCacheFile] = build.cache_file.string();
    return program;
  }

  // Drivers may generate machine code at the first dispatch (llvmpipe JITs
  // then): one empty dispatch (a zero-sized tile, every invocation returns at
  // once) puts that cost in `compile`, where it belongs, not in `render`.
  void warm_up(GLuint program) const {
    const GpuFrame empty{};
    gl::Buffer frame = frame_buffer_for(empty, {});
    gl::Buffer output(nullptr, gpu::kOutputHeaderBytes + sizeof(GpuTraceRay));
    state_->bind_scene();
    frame.bind(gpu::kBindFrame);
    output.bind(gpu::kBindOutput);
    glUseProgram(program);
    glUniform4i(0, 0, 0, 0, 0);
    glDispatchCompute(1, 1, 1);
    glFinish();
    check_gl("kernel warm-up");
  }

  gl::Buffer frame_buffer_for(const GpuFrame& frame, const std::vector<glm::dvec2>& offsets) const {
    const std::vector<unsigned char> bytes = gpu::frame_bytes(state_->packed, frame, offsets);
    return gl::Buffer(bytes.data(), bytes.size());
  }

  // This device's tile budget: a CPU renderer's small tiles or a GPU's large ones.
  gpu::TileBudget tile_budget() const {
    GLint64 max_block = 0;
    glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &max_block);
    const size_t lights = std::max(state_->packed.lights.size(), state_->packed.lights_f.size());
    // Two tiles in flight on a GPU (a frame is at least two bands); a CPU
    // renderer runs a dispatch at once, so it gains nothing from more tiles.
    return gpu::tile_budget(context_->software(), size_t(max_block), int(lights), context_->software() ? 1 : 2);
  }

  std::unique_ptr<gl::EglContext> context_;
  std::unique_ptr<GpuState> state_;
  FrameBuffers frame_buffers_;
  Precision precision_ = Precision::automatic;
  bool tracing_ = false;  // the prepared world is for `trace`
  std::optional<glm::dvec3> trace_anchor_;  // a float world's anchor for `trace`: its rays' origins
  const Scene* scene_ = nullptr;
  BackendStats stats_;
};

void probe(PrismBackendProbe* out) {
  probe_by_starting(out, [] { return gl::EglContext().description(); });
}

Backend* create() { return new OpenGLBackend(); }

constexpr PrismBackendDesc kDesc = backend_desc("opengl", "1.0.0", 40, probe, create);

}  // namespace
}  // namespace prism

extern "C" PRISM_EXPORT const PrismBackendDesc* prism_backend_entry(void) { return &prism::kDesc; }
