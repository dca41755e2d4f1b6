// Progressive refinement: which samples per pixel the viewer renders next.
// While the camera moves every frame is 1 spp (the fastest); once it stops
// the same view is rendered again at 2, 4, 8, ... spp up to the scene's, and
// then nothing more until something changes. Each step is a whole render
// (backends have no sample offset to accumulate from), so the last frame is
// `prism render`'s image exactly and all the steps together cost less than
// twice that one render. No window here: unit-tested in tests/view.
#pragma once

#include <optional>

namespace prism::viewer {

class Refinement {
 public:
  // `target_spp` (>= 1): the scene's samples per pixel, where refinement ends.
  explicit Refinement(int target_spp);

  // The view changed (camera, window size): the frame shown is stale and
  // the next one is 1 spp.
  void restart();
  // The samples per pixel of the next frame to render; nothing when the
  // frame on screen is already at the target for the current view.
  std::optional<int> next_spp() const;
  // A frame at `spp` is now on screen for the current view.
  void rendered(int spp);

  bool done() const { return !next_spp(); }
  int shown_spp() const { return shown_; }  // 0: nothing current on screen
  int target_spp() const { return target_; }

 private:
  int target_;
  int shown_ = 0;
};

}  // namespace prism::viewer
