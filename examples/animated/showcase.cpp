#include "showcase.hpp"

#include <array>
#include <cmath>
#include <numbers>
#include <string>

#include <glm/gtc/quaternion.hpp>

namespace animated {

namespace {

using glm::dvec3;
using prism::MaterialDesc;
using prism::Rotation;

// Where the moving things start: the scene file's values.
constexpr dvec3 kGlassStart{-1.5, 1.0, 1.2};
constexpr dvec3 kMirrorStart{1.9, 1.0, -0.6};
constexpr dvec3 kPlanetCenter{-0.2, 1.3, -3.0};
constexpr dvec3 kPlanetTiltAxis{1, 0, -0.5};
constexpr double kPlanetTiltDegrees = 30;
constexpr dvec3 kTorusCenter{-4.6, 0.95, -2.4};
constexpr dvec3 kTorusTiltAxis{1, 0.2, 0};
constexpr double kTorusTiltDegrees = 70;
constexpr dvec3 kLampStart{2.3, 3.4, 1.6};

// How fast they move.
constexpr double kOrbitDegreesPerSecond = 30;   // one turn of the sphere pair in 12 s
constexpr double kPlanetDegreesPerSecond = 20;
constexpr double kTorusDegreesPerSecond = 90;
constexpr double kLampDegreesPerSecond = 45;
constexpr double kLampBob = 0.4;  // the lamp rises and falls this much twice a turn
// The sphere pair's path is an ellipse about their midpoint, its long axis
// through both starting points; its short half-axis is just over one sphere
// radius, so the two pass 0.04 apart and the near one clears the planet's
// rings (a circle through the starting points would cut through them).
constexpr double kOrbitMinorRadius = 1.02;

const std::array<const char*, 6> kSky = {"sky_px", "sky_nx", "sky_py", "sky_ny", "sky_pz", "sky_nz"};

double radians(double degrees) { return degrees * std::numbers::pi / 180.0; }

glm::dquat about(const dvec3& axis, double degrees) { return glm::angleAxis(radians(degrees), glm::normalize(axis)); }

Rotation as_rotation(const glm::dquat& q) { return Rotation{.quaternion = glm::dvec4(q.w, q.x, q.y, q.z)}; }

void add_textures(prism::LiveScene& scene, const std::filesystem::path& folder) {
  for (const char* name : {"checker", "planet", "marble", "perforated"})
    scene.add_texture(name, folder / (std::string(name) + ".png"));
  for (const char* name : kSky) scene.add_texture(name, folder / (std::string(name) + ".png"));
}

void add_materials(prism::LiveScene& scene) {
  const dvec3 white{1, 1, 1};
  scene.set_material("floor", {.color = {0.6, 0.6, 0.6}, .texture = "checker", .uv_scale = {0.125, 0.125},
                               .specular = 0.2, .shininess = 64, .reflect = 0.12});
  scene.set_material("glass", {.ior = 1.5, .absorb = {0.18, 0.06, 0.03}});
  scene.set_material("mirror", {.color = {0.9, 0.9, 0.92}, .diffuse = 0.1, .specular = 0.6, .shininess = 200,
                                .reflect = 0.9});
  scene.set_material("planet", {.color = white, .texture = "planet", .specular = 0.25, .shininess = 40});
  scene.set_material("rings", {.color = white, .texture = "perforated", .uv_scale = {1, 12}, .specular = 0.2});
  scene.set_material("marble", {.color = white, .texture = "marble", .specular = 0.4, .shininess = 80,
                                .reflect = 0.05});
  scene.set_material("copper", {.color = {0.85, 0.45, 0.25}, .specular = 0.7, .shininess = 60, .reflect = 0.25});
  scene.set_material("teal", {.color = {0.1, 0.55, 0.5}, .specular = 0.3, .shininess = 24});
  scene.set_material("plum", {.color = {0.45, 0.15, 0.4}, .specular = 0.5, .shininess = 48});
}

prism::PointLight lamp_at(const dvec3& position) {
  return {.position = position, .color = {1.0, 0.8, 0.55}, .intensity = 1.0, .linear = 0.1, .quadratic = 0.05,
          .radius = 0.15};
}

prism::LightId add_lights(prism::LiveScene& scene) {
  scene.add_light(prism::DirectionalLight{.direction = {-0.55, -0.45, 0.70}, .color = {1.0, 0.94, 0.84},
                                          .intensity = 0.55});
  scene.add_light(prism::PointLight{.position = {-5.0, 6.5, 6.0}, .color = {0.85, 0.9, 1.0}, .intensity = 0.35});
  return scene.add_light(lamp_at(kLampStart));
}

Showcase add_objects(prism::LiveScene& scene) {
  Showcase s;
  const Rotation planet_tilt{.axis = kPlanetTiltAxis, .degrees = kPlanetTiltDegrees};
  scene.add_object("plane", {{"point", dvec3{0, 0, 0}}, {"normal", dvec3{0, 1, 0}}}, "floor");
  s.glass = scene.add_object("sphere", {{"center", kGlassStart}, {"radius", 1.0}}, "glass");
  s.mirror = scene.add_object("sphere", {{"center", kMirrorStart}, {"radius", 1.0}}, "mirror");
  // The planet is turned so that its texture and its rings tilt together.
  s.planet = scene.add_object("sphere", {{"center", kPlanetCenter}, {"radius", 0.8}}, "planet", planet_tilt);
  scene.add_object("ring", {{"center", kPlanetCenter}, {"inner_radius", 1.0}, {"outer_radius", 1.5}}, "rings",
                   planet_tilt);
  scene.add_object("box", {{"center", dvec3{-3.3, 0.6, 2.6}}, {"half_size", dvec3{0.6, 0.6, 0.6}}}, "marble",
                   Rotation{.axis = {0, 1, 0}, .degrees = 30});
  scene.add_object("cone", {{"center", dvec3{4.4, 1.6, -1.8}}, {"radius", 0.6}, {"height", 1.6}}, "copper",
                   Rotation{.axis = {1, 0, 0}, .degrees = 180});
  scene.add_object("cylinder", {{"center", dvec3{3.1, 0.0, 2.9}}, {"radius", 0.45}, {"height", 1.1}}, "teal");
  s.torus = scene.add_object("torus", {{"center", kTorusCenter}, {"major_radius", 0.65}, {"minor_radius", 0.22}},
                             "plum", Rotation{.axis = kTorusTiltAxis, .degrees = kTorusTiltDegrees});
  return s;
}

// The pair's positions `degrees` along their ellipse (see kOrbitMinorRadius).
std::array<dvec3, 2> sphere_pair_at(double degrees) {
  const dvec3 middle = (kGlassStart + kMirrorStart) * 0.5;
  const dvec3 major = kGlassStart - middle;  // horizontal: both start at y = 1
  const dvec3 minor = glm::normalize(glm::cross(dvec3(0, 1, 0), major)) * kOrbitMinorRadius;
  const double a = radians(degrees);
  const dvec3 offset = major * std::cos(a) + minor * std::sin(a);
  return {middle + offset, middle - offset};
}

}  // namespace

Showcase build_showcase(prism::LiveScene& scene, const std::filesystem::path& textures) {
  scene.set_camera({.position = {0.0, 2.4, 9.5}, .look_at = {0.0, 0.9, 0.0}, .up = {0, 1, 0}, .fov_y = 42});
  add_textures(scene, textures);
  scene.set_background_cubemap({kSky[0], kSky[1], kSky[2], kSky[3], kSky[4], kSky[5]});
  scene.set_ambient({0.06, 0.07, 0.09});
  scene.set_shadow_ambient({0.12, 0.12, 0.14});
  add_materials(scene);
  Showcase showcase = add_objects(scene);
  showcase.lamp = add_lights(scene);
  return showcase;
}

void animate(prism::LiveScene& scene, const Showcase& s, double seconds) {
  const auto [glass, mirror] = sphere_pair_at(kOrbitDegreesPerSecond * seconds);
  scene.move_object(s.glass, glass);
  scene.move_object(s.mirror, mirror);

  // Spin about the planet's own (tilted) axis: the tilt applied after it.
  const glm::dquat tilt = about(kPlanetTiltAxis, kPlanetTiltDegrees);
  scene.rotate_object(s.planet, as_rotation(tilt * about({0, 1, 0}, kPlanetDegreesPerSecond * seconds)));

  // The torus keeps its tilt and turns about the vertical.
  const glm::dquat torus_tilt = about(kTorusTiltAxis, kTorusTiltDegrees);
  scene.rotate_object(s.torus, as_rotation(about({0, 1, 0}, kTorusDegreesPerSecond * seconds) * torus_tilt));

  // The lamp circles the vertical through the origin at its starting radius, bobbing.
  const double a = radians(kLampDegreesPerSecond * seconds);
  const double radius = std::hypot(kLampStart.x, kLampStart.z), start = std::atan2(kLampStart.z, kLampStart.x);
  const dvec3 lamp{radius * std::cos(start + a), kLampStart.y + kLampBob * std::sin(2 * a),
                   radius * std::sin(start + a)};
  scene.update_light(s.lamp, lamp_at(lamp));
}

}  // namespace animated
