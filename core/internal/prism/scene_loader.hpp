// Reads a scene file, validates every rule of the format (errors name the
// JSON path: `objects[3].radius: must be > 0, got -1`), loads only the
// primitive plugins the scene uses and the textures it names.
#pragma once

#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

#include "prism/registry.hpp"
#include "prism/scene.hpp"

namespace prism {

// The file name that stands for standard input, and how messages name it.
inline constexpr const char* kStandardInput = "-";
inline constexpr const char* kStandardInputName = "<stdin>";

// Throws InputError on any problem with the file or what it names. The file
// "-" is standard input, its texture paths relative to the current directory.
// What loads but looks wrong is left in Scene::warnings.
Scene load_scene(const std::filesystem::path& file, Registry& registry);

// The same from JSON text; relative texture paths resolve against `base_dir`.
Scene load_scene_from_string(const std::string& json, const std::filesystem::path& base_dir,
                             Registry& registry, const std::string& source_name = "<string>");

// Each of the scene's warnings as a line "prism: warning: ..." (stderr for the command line).
void write_warnings(const Scene& scene, std::ostream& out);

// The text of a scene file ("-": standard input), refused (InputError) when it cannot be read or
// is over limits::kMaxSceneFileBytes.
std::string read_scene_text(const std::filesystem::path& file);

// A camera path: {"cameras": [camera, ...]}, each camera as a scene file's
// `camera` (errors name `cameras[i].field`). At least one camera.
std::vector<Camera> load_cameras(const std::filesystem::path& file);
std::vector<Camera> load_cameras_from_string(const std::string& json, const std::string& source_name);

// Checks a command-line override against the same range as the scene field.
void check_image_settings(const ImageSettings& image, const std::string& where);

}  // namespace prism
