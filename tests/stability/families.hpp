// The stiff-case generator of the stability suite: for every primitive type,
// named families of hard cases (grazing rays, far origins, tiny and huge
// objects, secondary rays with tmin, and what is hard for that type alone:
// torus holes and tube tangents, nearly linear quadrics, cone apices, box
// edges and corners, ring inner radii, ...).
//
// A family is a list of cases, one per value of its parameter; a case is one
// scene (the "objects" array of a scene file) and its rays as doubles, the
// exact numbers the runner writes (%.17g round-trips them) and the oracle
// reads. Every ray direction is written with a double length of exactly 1
// (see unit_in_double in families.cpp), so `prism trace`'s normalisation on
// read leaves it unchanged and the backend traces exactly the ray the oracle
// solves.
//
// `quick` holds one parameter value per family (usually the hardest) and 48
// rays; `full` the whole sweep with 256 rays per value. Everything is
// deterministic: each case draws from its own fixed-seed generator.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace prism::stability {

struct Ray {
  double origin[3] = {0, 0, 0};
  double dir[3] = {0, 0, 1};  // double length exactly 1
  double tmin = 0;
};

struct Case {
  std::string param;       // "angle=1e-07": the family's parameter at this case
  nlohmann::json objects;  // the scene's "objects" array
  std::vector<Ray> rays;
};

struct Family {
  std::string name;       // "<primitive>.<family>", e.g. "torus.hole"
  std::string primitive;  // "torus"
  std::string description;
  std::vector<Case> cases;  // one in quick mode, the sweep in full mode
  // Float cannot do it (docs/numerics.md, "What float cannot do"): its
  // float rows are measured and reported, not held to the float caps.
  bool double_only = false;
};

enum class Mode { quick, full };

// The primitive types the suite covers: those whose case module
// (tests/cases/primitive_cases.hpp) has an oracle and an object, by name.
const std::vector<std::string>& primitive_types();

// Every family of `primitive` (of every type when empty), in `mode`.
// Throws std::invalid_argument for an unknown primitive type.
std::vector<Family> make_families(Mode mode, const std::string& primitive = "");

// A whole scene file around `objects`: a camera (never used by `trace`) and no
// lights, so no light sphere can take part in the answers.
nlohmann::json scene_json(const nlohmann::json& objects);

// The rays as `prism trace` reads them: ox,oy,oz,dx,dy,dz,tmin with %.17g.
std::string rays_csv(const std::vector<Ray>& rays);

}  // namespace prism::stability
