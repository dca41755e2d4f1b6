// What a LiveScene holds (prism/api.hpp): the model, the JSON fragment each
// part was read from, stable ids, and the revision at which each part last
// changed, from which a Renderer works out what to send its backend again.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <unordered_map>
#include <vector>

#include "loader_parts.hpp"
#include "prism/api.hpp"

namespace prism {

struct LiveScene::State {
  explicit State(Engine& engine);

  Engine* engine;
  uint64_t serial;  // unique to this scene in the process: a renderer sees when it is handed another
  Scene scene;

  json::Json camera_doc, image_doc, background_doc;
  std::map<std::string, json::Json> texture_docs, material_docs;  // by name
  std::vector<json::Json> object_docs, light_docs;                // by index, as in `scene`
  std::vector<uint64_t> object_ids, light_ids;                    // by index
  std::unordered_map<uint64_t, size_t> object_index;              // id -> index: edits of big scenes stay O(1)
  uint64_t next_id = 1;

  // Revisions: every edit takes the next one; each stamp is the last edit of its part.
  uint64_t revision = 0;
  std::vector<uint64_t> object_stamp;  // by index
  uint64_t structure_stamp = 0;        // an object added or removed
  uint64_t materials_stamp = 0, lights_stamp = 0, textures_stamp = 0, environment_stamp = 0;

  void touch_object(size_t index);
  // Index of an id; InputError naming `path` when it is not in this scene.
  size_t index_of(ObjectId id, const std::string& path) const;
  size_t light_index_of(LightId id, const std::string& path) const;
  std::map<std::string, int> texture_names() const;
  std::map<std::string, int> material_names() const;

  ObjectId new_object_id();  // for the object just appended
  Object read_object(const json::Json& fragment, const std::string& path);
  ObjectId append_object(json::Json fragment, const std::string& path);
  void replace_object(size_t index, json::Json fragment, const std::string& path);
  LightId append_light(json::Json fragment, const std::string& path);
};

}  // namespace prism
