#include "prism/registry.hpp"
#include "prism/scene.hpp"

namespace prism {

const void* Object::record() const { return record_storage.data(); }

std::vector<std::string> Scene::plugin_names() const {
  std::vector<std::string> names;
  for (const auto& plugin : plugins) names.push_back(plugin->name());
  return names;
}

}  // namespace prism
