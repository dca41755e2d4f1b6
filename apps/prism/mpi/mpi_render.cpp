// The distributed render of mpi_render.hpp: rank 0 schedules and writes,
// the other ranks render tiles. With one rank, rank 0 renders it all.
#include "mpi_render.hpp"

#include <mpi.h>
#include <tbb/global_control.h>
#include <stdlib.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <deque>
#include <fstream>
#include <map>
#include <optional>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>

#include "prism/cancel.hpp"
#include "prism/errors.hpp"
#include "prism/image_io.hpp"
#include "prism/registry.hpp"
#include "prism/scene_loader.hpp"

namespace prism::cli {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

enum Tag : int { kReady = 1, kWork, kResult, kFailed, kStats };

constexpr int kTilesAhead = 4;  // tiles given to a rank at a time

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// Seconds spent inside MPI calls, per rank: the scheduling overhead.
struct MpiClock {
  double seconds = 0;
  template <class Call>
  void operator()(Call call) {
    const auto start = Clock::now();
    call();
    seconds += seconds_since(start);
  }
};

// ---- bytes: the scene bundle and the messages are flat byte strings

class Writer {
 public:
  template <class T>
  void pod(const T& value) {
    bytes_.append(reinterpret_cast<const char*>(&value), sizeof value);
  }
  void text(const std::string& s) {
    pod(uint64_t(s.size()));
    bytes_ += s;
  }
  template <class T>
  void array(const std::vector<T>& v) {
    pod(uint64_t(v.size()));
    bytes_.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
  }
  std::string& bytes() { return bytes_; }

 private:
  std::string bytes_;
};

class Reader {
 public:
  explicit Reader(const std::string& bytes) : bytes_(bytes) {}
  template <class T>
  T pod() {
    T value;
    take(&value, sizeof value);
    return value;
  }
  std::string text() {
    std::string s(size_t(pod<uint64_t>()), '\0');
    take(s.data(), s.size());
    return s;
  }
  template <class T>
  std::vector<T> array() {
    std::vector<T> v(size_t(pod<uint64_t>()));
    take(v.data(), v.size() * sizeof(T));
    return v;
  }

 private:
  void take(void* out, size_t n) {
    if (at_ + n > bytes_.size()) throw RuntimeError("mpi: a message from another rank is truncated");
    std::memcpy(out, bytes_.data() + at_, n);
    at_ += n;
  }
  const std::string& bytes_;
  size_t at_ = 0;
};

// ---- the scene bundle: the scene text with its textures renamed to files
// shipped beside it, the render settings and the cameras

struct Bundle {
  std::string scene_name;  // the file rank 0 read, for messages
  std::string scene_json;
  std::vector<std::pair<std::string, std::string>> files;  // bundle name, bytes
  RenderSettings settings;
  std::vector<Camera> cameras;
};

std::string read_bytes(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream out;
  out << in.rdbuf();
  if (!in && !in.eof()) throw InputError(file.string() + ": cannot read");
  return out.str();
}

// The texture paths of the scene text, rewritten to "t<i><ext>" with the files' bytes beside.
Bundle make_bundle(const MpiJob& job) {
  Bundle bundle;
  bundle.scene_name = job.scene_file.string();
  nlohmann::json root = nlohmann::json::parse(read_scene_text(job.scene_file));
  const fs::path base = job.scene_file.parent_path();
  if (auto textures = root.find("textures"); textures != root.end()) {
    int index = 0;
    for (auto& entry : *textures) {
      std::string& path = entry.is_string() ? entry.get_ref<std::string&>() : entry["path"].get_ref<std::string&>();
      const fs::path source = fs::path(path).is_absolute() ? fs::path(path) : base / path;
      const std::string name = "t" + std::to_string(index++) + source.extension().string();
      bundle.files.emplace_back(name, read_bytes(source));
      path = name;
    }
  }
  bundle.scene_json = root.dump();
  bundle.settings = job.settings;
  bundle.cameras = job.cameras;
  return bundle;
}

std::string serialize(const Bundle& b) {
  Writer w;
  w.text(b.scene_name);
  w.text(b.scene_json);
  w.pod(uint64_t(b.files.size()));
  for (const auto& [name, bytes] : b.files) {
    w.text(name);
    w.text(bytes);
  }
  w.pod(b.settings.image);
  w.pod(uint8_t(b.settings.aov_id));
  w.pod(uint8_t(b.settings.aov_path));
  w.pod(uint8_t(b.settings.aov_depth));
  w.pod(uint8_t(b.settings.aov_normal));
  w.pod(uint8_t(b.settings.aov_albedo));
  w.array(b.cameras);
  return std::move(w.bytes());
}

Bundle deserialize(const std::string& bytes) {
  Reader r(bytes);
  Bundle b;
  b.scene_name = r.text();
  b.scene_json = r.text();
  const auto files = r.pod<uint64_t>();
  for (uint64_t i = 0; i < files; ++i) {
    std::string name = r.text();
    b.files.emplace_back(std::move(name), r.text());
  }
  b.settings.image = r.pod<ImageSettings>();
  b.settings.aov_id = r.pod<uint8_t>() != 0;
  b.settings.aov_path = r.pod<uint8_t>() != 0;
  b.settings.aov_depth = r.pod<uint8_t>() != 0;
  b.settings.aov_normal = r.pod<uint8_t>() != 0;
  b.settings.aov_albedo = r.pod<uint8_t>() != 0;
  b.cameras = r.array<Camera>();
  return b;
}

// Rank 0's bytes on every rank, in pieces MPI's int counts can hold. Empty: rank 0 gave up.
std::string broadcast(std::string bytes, MpiClock& clock) {
  uint64_t size = bytes.size();
  clock([&] { MPI_Bcast(&size, 1, MPI_UINT64_T, 0, MPI_COMM_WORLD); });
  bytes.resize(size_t(size));
  constexpr uint64_t kPiece = uint64_t(1) << 30;
  for (uint64_t at = 0; at < size; at += kPiece)
    clock([&] { MPI_Bcast(bytes.data() + at, int(std::min(kPiece, size - at)), MPI_BYTE, 0, MPI_COMM_WORLD); });
  return bytes;
}

// The bundle's scene, loaded from its files in a private folder.
Scene load_bundle(const Bundle& bundle, Registry& registry) {
  std::string pattern = (fs::temp_directory_path() / "prism-mpi-XXXXXX").string();
  if (!mkdtemp(pattern.data())) throw RuntimeError("mpi: cannot make a temporary folder in " + fs::temp_directory_path().string());
  const fs::path folder = pattern;
  struct Remove {
    fs::path folder;
    ~Remove() {
      std::error_code ec;
      fs::remove_all(folder, ec);
    }
  } remove{folder};
  for (const auto& [name, bytes] : bundle.files) {
    std::ofstream out(folder / name, std::ios::binary);
    out << bytes;
    if (!out) throw RuntimeError("mpi: cannot write " + (folder / name).string());
  }
  return load_scene_from_string(bundle.scene_json, folder, registry, bundle.scene_name);
}

// ---- units of work and their results

struct Unit {
  int32_t frame = -1;  // -1: stop
  PixelRect rect;
};

std::vector<Unit> units_of(const RenderSettings& settings, size_t frames, int tile) {
  std::vector<Unit> units;
  const ImageSettings& image = settings.image;
  for (size_t f = 0; f < frames; ++f)
    for (int y = 0; y < image.height; y += tile)
      for (int x = 0; x < image.width; x += tile)
        units.push_back({int32_t(f), {x, y, std::min(tile, image.width - x), std::min(tile, image.height - y)}});
  return units;
}

std::string result_bytes(const Unit& unit, const Image& tile) {
  Writer w;
  w.pod(unit);
  w.array(tile.rgb);
  w.array(tile.id);
  w.array(tile.path);
  w.array(tile.depth);
  w.array(tile.normal);
  w.array(tile.albedo);
  return std::move(w.bytes());
}

// Copies the rows of a tile's channel (`per_pixel` floats a pixel; empty:
// not asked for) into the frame's.
void copy_tile_channel(const std::vector<float>& tile, std::vector<float>& frame, const PixelRect& t, int frame_width,
                       size_t per_pixel) {
  if (tile.empty()) return;
  for (int row = 0; row < t.height; ++row) {
    const size_t from = size_t(row) * size_t(t.width), to = size_t(t.y + row) * size_t(frame_width) + size_t(t.x);
    std::copy_n(tile.begin() + std::ptrdiff_t(from * per_pixel), size_t(t.width) * per_pixel,
                frame.begin() + std::ptrdiff_t(to * per_pixel));
  }
}

// Copies a tile into its frame; returns the pixels it covered.
size_t store_result(const std::string& bytes, std::vector<Image>& frames) {
  Reader r(bytes);
  const Unit unit = r.pod<Unit>();
  Image& image = frames.at(size_t(unit.frame));
  const PixelRect& t = unit.rect;
  // In result_bytes' order.
  copy_tile_channel(r.array<float>(), image.rgb, t, image.width, 3);
  copy_tile_channel(r.array<float>(), image.id, t, image.width, 1);
  copy_tile_channel(r.array<float>(), image.path, t, image.width, 1);
  copy_tile_channel(r.array<float>(), image.depth, t, image.width, 1);
  copy_tile_channel(r.array<float>(), image.normal, t, image.width, 3);
  copy_tile_channel(r.array<float>(), image.albedo, t, image.width, 3);
  return size_t(t.width) * size_t(t.height);
}

Image blank(const RenderSettings& settings) {
  Image image;
  image.width = settings.image.width;
  image.height = settings.image.height;
  assign_channel(image.rgb, size_t(image.width) * size_t(image.height) * 3, 0.0f);
  assign_aovs(image, settings);
  return image;
}

void send_bytes(const std::string& bytes, int to, int tag, MpiClock& clock) {
  clock([&] { MPI_Send(bytes.data(), int(bytes.size()), MPI_BYTE, to, tag, MPI_COMM_WORLD); });
}

std::string receive_bytes(int from, int tag, MPI_Status& status, MpiClock& clock) {
  std::string bytes;
  clock([&] {
    MPI_Probe(from, tag, MPI_COMM_WORLD, &status);
    int count = 0;
    MPI_Get_count(&status, MPI_BYTE, &count);
    bytes.resize(size_t(count));
    MPI_Recv(bytes.data(), count, MPI_BYTE, status.MPI_SOURCE, status.MPI_TAG, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  });
  return bytes;
}

// What each rendering rank reports when it stops. Start-up (receiving the
// scene, loading it, starting and preparing the backend) is apart from the
// tile loop, whose time in MPI calls is the scheduling overhead.
struct WorkerStats {
  double startup = 0, loop = 0, rendering = 0, loop_in_mpi = 0;
  uint64_t tiles = 0;
  uint64_t rays = 0;     // every ray the rank's backend traced
  uint64_t threads = 0;  // the rank's TBB thread limit (--threads)
};

// ---- a rendering rank

void run_worker(const MpiRequest& request, MpiClock& clock) {
  const std::string bytes = broadcast({}, clock);
  if (bytes.empty()) return;  // rank 0 could not prepare the job, and says why
  const Bundle bundle = deserialize(bytes);
  const auto start = Clock::now();
  WorkerStats stats;
  Registry registry;
  Scene scene;
  OpenedBackend opened;
  std::string failure;
  try {
    scene = load_bundle(bundle, registry);
    opened = open_backend(registry, request.backend);
    opened.backend->prepare(scene);
  } catch (const std::exception& e) {
    failure = e.what();
  }
  Writer ready;
  ready.text(failure);
  ready.text(opened.name);  // "auto" resolved on this rank, for the summary line
  send_bytes(ready.bytes(), 0, kReady, clock);
  stats.startup = seconds_since(start);
  const double mpi_before_loop = clock.seconds;
  // A tile's result goes out while the next renders: rank 0 takes it when it
  // next polls. One send in flight at a time, its bytes kept alive.
  std::string sending;
  MPI_Request send_request = MPI_REQUEST_NULL;
  while (failure.empty()) {
    Unit unit;
    clock([&] { MPI_Recv(&unit, sizeof unit, MPI_BYTE, 0, kWork, MPI_COMM_WORLD, MPI_STATUS_IGNORE); });
    if (unit.frame < 0) break;
    RenderSettings settings = bundle.settings;
    settings.camera = bundle.cameras.at(size_t(unit.frame));
    settings.region = unit.rect;
    const auto render_start = Clock::now();
    try {
      const Image tile = opened.backend->render(settings);
      stats.rendering += seconds_since(render_start);
      ++stats.tiles;
      std::string bytes = result_bytes(unit, tile);
      clock([&] {
        MPI_Wait(&send_request, MPI_STATUS_IGNORE);
        sending = std::move(bytes);
        MPI_Isend(sending.data(), int(sending.size()), MPI_BYTE, 0, kResult, MPI_COMM_WORLD, &send_request);
      });
    } catch (const std::exception& e) {
      failure = e.what();
      Writer failed;
      failed.text(failure);
      send_bytes(failed.bytes(), 0, kFailed, clock);
    }
  }
  clock([&] { MPI_Wait(&send_request, MPI_STATUS_IGNORE); });
  stats.loop = seconds_since(start) - stats.startup;
  stats.loop_in_mpi = clock.seconds - mpi_before_loop;
  if (opened.backend) stats.rays = opened.backend->stats().rays;
  stats.threads = tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism);
  clock([&] { MPI_Send(&stats, sizeof stats, MPI_BYTE, 0, kStats, MPI_COMM_WORLD); });
}

// ---- rank 0: the scheduler

class Scheduler {
 public:
  Scheduler(const MpiJob& job, const std::vector<std::string>& hosts, int tile, MpiClock& clock)
      : job_(job), hosts_(hosts), clock_(clock) {
    for (const Unit& u : units_of(job.settings, job.cameras.size(), tile)) pending_.push_back(u);
    units_ = pending_.size();
    for (size_t f = 0; f < job.cameras.size(); ++f) {
      frames_.push_back(blank(job.settings));
      missing_.push_back(size_t(job.settings.image.width) * size_t(job.settings.image.height));
    }
  }

  // Runs until every rendering rank has stopped; false when tiles were left
  // undone (no rank could render them).
  bool run() {
    const int workers = int(hosts_.size()) - 1;
    while (stopped_ < workers) {
      throw_if_cancelled();
      int waiting = 0;
      MPI_Status status;
      clock_([&] { MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &waiting, &status); });
      if (waiting) {
        handle(status.MPI_SOURCE, status.MPI_TAG);
      } else {
        // Open MPI's blocking receive spins a core; rank 0 shares the
        // machine with rendering ranks, so it polls and sleeps instead.
        std::this_thread::sleep_for(std::chrono::microseconds(200));
      }
    }
    return pending_.empty() && tiles_out() == 0;
  }

  size_t units() const { return units_; }
  size_t units_left() const { return pending_.size() + tiles_out(); }
  const std::map<int, WorkerStats>& worker_stats() const { return worker_stats_; }
  // The backends the rendering ranks started, each name once, joined by "/".
  std::string backend_names() const {
    std::vector<std::string> names;
    for (const auto& [rank, name] : backends_)
      if (std::ranges::find(names, name) == names.end()) names.push_back(name);
    std::string joined;
    for (const auto& name : names) joined += (joined.empty() ? "" : "/") + name;
    return joined;
  }
  // Milliseconds from the first rank ready to the last tile back: the time
  // tiles were rendered in (writing the last frame is not rendering).
  double render_ms() const {
    if (!first_ready_ || last_tile_ < *first_ready_) return 0.0;
    return std::chrono::duration<double, std::milli>(last_tile_ - *first_ready_).count();
  }

 private:
  void handle(int rank, int tag) {
    if (tag == kStats) {
      WorkerStats stats;
      clock_([&] { MPI_Recv(&stats, sizeof stats, MPI_BYTE, rank, kStats, MPI_COMM_WORLD, MPI_STATUS_IGNORE); });
      worker_stats_[rank] = stats;
      ++stopped_;
      return;
    }
    MPI_Status status;
    const std::string bytes = receive_bytes(rank, tag, status, clock_);
    if (tag == kReady) {
      Reader r(bytes);
      const std::string failure = r.text();
      if (!failure.empty()) return warn(rank, "cannot start its backend", failure);  // it stops by itself
      backends_[rank] = r.text();
      if (!first_ready_) first_ready_ = Clock::now();
      // Two tiles each: a rank has its next tile queued while it renders one,
      // so it never waits on rank 0 between tiles.
      for (int i = 0; i < kTilesAhead; ++i) give(rank);
    } else if (tag == kResult) {
      const Unit unit = in_flight_.at(rank).front();  // a rank renders its tiles in the order given
      in_flight_.at(rank).pop_front();
      const bool frame_done = (missing_[size_t(unit.frame)] -= store_result(bytes, frames_)) == 0;
      last_tile_ = Clock::now();
      give(rank);
      release_if_done();
      // Written after the ranks have their next tiles: writing takes a while
      // (1.6 s for a 1920x1080 EXR here), and no rank should wait on it.
      if (frame_done) write_frame(size_t(unit.frame));
      return;
    } else if (tag == kFailed) {
      Reader r(bytes);
      warn(rank, "failed while rendering", r.text());
      for (const Unit& unit : in_flight_.at(rank)) pending_.push_front(unit);  // other ranks render them
      in_flight_.erase(rank);
      std::erase(idle_, rank);
      while (!idle_.empty() && !pending_.empty()) {
        const int idle = idle_.back();
        idle_.pop_back();
        give(idle);
      }
    }
    release_if_done();
  }

  // Once every tile is back, the ranks waiting for more are told to stop.
  void release_if_done() {
    if (!pending_.empty() || tiles_out() != 0) return;
    for (int idle : idle_) stop(idle);
    idle_.clear();
  }

  size_t tiles_out() const {
    size_t n = 0;
    for (const auto& [rank, units] : in_flight_) n += units.size();
    return n;
  }

  // The next tile, or a wait: a tile still out may fail and come back. A
  // rank waits only once it has no tile queued.
  void give(int rank) {
    if (pending_.empty()) {
      if (in_flight_[rank].empty() && std::ranges::find(idle_, rank) == idle_.end()) idle_.push_back(rank);
      return;
    }
    const Unit unit = pending_.front();
    pending_.pop_front();
    in_flight_[rank].push_back(unit);
    clock_([&] { MPI_Send(&unit, sizeof unit, MPI_BYTE, rank, kWork, MPI_COMM_WORLD); });
  }

  void stop(int rank) {
    const Unit unit;  // frame -1
    clock_([&] { MPI_Send(&unit, sizeof unit, MPI_BYTE, rank, kWork, MPI_COMM_WORLD); });
  }

  void write_frame(size_t frame) {
    write_image(frames_[frame], job_.outputs[frame]);
    frames_[frame] = Image{};  // written: its memory goes back
  }

  void warn(int rank, const char* what, const std::string& why) const {
    std::fprintf(stderr, "prism: mpi: rank %d on %s %s: %s; its tiles go to the other ranks\n", rank,
                 hosts_[size_t(rank)].c_str(), what, why.c_str());
  }

  const MpiJob& job_;
  const std::vector<std::string>& hosts_;
  MpiClock& clock_;
  std::deque<Unit> pending_;
  std::map<int, std::deque<Unit>> in_flight_;  // per rank, in the order sent
  std::vector<int> idle_;
  std::vector<Image> frames_;
  std::vector<size_t> missing_;  // per frame, pixels not back yet
  std::map<int, WorkerStats> worker_stats_;
  std::map<int, std::string> backends_;  // per rank that started one
  std::optional<Clock::time_point> first_ready_;
  Clock::time_point last_tile_;
  size_t units_ = 0;
  int stopped_ = 0;
};

// ---- the run

std::vector<std::string> gather_hosts(int rank, int size, MpiClock& clock) {
  char name[MPI_MAX_PROCESSOR_NAME] = {};
  int length = 0;
  MPI_Get_processor_name(name, &length);
  std::vector<char> all(size_t(size) * MPI_MAX_PROCESSOR_NAME);
  clock([&] { MPI_Gather(name, MPI_MAX_PROCESSOR_NAME, MPI_CHAR, all.data(), MPI_MAX_PROCESSOR_NAME, MPI_CHAR, 0, MPI_COMM_WORLD); });
  std::vector<std::string> hosts;
  if (rank == 0)
    for (int r = 0; r < size; ++r) hosts.emplace_back(&all[size_t(r) * MPI_MAX_PROCESSOR_NAME]);
  return hosts;
}

// One rank: rank 0 renders every frame itself, whole.
void render_alone(const MpiJob& job, const MpiRequest& request) {
  Registry registry;
  const Scene scene = load_scene(job.scene_file, registry);
  OpenedBackend opened = open_backend(registry, request.backend);
  opened.backend->prepare(scene);
  double rendering = 0;  // seconds, writing the frames left out (as without --mpi)
  for (size_t f = 0; f < job.cameras.size(); ++f) {
    RenderSettings settings = job.settings;
    settings.camera = job.cameras[f];
    const auto start = Clock::now();
    Image image = opened.backend->render(settings);
    rendering += seconds_since(start);
    write_image(image, job.outputs[f]);
  }
  if (request.written) request.written(opened.name, 1000.0 * rendering, opened.backend->stats().rays);
}

void report(const Scheduler& scheduler, const std::vector<std::string>& hosts, double wall, const MpiClock& clock,
            const MpiRequest& request) {
  double loop = 0, loop_in_mpi = 0, rendering = 0, startup = 0;
  nlohmann::json ranks = nlohmann::json::array();
  for (const auto& [rank, s] : scheduler.worker_stats()) {
    loop += s.loop;
    loop_in_mpi += s.loop_in_mpi;
    rendering += s.rendering;
    startup = std::max(startup, s.startup);
    ranks.push_back({{"rank", rank},          {"host", hosts[size_t(rank)]}, {"tiles", s.tiles},
                     {"startup_s", s.startup}, {"tile_loop_s", s.loop},      {"rendering_s", s.rendering},
                     {"tile_loop_in_mpi_s", s.loop_in_mpi}, {"rays", s.rays}, {"threads", s.threads}});
  }
  const double overhead = loop > 0 ? loop_in_mpi / loop : 0;
  std::fprintf(stderr,
               "prism: mpi: %zu ranks, %zu rendering: %zu tiles of %d px in %.3f s (start-up %.3f s); "
               "scheduling overhead (time in MPI calls over the tile loop) %.2f%%\n",
               hosts.size(), scheduler.worker_stats().size(), scheduler.units(), request.tile, wall, startup,
               100 * overhead);
  if (request.stats.empty()) return;
  const nlohmann::json stats = {{"ranks", hosts.size()},       {"tiles", scheduler.units()},
                                {"tile", request.tile},        {"wall_s", wall},
                                {"startup_s", startup},        {"rank0_in_mpi_s", clock.seconds},
                                {"scheduling_overhead", overhead}, {"rendering_s", rendering},
                                {"workers", ranks}};
  write_text_file_atomically(request.stats, stats.dump(2) + "\n");
}

// Rank 0's preparation: the job and, with other ranks, its bundle. A
// failure tells the other ranks to stop (an empty bundle) and is rethrown.
std::pair<MpiJob, std::string> prepare(const MpiRequest& request, size_t ranks, MpiClock& clock) {
  try {
    MpiJob job = request.prepare_job();
    std::string bundle = ranks > 1 ? serialize(make_bundle(job)) : std::string();
    return {std::move(job), std::move(bundle)};
  } catch (...) {
    if (ranks > 1) broadcast({}, clock);
    throw;
  }
}

// The exit status: 1 when no rank could render some tiles (every rank has
// stopped by then, and the frames they belong to were not written).
int run_rank0(const MpiRequest& request, const MpiJob& job, std::string bundle, const std::vector<std::string>& hosts,
              MpiClock& clock) {
  const auto start = Clock::now();
  if (hosts.size() == 1) {
    render_alone(job, request);
    return 0;
  }
  broadcast(std::move(bundle), clock);
  Scheduler scheduler(job, hosts, request.tile, clock);
  if (!scheduler.run()) {
    std::fprintf(stderr, "prism: error: mpi: no rank could render the last %zu tiles (see above)\n",
                 scheduler.units_left());
    return 1;
  }
  const double render_ms = scheduler.render_ms();
  report(scheduler, hosts, seconds_since(start), clock, request);
  if (request.written) {
    uint64_t rays = 0;
    for (const auto& [rank, s] : scheduler.worker_stats()) rays += s.rays;
    request.written(scheduler.backend_names(), render_ms, rays);
  }
  return 0;
}

}  // namespace
}  // namespace prism::cli

extern "C" __attribute__((visibility("default"))) int prism_mpi_render(const prism::cli::MpiRequest& request) {
  using namespace prism::cli;
  int provided = 0;
  MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  MpiClock clock;
  const std::vector<std::string> hosts = gather_hosts(rank, size, clock);
  if (rank != 0) {
    run_worker(request, clock);
    MPI_Finalize();
    return 0;
  }
  std::pair<MpiJob, std::string> prepared;
  try {
    prepared = prepare(request, hosts.size(), clock);
  } catch (...) {
    MPI_Finalize();  // every other rank has stopped too
    throw;
  }
  // From here on the other ranks wait on rank 0: a failure must end them all.
  try {
    const int status = run_rank0(request, prepared.first, std::move(prepared.second), hosts, clock);
    MPI_Finalize();
    return status;
  } catch (const prism::Cancelled& e) {
    std::fprintf(stderr, "prism: %s; the output files were left as they were\n", e.what());
    MPI_Abort(MPI_COMM_WORLD, 128 + e.signal());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "prism: error: %s\n", e.what());
    MPI_Abort(MPI_COMM_WORLD, 1);
  }
  return 1;
}
