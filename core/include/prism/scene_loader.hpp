// Reads a scene file, validates every rule of the format (errors name the
// JSON path: `objects[3].radius: must be > 0, got -1`), loads only the
// primitive plugins the scene uses and the textures it names.
#pragma once

#include <filesystem>
#include <string>

#include "prism/registry.hpp"
#include "prism/scene.hpp"

namespace prism {

// Throws InputError on any problem with the file or what it names.
Scene load_scene(const std::filesystem::path& file, Registry& registry);

// The same from JSON text; relative texture paths resolve against `base_dir`.
Scene load_scene_from_string(const std::string& json, const std::filesystem::path& base_dir,
                             Registry& registry, const std::string& source_name = "<string>");

// Checks a command-line override against the same range as the scene field.
void check_image_settings(const ImageSettings& image, const std::string& where);

}  // namespace prism
