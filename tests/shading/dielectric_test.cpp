// Steps 3 and 6: dielectrics (Schlick with R0, Shade1, refraction, total
// internal reflection, Beer-Lambert absorption). Secondary rays start at
// P +- eps*n with eps = 1e-4 * (1 + max_i |P_i|); the segment lengths below
// include that offset where it matters.
#include "shading_support.hpp"

namespace prism::test {
namespace {

class DielectricTest : public BackendTest {};

// The one-pixel camera (ray (0,0,-1) from the origin) looks through a glass
// box spanning z in [-4, -2] (centre (0,0,-3), half size 1) at the background.
std::string slab_scene(const std::string& top_level_extra, const std::string& glass) {
  return one_pixel_scene(top_level_extra + R"(
    "materials": {"glass": )" + glass + R"(},
    "objects": [{"type": "box", "center": [0, 0, -3], "half_size": [1, 1, 1], "material": "glass"}])");
}

TEST_P(DielectricTest, GlassSlabAtNormalIncidence) {
  // ior 1.5: R0 = ((1-1.5)/(1+1.5))^2 = 0.04, and at normal incidence
  // x = cosi = cos_t = 1, so F = 0.04 at both faces. The glass's own colour,
  // specular and reflect are ignored; the light (l = (0,0,1)) lights no face
  // from inside. Background B = (1, 0.5, 0.25).
  // Front face: + F * Shade1(reflect = (0,0,1)) = 0.04 B (a miss); w = 0.96.
  // Back face (leaving): + w * F * Shade1(inward reflection): that ray hits the
  //   front face from inside, Local = 0 (no ambient; dot(n, l) = -1); w = 0.9216.
  // Then a miss: + 0.9216 B. Total 0.9616 B = (0.9616, 0.4808, 0.2404).
  Scene scene = load(slab_scene(R"(
    "background": {"color": [1, 0.5, 0.25]},
    "lights": [{"type": "directional", "direction": [0, 0, -1]}],)",
                                R"({"ior": 1.5, "color": [0.1, 0.2, 0.3], "specular": 1, "reflect": 0.7})"));
  EXPECT_TRUE(pixel_near(render(scene), 0, 0, {0.9616, 0.4808, 0.2404}));
}

TEST_P(DielectricTest, AbsorptionAndShade1InsideASlab) {
  // As above with ambient A = 0.5, glass colour c = (0.4, 0.6, 0.8),
  // absorb = (0.5, 0.1, 0), B = 1.
  // Front face P = (0,0,-2): eps = 3e-4; + 0.04 B; w = 0.96; the refracted ray
  //   starts at z = -2.0003.
  // Back face P = (0,0,-4), t1 = 1.9997 (leaving): w *= T1 = exp(-absorb*1.9997).
  //   Shade1(reflect) starts at z = -4 + 5e-4 (eps = 5e-4) and hits the front
  //   face from inside at t2 = 1.9995: Local as opaque = A*c = (0.2, 0.3, 0.4),
  //   times T2 = exp(-absorb*1.9995). + w * 0.04 * that; w *= 0.96; then a miss.
  // Total = 0.04 + 0.96*T1*(0.04*A*c*T2 + 0.96):
  //   T1 = (0.367934627, 0.818755315, 1), T2 = (0.367971423, 0.818771691, 1)
  //   -> (0.380128343, 0.802287603, 0.97696).
  Scene scene = load(slab_scene(R"(
    "background": {"color": [1, 1, 1]},
    "ambient": [0.5, 0.5, 0.5],)",
                                R"({"ior": 1.5, "color": [0.4, 0.6, 0.8], "absorb": [0.5, 0.1, 0]})"));
  EXPECT_TRUE(pixel_near(render(scene), 0, 0, {0.380128343, 0.802287603, 0.97696}));
}

TEST_P(DielectricTest, Shade1SeesALightSphere) {
  // The slab of GlassSlabAtNormalIncidence with a light sphere of colour
  // (0.5, 1, 0.25) behind the camera (centre (0,0,3), radius 0.5) and B = 0.1.
  // Front face: + 0.04 * Shade1 = 0.04 * light colour (the reflected ray passes
  // the camera and hits the sphere). Back face: its Shade1 hits the front face
  // from inside, where the light is behind (dot(n, l) = -1): Local = 0.
  // Then a miss: + 0.9216 B.
  // (0.02 + 0.09216, 0.04 + 0.09216, 0.01 + 0.09216) = (0.11216, 0.13216, 0.10216).
  Scene scene = load(slab_scene(R"(
    "background": {"color": [0.1, 0.1, 0.1]},
    "lights": [{"type": "point", "position": [0, 0, 3], "color": [0.5, 1, 0.25], "radius": 0.5}],)",
                                R"({"ior": 1.5})"));
  EXPECT_TRUE(pixel_near(render(scene), 0, 0, {0.11216, 0.13216, 0.10216}));
}

TEST_P(DielectricTest, Shade1ShadesWithLightsAndShadowRays) {
  // The slab, B = 0.1, a plane at z = 5 facing the slab with c = (1, 0.5, 0.25),
  // and a directional light with l = (0,0,-1) (travelling +z) that lights it
  // head-on, but whose shadow ray from the plane runs into the slab: blocked,
  // S = shadow_ambient = 0.5. Glass colour c_g = (0.2, 0.4, 0.6), no ambient.
  // Front face: + 0.04 * Shade1 = 0.04 * (0.5 * c * 1) = 0.02 c; w = 0.96.
  // Back face: Shade1 hits the front face from inside, n = (0,0,-1) faces the
  //   light (dot = 1), but its shadow ray leaves through the back face: blocked.
  //   Local = 0.5 * c_g; + 0.96 * 0.04 * 0.5 c_g = 0.0192 c_g; w = 0.9216.
  // Then a miss: + 0.9216 * 0.1 = 0.09216.
  // R: 0.02 + 0.00384 + 0.09216 = 0.116; G: 0.01 + 0.00768 + 0.09216 = 0.10984;
  // B: 0.005 + 0.01152 + 0.09216 = 0.10868.
  Scene scene = load(one_pixel_scene(R"(
    "background": {"color": [0.1, 0.1, 0.1]},
    "shadow_ambient": [0.5, 0.5, 0.5],
    "materials": {"glass": {"ior": 1.5, "color": [0.2, 0.4, 0.6]}, "wall": {"color": [1, 0.5, 0.25]}},
    "lights": [{"type": "directional", "direction": [0, 0, 1]}],
    "objects": [{"type": "box", "center": [0, 0, -3], "half_size": [1, 1, 1], "material": "glass"},
                {"type": "plane", "point": [0, 0, 5], "normal": [0, 0, -1], "material": "wall"}])"));
  EXPECT_TRUE(pixel_near(render(scene), 0, 0, {0.116, 0.10984, 0.10868}));
}

// The camera sits inside a glass box (|x| <= 1, |y| <= 1, |z| <= 2) looking
// along (0,-0.6,-0.8): it reaches the face y = -1 first (t = 1/0.6 = 5/3, at
// z = -4/3) with cosi = 0.6, below the critical cosine sqrt(1 - 1/1.5^2) =
// 0.745: total internal reflection, to (0,0.6,-0.8). That ray starts at
// y = -1 + eps and reaches the face z = -2 after (2 - 4/3)/0.8 = 5/6 with
// cosi = 0.8: k = 1 - 2.25*(1-0.64) = 0.19, cos_t = sqrt(0.19) = 0.435889894,
// F = 0.04 + 0.96*(1 - cos_t)^5 = 0.04 + 0.96*0.0571241038 = 0.0948391396.
// Shade1 there sees only glass from inside (Local = 0, no ambient or light),
// and the refracted ray (0, 0.9, -0.4359) misses: (1-F) * T * B, with
// T = exp(-absorb * (5/3 + 5/6)) = exp(-absorb * 2.5) and B = 1.
std::string inside_glass_scene(int max_depth) {
  return R"({"prism": 1,
    "camera": {"position": [0, 0, 0], "look_at": [0, -0.6, -0.8]},
    "image": {"width": 1, "height": 1, "max_depth": )" + std::to_string(max_depth) + R"(},
    "background": {"color": [1, 1, 1]},
    "materials": {"glass": {"ior": 1.5, "absorb": [0.2, 0, 0.4]}},
    "objects": [{"type": "box", "center": [0, 0, 0], "half_size": [1, 1, 2], "material": "glass"}]})";
}

TEST_P(DielectricTest, TotalInternalReflectionKeepsTheWeight) {
  // (1-F) * exp(-(0.5, 0, 1)) = 0.90516086 * (0.60653066, 1, 0.367879441)
  //   = (0.549007814, 0.90516086, 0.332990071).
  EXPECT_TRUE(pixel_near(render(load(inside_glass_scene(3))), 0, 0,
                         {0.549007814, 0.90516086, 0.332990071}));
}

TEST_P(DielectricTest, TotalInternalReflectionCountsAsAnInteraction) {
  // Interactions: 1 = TIR, 2 = the exit face, 3 = the miss. With max_depth 2
  // the sample ends after the exit face, having added only F * Shade1 = 0.
  EXPECT_TRUE(pixel_near(render(load(inside_glass_scene(2))), 0, 0, {0, 0, 0}));
}

PRISM_INSTANTIATE_BACKEND_TESTS(DielectricTest);

}  // namespace
}  // namespace prism::test
