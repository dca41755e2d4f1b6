// Objects: the core reads the fields a primitive plugin declares, checks
// each against its declared range, then lets the plugin check the rest and
// pack its parameter record. Every message carries the JSON path.
#include <cmath>

#include "loader_parts.hpp"
#include "prism/errors.hpp"

namespace prism::loader {

using json::Json;

RotationExt read_rotation_ext(const Json& value, const std::string& path) {
  using real = long double;
  json::ObjectReader r(value, path);
  if (const Json* q = r.find("quaternion")) {
    r.require_absent("axis", "a rotation has either quaternion or axis and degrees, not both");
    r.require_absent("degrees", "a rotation has either quaternion or axis and degrees, not both");
    r.finish();
    auto v = json::read_numbers(*q, r.path_of("quaternion"), 4);
    const real n = std::sqrt(real(v[0]) * v[0] + real(v[1]) * v[1] + real(v[2]) * v[2] + real(v[3]) * v[3]);
    if (n == 0) json::fail(r.path_of("quaternion"), "must be non-zero");
    const real w = v[0] / n, x = v[1] / n, y = v[2] / n, z = v[3] / n;
    return {1 - 2 * (y * y + z * z), 2 * (x * y - w * z),     2 * (x * z + w * y),
            2 * (x * y + w * z),     1 - 2 * (x * x + z * z), 2 * (y * z - w * x),
            2 * (x * z - w * y),     2 * (y * z + w * x),     1 - 2 * (x * x + y * y)};
  }
  const glm::dvec3 given = r.required_vec3("axis");
  json::require_nonzero(given, r.path_of("axis"));
  const double degrees = r.required_number("degrees");
  r.finish();
  const real n = std::sqrt(real(given.x) * given.x + real(given.y) * given.y + real(given.z) * given.z);
  const real x = given.x / n, y = given.y / n, z = given.z / n;
  const real a = degrees * (3.14159265358979323846264338327950288L / 180), c = std::cos(a), s = std::sin(a), k = 1 - c;
  // Rodrigues' formula, right-hand rule.
  return {c + x * x * k,     x * y * k - z * s, x * z * k + y * s,
          y * x * k + z * s, c + y * y * k,     y * z * k - x * s,
          z * x * k - y * s, z * y * k + x * s, c + z * z * k};
}

glm::dmat3 rounded(const RotationExt& m) {
  glm::dmat3 out;  // glm is column-major: out[col][row]
  for (int row = 0; row < 3; ++row)
    for (int col = 0; col < 3; ++col) out[col][row] = static_cast<double>(m[size_t(3 * row + col)]);
  return out;
}

namespace {

json::Range field_range(const PrismField& f) {
  json::Range range{f.min, f.max, (f.flags & PRISM_FIELD_MIN_EXCLUSIVE) != 0, false};
  if (f.flags & PRISM_FIELD_LENGTH) {
    range.min = std::max(range.min, -json::kMaxLength);
    range.max = std::min(range.max, json::kMaxLength);
  }
  return range;
}

// Appends the field's `count` values to `values`.
void read_field(json::ObjectReader& r, const PrismField& f, std::vector<double>& values) {
  const std::string path = r.path_of(f.name);
  const Json* v = r.find(f.name);
  if (!v) {
    if ((f.flags & PRISM_FIELD_REQUIRED) || !f.defaults) r.fail_missing(f.name);
    values.insert(values.end(), f.defaults, f.defaults + f.count);
    return;
  }
  const json::Range range = field_range(f);
  if (f.kind == PRISM_FIELD_NUMBER) {
    values.push_back(json::read_number(*v, path, range));
    return;
  }
  const bool nullable = f.kind == PRISM_FIELD_ARRAY_OR_NULL;
  if (!v->is_array() || v->size() != f.count)
    json::fail(path, "must be an array of " + std::to_string(f.count) + (nullable ? " numbers or nulls" : " numbers") +
                         ", got " + json::describe(*v));
  bool all_zero = true;
  for (size_t i = 0; i < f.count; ++i) {
    const Json& e = (*v)[i];
    double x = (nullable && e.is_null()) ? f.null_value : json::read_number(e, json::index_path(path, i), range);
    all_zero = all_zero && x == 0;
    values.push_back(x);
  }
  if ((f.flags & PRISM_FIELD_NONZERO) && all_zero) json::fail(path, "must be non-zero");
}

void pack_record(const PrismPrimitiveDesc& desc, const std::vector<double>& values, Object& object) {
  desc.pack(values.data(), object.reset_record(desc.record_size));
}

void compute_world_bounds(Object& object) {
  double lo[3], hi[3];
  object.bounded = object.desc->bounds(object.record(), lo, hi) != 0;
  if (!object.bounded) return;
  // Transform the local box: centre + R*local, as |R| applied to the half extent.
  glm::dvec3 mid{(lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, (lo[2] + hi[2]) / 2};
  glm::dvec3 half{(hi[0] - lo[0]) / 2, (hi[1] - lo[1]) / 2, (hi[2] - lo[2]) / 2};
  glm::dvec3 world_mid = object.center + object.rotation * mid;
  glm::dvec3 world_half{0};
  for (int row = 0; row < 3; ++row)
    for (int col = 0; col < 3; ++col) world_half[row] += std::abs(object.rotation[col][row]) * half[col];
  object.world_bounds = {world_mid - world_half, world_mid + world_half};
}

void use_plugin(Scene& scene, const std::shared_ptr<const PrimitivePlugin>& plugin) {
  for (const auto& p : scene.plugins)
    if (p == plugin) return;
  scene.plugins.push_back(plugin);
}

}  // namespace

Object read_object(const Json& value, const std::string& path, Registry& registry,
                   const std::map<std::string, int>& materials, Scene& scene) {
  json::ObjectReader r(value, path);
  const std::string type = json::read_string(r.at("type"), r.path_of("type"));
  std::shared_ptr<const PrimitivePlugin> plugin;
  try {
    plugin = registry.primitive(type);
  } catch (const InputError& e) {
    json::fail(r.path_of("type"), e.what());
  }
  use_plugin(scene, plugin);
  const PrismPrimitiveDesc& desc = plugin->desc();
  Object object;
  object.plugin = plugin.get();
  object.desc = &desc;
  if (auto name = r.string("material")) {
    auto it = materials.find(*name);
    if (it == materials.end())
      json::fail(r.path_of("material"), json::unknown_name("material", "materials", *name, names_of(materials)));
    object.material = it->second;
  }
  if (desc.flags & PRISM_PRIMITIVE_TRANSFORMABLE) {
    object.center = r.vec3("center", {0, 0, 0}, json::kLength);
    if (const Json* rot = r.find("rotation")) {
      auto exact = std::make_shared<const RotationExt>(read_rotation_ext(*rot, r.path_of("rotation")));
      object.rotation = rounded(*exact);
      object.rotation_ext = std::move(exact);
      object.has_rotation = true;
    }
  }
  std::vector<double> values;
  for (uint32_t i = 0; i < desc.field_count; ++i) read_field(r, desc.fields[i], values);
  r.finish();
  if (desc.validate) {
    PrismError error{};
    if (desc.validate(values.data(), &error) != 0) {
      error.field[sizeof error.field - 1] = '\0';
      error.message[sizeof error.message - 1] = '\0';
      json::fail(error.field[0] ? r.path_of(error.field) : path, error.message);
    }
  }
  pack_record(desc, values, object);
  compute_world_bounds(object);
  return object;
}

}  // namespace prism::loader
