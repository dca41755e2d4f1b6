// The OpenGL backend: the scene-specialised GLSL kernel (backends/glsl) run
// as a GL 4.5 compute shader in a headless EGL context. Work is dispatched
// in tiles small enough that no dispatch trips a desktop driver's watchdog;
// each tile's pixels and ray counters are read back before the next.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <memory>
#include <optional>

#include "egl_context.hpp"
#include "gl_buffers.hpp"
#include "gl_program.hpp"
#include "gpu_scene.hpp"
#include "kernel_source.hpp"
#include "prism/backend.hpp"
#include "prism/errors.hpp"

namespace prism {
namespace {

using gpu::GpuFrame;
using gpu::GpuPixel;
using gpu::GpuTraceRay;

// Samples per tile: about 0.25 M, a few milliseconds on a GPU, well under a
// second on llvmpipe, and few enough that 32-bit ray counters cannot overflow.
constexpr long kSamplesPerTile = 1 << 18;
constexpr int kTraceLocalSize = 64;
constexpr size_t kTraceRaysPerDispatch = 1 << 16;

// A GL 4.5 glue for the shared kernel: the tile origin is a plain uniform.
constexpr const char* kApiGlue =
    "layout(location = 0) uniform ivec4 prism_tile;\n"
    "#define PRISM_TILE_ORIGIN prism_tile\n";

double ms_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

// Tile width and height for an image and spp (multiples of the 8x8 work group).
std::pair<int, int> tile_size(const ImageSettings& s) {
  long pixels = std::max<long>(64, kSamplesPerTile / s.spp);
  int w = std::min(s.width, 512);
  w = (w + 7) / 8 * 8;
  int h = int(std::max<long>(8, pixels / w / 8 * 8));
  return {w, std::min(h, (s.height + 7) / 8 * 8)};
}

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
  gl::Buffer records, objects, nodes, materials, lights, texels;
  GLuint render_program = 0, trace_program = 0;
  std::vector<std::string> features;

  ~GpuState() {
    if (render_program) glDeleteProgram(render_program);
    if (trace_program) glDeleteProgram(trace_program);
  }
  void bind_scene() const {
    records.bind(gpu::kBindRecords);
    objects.bind(gpu::kBindObjects);
    nodes.bind(gpu::kBindNodes);
    materials.bind(gpu::kBindMaterials);
    lights.bind(gpu::kBindLights);
    texels.bind(gpu::kBindTexels);
  }
};

template <class T>
gl::Buffer buffer_of(const std::vector<T>& v) {
  return gl::Buffer(v.data(), v.size() * sizeof(T));
}

class OpenGLBackend : public Backend {
 public:
  OpenGLBackend() : context_(std::make_unique<gl::EglContext>()) {
    stats_.info["device"] = context_->description();
    stats_.info["precision"] = "double geometry, float32 shading";
  }

  ~OpenGLBackend() override {
    gl::EglContext::Current current(*context_);
    state_.reset();
  }

  void prepare(const Scene& scene) override {
    gl::EglContext::Current current(*context_);
    auto start = std::chrono::steady_clock::now();
    scene_ = &scene;
    state_.reset();
    auto state = std::make_unique<GpuState>();
    state->packed = gpu::pack_scene(scene);
    const gpu::PackedScene& p = state->packed;
    check_limits(p);
    state->records = buffer_of(p.records);
    state->objects = buffer_of(p.objects);
    state->nodes = buffer_of(p.nodes);
    state->materials = buffer_of(p.materials);
    state->lights = buffer_of(p.lights);
    state->texels = buffer_of(p.texels);
    glFinish();
    check_gl("scene upload");
    state_ = std::move(state);
    stats_.ms["build"] = ms_since(start);
  }

  Image render(const RenderSettings& settings) override {
    gl::EglContext::Current current(*context_);
    GLuint program = program_for(false);
    auto start = std::chrono::steady_clock::now();
    const ImageSettings& s = settings.image;
    GpuFrame frame = gpu::frame_for(state_->packed, settings.camera.value_or(scene_->camera), settings);
    gl::Buffer frame_buffer = frame_buffer_for(frame, gpu::sample_offsets(s.spp));
    auto [tw, th] = tile_size(s);
    gl::Buffer output(nullptr, gpu::kOutputHeaderBytes + size_t(tw) * th * sizeof(GpuPixel));
    state_->bind_scene();
    frame_buffer.bind(gpu::kBindFrame);
    output.bind(gpu::kBindOutput);
    glUseProgram(program);

    Image image = blank_image(settings);
    std::vector<GpuPixel> pixels(size_t(tw) * th);
    uint32_t counters[gpu::kRayCounterCount];
    const int tiles_x = (s.width + tw - 1) / tw, tiles_y = (s.height + th - 1) / th;
    for (int ty = 0; ty < tiles_y; ++ty) {
      for (int tx = 0; tx < tiles_x; ++tx) {
        const int x0 = tx * tw, y0 = ty * th, w = std::min(tw, s.width - x0), h = std::min(th, s.height - y0);
        const uint32_t zero[gpu::kRayCounterCount] = {};
        output.write(0, sizeof zero, zero);
        glUniform4i(0, x0, y0, w, h);
        glDispatchCompute(GLuint((w + 7) / 8), GLuint((h + 7) / 8), 1);
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        output.read(0, sizeof counters, counters);
        output.read(gpu::kOutputHeaderBytes, size_t(w) * h * sizeof(GpuPixel), pixels.data());
        check_gl("rendering");
        store_tile(image, settings, pixels, x0, y0, w, h);
        add_counters(counters);
        if (settings.progress) settings.progress(double(ty * tiles_x + tx + 1) / (tiles_x * tiles_y));
      }
    }
    stats_.ms["render"] += ms_since(start);
    return image;
  }

  std::vector<TraceResult> trace(std::span<const TraceQuery> rays) override {
    gl::EglContext::Current current(*context_);
    GLuint program = program_for(true);
    auto start = std::chrono::steady_clock::now();
    RenderSettings settings;
    GpuFrame frame = gpu::frame_for(state_->packed, scene_->camera, settings);
    std::vector<TraceResult> results(rays.size());
    state_->bind_scene();
    glUseProgram(program);
    for (size_t first = 0; first < rays.size(); first += kTraceRaysPerDispatch) {
      const size_t n = std::min(kTraceRaysPerDispatch, rays.size() - first);
      frame.flags[1] = int32_t(n);
      gl::Buffer frame_buffer = frame_buffer_for(frame, {});
      std::vector<GpuTraceRay> io(n);
      for (size_t i = 0; i < n; ++i) {
        const TraceQuery& q = rays[first + i];
        io[i] = GpuTraceRay{{q.origin.x, q.origin.y, q.origin.z, q.tmin}, {q.dir.x, q.dir.y, q.dir.z, 0.0}, {}, {}, {}};
      }
      gl::Buffer io_buffer = buffer_of(io);
      frame_buffer.bind(gpu::kBindFrame);
      io_buffer.bind(gpu::kBindOutput);
      glUniform4i(0, 0, 0, 0, 0);
      glDispatchCompute(GLuint((n + kTraceLocalSize - 1) / kTraceLocalSize), 1, 1);
      glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
      io_buffer.read(0, n * sizeof(GpuTraceRay), io.data());
      check_gl("tracing");
      for (size_t i = 0; i < n; ++i) {
        TraceResult& r = results[first + i];
        r.t = io[i].t_normal[0];
        r.id = io[i].id[0];
        r.normal = {io[i].t_normal[1], io[i].t_normal[2], io[i].t_normal[3]};
      }
    }
    stats_.rays += rays.size();
    stats_.rays_by_kind["trace"] += rays.size();
    stats_.ms["render"] += ms_since(start);
    return results;
  }

  BackendStats stats() const override { return stats_; }

 private:
  void check_limits(const gpu::PackedScene& p) const {
    GLint64 max_block = 0;
    glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &max_block);
    const size_t largest = std::max({p.records.size() * sizeof(double), p.objects.size() * sizeof(gpu::GpuObject),
                                     p.nodes.size() * sizeof(gpu::GpuNode), p.texels.size() * sizeof(glm::vec4)});
    if (max_block > 0 && largest > size_t(max_block))
      throw RuntimeError("the scene needs a " + std::to_string(largest) + "-byte storage buffer; this OpenGL driver allows " +
                         std::to_string(max_block));
  }

  // The render or trace program, generated and built on first use.
  GLuint program_for(bool trace) {
    if (!state_) throw RuntimeError("opengl backend: render or trace before prepare");
    GLuint& program = trace ? state_->trace_program : state_->render_program;
    if (program) return program;
    gpu::KernelOptions options;
    options.trace = trace;
    options.all_features = gpu::all_features_forced();
    options.api_glue = kApiGlue;
    if (trace) {
      options.local_size_x = kTraceLocalSize;
      options.local_size_y = 1;
    }
    gpu::KernelSource kernel = gpu::generate_kernel(state_->packed, options);
    gl::ProgramStats build;
    program = gl::build_program(kernel.text, context_->driver_identity(), build);
    auto start = std::chrono::steady_clock::now();
    warm_up(program);
    stats_.kernel_features = kernel.features;
    stats_.ms["compile"] += build.ms + ms_since(start);
    stats_.counters["gl_compile_shader_calls"] += build.compile_calls;
    stats_.counters["gl_link_program_calls"] += build.link_calls;
    stats_.info["program_cache"] = build.cache;
    if (!build.cache_file.empty()) stats_.info["program_cache_file"] = build.cache_file.string();
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

  static gl::Buffer frame_buffer_for(const GpuFrame& frame, const std::vector<glm::dvec2>& offsets) {
    std::vector<unsigned char> bytes(sizeof frame + offsets.size() * sizeof(glm::dvec2));
    std::memcpy(bytes.data(), &frame, sizeof frame);
    if (!offsets.empty()) std::memcpy(bytes.data() + sizeof frame, offsets.data(), offsets.size() * sizeof(glm::dvec2));
    return gl::Buffer(bytes.data(), bytes.size());
  }

  static Image blank_image(const RenderSettings& settings) {
    Image image;
    image.width = settings.image.width;
    image.height = settings.image.height;
    const size_t n = size_t(image.width) * image.height;
    image.rgb.assign(n * 3, 0.0f);
    if (settings.aov_id) image.id.assign(n, -1.0f);
    if (settings.aov_path) image.path.assign(n, 0.0f);
    return image;
  }

  static void store_tile(Image& image, const RenderSettings& settings, const std::vector<GpuPixel>& pixels, int x0,
                         int y0, int w, int h) {
    for (int j = 0; j < h; ++j) {
      for (int i = 0; i < w; ++i) {
        const GpuPixel& px = pixels[size_t(j) * w + i];
        const size_t p = size_t(y0 + j) * image.width + (x0 + i);
        std::copy_n(px.rgb, 3, &image.rgb[p * 3]);
        if (settings.aov_id) image.id[p] = px.id;
        if (settings.aov_path) image.path[p] = px.path;
      }
    }
  }

  void add_counters(const uint32_t counters[]) {
    static const char* kinds[] = {"camera", "shadow", "reflect", "refract", "alpha", "shade1"};
    for (int k = 0; k < 6; ++k) {
      stats_.rays_by_kind[kinds[k]] += counters[k];
      stats_.rays += counters[k];
    }
  }

  std::unique_ptr<gl::EglContext> context_;
  std::unique_ptr<GpuState> state_;
  const Scene* scene_ = nullptr;
  BackendStats stats_;
};

void probe(PrismBackendProbe* out) {
  try {
    gl::EglContext context;
    out->usable = 1;
    std::snprintf(out->reason, sizeof out->reason, "%s", context.description().c_str());
  } catch (const std::exception& e) {
    out->usable = 0;
    std::snprintf(out->reason, sizeof out->reason, "%s", e.what());
  }
}

Backend* create() { return new OpenGLBackend(); }

const PrismBackendDesc kDesc = {PRISM_BACKEND_ABI_VERSION, sizeof(PrismBackendDesc), "opengl", "1.0.0", 40, probe, create};

}  // namespace
}  // namespace prism

extern "C" PRISM_EXPORT const PrismBackendDesc* prism_backend_entry(void) { return &prism::kDesc; }
