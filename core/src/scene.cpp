#include "prism/registry.hpp"
#include "prism/scene.hpp"

namespace prism {

std::vector<std::string> Scene::plugin_names() const {
  std::vector<std::string> names;
  for (const auto& plugin : plugins) names.push_back(plugin->name());
  return names;
}

size_t Scene::packed_object_bytes() const {
  size_t bytes = 0;
  for (const Object& object : objects) bytes += sizeof(Object) + object.record_heap.size();
  return bytes;
}

}  // namespace prism
