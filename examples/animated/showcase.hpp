// scenes/showcase.json built in code through prism::LiveScene, and its
// animation: the glass and mirror spheres circling each other, the planet
// turning under its rings, the torus spinning and the warm lamp flying round.
#pragma once

#include <filesystem>

#include <prism/api.hpp>

namespace animated {

// The handles of what moves.
struct Showcase {
  prism::ObjectId glass, mirror, planet, torus;
  prism::LightId lamp;  // the warm point light with a visible sphere
};

// Adds the showcase's camera, textures (PNG files in `textures`), materials,
// background, lights and objects to an empty `scene`, exactly as the scene
// file has them; the image settings are left to the caller.
Showcase build_showcase(prism::LiveScene& scene, const std::filesystem::path& textures);

// Poses everything that moves at `seconds` into the animation; at 0 the
// scene is the showcase as the file has it. Each call edits only what moves,
// so a renderer sends only those objects and the lamp again.
void animate(prism::LiveScene& scene, const Showcase& showcase, double seconds);

}  // namespace animated
