#include "test_support.hpp"

#include <fcntl.h>
#include <sys/mount.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

#include "prism/scene_loader.hpp"

extern char** environ;

namespace fs = std::filesystem;

namespace prism::test {

fs::path source_dir() { return PRISM_SOURCE_DIR; }
fs::path binary_dir() { return PRISM_BINARY_DIR; }

const std::vector<std::string>& backend_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> found = Registry().backend_names_found();
    std::sort(found.begin(), found.end());
    found.erase(std::unique(found.begin(), found.end()), found.end());
    return found;
  }();
  return names;
}

std::vector<std::string> required_backends() {
  std::vector<std::string> names;
  const char* env = std::getenv("PRISM_REQUIRE_BACKENDS");
  std::stringstream list(env ? env : "");
  for (std::string name; std::getline(list, name, ',');) {
    name.erase(0, name.find_first_not_of(" \t"));
    name.erase(name.find_last_not_of(" \t") + 1);
    if (!name.empty()) names.push_back(name);
  }
  return names;
}

bool backend_required(const std::string& name) {
  const auto required = required_backends();
  return std::find(required.begin(), required.end(), name) != required.end();
}

std::string backend_param_name(const testing::TestParamInfo<std::string>& info) {
  std::string name = info.param;
  for (char& c : name) {
    const bool alnum = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9');
    if (!alnum) c = '_';
  }
  return name;
}

fs::path fresh_temp_dir() {
  const auto* info = testing::UnitTest::GetInstance()->current_test_info();
  std::string name = "prism_" + std::to_string(getpid());
  if (info) name += std::string("_") + info->test_suite_name() + "_" + info->name();
  for (char& c : name) {
    if (c == '/') c = '_';
  }
  const fs::path dir = fs::path(testing::TempDir()) / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::vector<std::string> backends_except(const std::string& name) {
  std::vector<std::string> names = backend_names();
  names.erase(std::remove(names.begin(), names.end(), name), names.end());
  return names;
}

std::vector<std::string> gpu_backend_names() {
  std::vector<std::string> names = backend_names();
  std::erase_if(names, [](const std::string& name) { return name != "opengl" && name != "vulkan"; });
  return names;
}

bool require_backend_or_skip(const std::string& name) {
  // Probing can be slow (a GPU backend opens a device): once per backend per process.
  static Registry registry;
  static std::map<std::string, std::string> why_not;  // backend -> "" when usable
  auto it = why_not.find(name);
  if (it == why_not.end()) {
    std::string reason;
    try {
      const PrismBackendProbe probe = registry.backend(name)->probe();
      if (!probe.usable) {
        reason = "cannot run here: " + std::string(probe.reason, strnlen(probe.reason, sizeof probe.reason));
      }
    } catch (const std::exception& e) {
      reason = std::string("does not load: ") + e.what();
    }
    it = why_not.emplace(name, reason).first;
  }
  const std::string& reason = it->second;
  if (reason.empty()) return true;
  if (backend_required(name) || reason.rfind("does not load", 0) == 0) {
    const std::string message = "backend '" + name + "' " + reason +
                                (backend_required(name) ? " (it is in PRISM_REQUIRE_BACKENDS)" : "");
    // FAIL() without its `return`: a fatal failure, so a fixture's SetUp skips the body.
    GTEST_MESSAGE_(message.c_str(), testing::TestPartResult::kFatalFailure);
  } else {
    const std::string message = "backend '" + name + "' " + reason;
    GTEST_MESSAGE_(message.c_str(), testing::TestPartResult::kSkip);  // GTEST_SKIP() without its `return`
  }
  return false;
}

void BackendTest::SetUp() {
  const std::string name = backend_name();
  if (!require_backend_or_skip(name)) return;
  plugin_ = registry_.backend(name);
}

Scene BackendTest::load(const std::string& json, const fs::path& base_dir) {
  return load_scene_from_string(json, base_dir, registry_, "<test scene>");
}

Image BackendTest::render(const Scene& scene, const RenderSettings& settings) {
  std::unique_ptr<Backend> backend = plugin_->create();
  backend->prepare(scene);
  return backend->render(settings);
}

Image BackendTest::render(const Scene& scene) {
  RenderSettings settings;
  settings.image = scene.image;
  return render(scene, settings);
}

std::vector<TraceResult> BackendTest::trace(const Scene& scene, std::span<const TraceQuery> rays,
                                            BackendStats* stats) {
  std::unique_ptr<Backend> backend = plugin_->create();
  backend->prepare(scene);
  std::vector<TraceResult> hits = backend->trace(rays);
  if (stats) *stats = backend->stats();
  return hits;
}

std::string read_file(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

void write_file(const std::filesystem::path& file, const std::string& contents) {
  std::ofstream out(file, std::ios::binary);
  out << contents;
  out.close();
  if (!out) throw std::runtime_error("cannot write " + file.string());
}

int spawn_with_output(const std::vector<std::string>& args, const std::vector<std::string>& env,
                      const fs::path& out_file, const fs::path& err_file, const fs::path& cwd, int& pid) {
  std::vector<std::string> arg_text = args, env_text = env;
  std::vector<char*> argv, envp;
  for (auto& a : arg_text) argv.push_back(a.data());
  argv.push_back(nullptr);
  for (auto& e : env_text) envp.push_back(e.data());
  envp.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, out_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, err_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (!cwd.empty()) posix_spawn_file_actions_addchdir_np(&actions, cwd.c_str());
  pid_t child = 0;
  const int rc = posix_spawnp(&child, argv[0], &actions, nullptr, argv.data(), env.empty() ? environ : envp.data());
  posix_spawn_file_actions_destroy(&actions);
  pid = child;
  return rc;
}

CapturedRun run_captured(const std::vector<std::string>& args, const std::vector<std::string>& env,
                         const fs::path& out_file, const fs::path& err_file) {
  int pid = 0;
  const int rc = spawn_with_output(args, env, out_file, err_file, {}, pid);
  CapturedRun run;
  if (rc != 0) {
    run.start_error = "cannot start " + args[0] + ": " + std::strerror(rc);
    return run;
  }
  run.started = true;
  int wstatus = 0;
  while (::waitpid(pid, &wstatus, 0) < 0 && errno == EINTR) {
  }
  run.exited = WIFEXITED(wstatus);
  if (run.exited) run.status = WEXITSTATUS(wstatus);
  if (WIFSIGNALED(wstatus)) run.signal = WTERMSIG(wstatus);
  run.out = read_file(out_file);
  run.err = read_file(err_file);
  return run;
}

namespace {

// CRC-32 (ISO-HDLC, as PNG chunks use), bit by bit: the inputs are a few bytes.
uint32_t crc32(const std::string& bytes) {
  uint32_t crc = 0xffffffffu;
  for (unsigned char byte : bytes) {
    crc ^= byte;
    for (int bit = 0; bit < 8; ++bit) crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1u)));
  }
  return ~crc;
}

std::string big_endian(uint32_t v) {
  return {char(v >> 24), char(v >> 16), char(v >> 8), char(v)};
}

std::string png_chunk(const std::string& type, const std::string& data) {
  return big_endian(uint32_t(data.size())) + type + data + big_endian(crc32(type + data));
}

}  // namespace

std::string png_claiming_size(uint32_t width, uint32_t height) {
  // 8-bit RGB, deflate, no filter method, no interlace.
  const std::string ihdr = big_endian(width) + big_endian(height) + std::string("\x08\x02\x00\x00\x00", 5);
  // A zlib stream of one stored byte (0: the first row's filter type), so the header is followed by image data.
  const std::string idat("\x78\x01\x01\x01\x00\xfe\xff\x00\x00\x01\x00\x01", 12);
  return std::string("\x89PNG\r\n\x1a\n", 8) + png_chunk("IHDR", ihdr) + png_chunk("IDAT", idat) +
         png_chunk("IEND", "");
}

std::string SmallDisk::mount(const fs::path& folder) {
  if (::geteuid() != 0) return "mounting a small tmpfs needs root";
  folder_ = folder;
  fs::create_directories(folder_);
  if (::mount("tmpfs", folder_.c_str(), "tmpfs", 0, "size=64k") != 0)
    return std::string("cannot mount a tmpfs here: ") + std::strerror(errno);
  mounted_ = true;
  return "";
}

void SmallDisk::unmount() {
  if (mounted_) ::umount2(folder_.c_str(), MNT_DETACH);
  mounted_ = false;
}

bool SmallDisk::fill() const {
  const std::string block(4096, 'x');
  FILE* out = std::fopen((folder_ / "filler").c_str(), "wb");
  if (out == nullptr) return false;
  while (std::fwrite(block.data(), 1, block.size(), out) == block.size() && std::fflush(out) == 0) {
  }
  std::fclose(out);
  return true;
}

std::vector<std::string> SmallDisk::files() const {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(folder_))
    if (entry.path().filename() != "filler") names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

}  // namespace prism::test
