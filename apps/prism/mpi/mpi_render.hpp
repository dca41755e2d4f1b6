// `prism render --mpi`: the image (or frame sequence) cut into tiles dealt
// out over MPI ranks. Lives in libprism_mpi.so, beside libprism_core.so,
// loaded only for --mpi, so that `prism` itself needs no MPI library.
//
// Rank 0 loads the scene, broadcasts it with its textures' bytes (other
// hosts need no shared file system), then hands out tiles one at a time:
// a rank asks for the next when it returns one, so fast and slow ranks
// balance. It writes each frame atomically once all its tiles are back. A
// rank that cannot start its backend says why and gets no tiles; a rank that
// dies ends the job (Open MPI 4 aborts it), and no partial file is left.
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "prism/backend.hpp"

namespace prism::cli {

// What rank 0 renders, decided once the scene is loaded.
struct MpiJob {
  std::filesystem::path scene_file;
  RenderSettings settings;                      // image size, samples, depth, AOVs
  std::vector<Camera> cameras;                  // one per frame
  std::vector<std::filesystem::path> outputs;  // one per frame
};

struct MpiRequest {
  std::string backend;  // every rank starts its own
  int tile = 64;        // tile side in pixels
  std::string stats;    // rank 0 writes the run's figures here (JSON) when set
  // Runs on rank 0 only: loads and checks everything (InputError), before
  // any rank starts a backend.
  std::function<MpiJob()> prepare_job;
  // Runs on rank 0 once every frame is written, for the summary line: the
  // backend the ranks ran (their names joined by "/" where they differ), the
  // render time in milliseconds (from the first rank ready to the last tile
  // back; with one rank, its render calls) and the rays every rank traced.
  // May be empty.
  std::function<void(const std::string& backend, double render_ms, uint64_t rays)> written;
};

}  // namespace prism::cli

extern "C" {
// Runs the whole distributed render on this rank and returns its exit status
// (0, or 1 when no rank could render); InputError and RuntimeError from
// rank 0's preparation are rethrown there after the other ranks were told.
typedef int (*PrismMpiRenderFn)(const prism::cli::MpiRequest& request);
#define PRISM_MPI_RENDER_SYMBOL "prism_mpi_render"
}
