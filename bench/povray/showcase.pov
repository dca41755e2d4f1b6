// bench/povray/showcase.pov -- scenes/showcase.json written by hand for POV-Ray 3.7
//
// What it is: the Prism showcase scene (same camera, lights, materials and the
// same nine objects, plus six sky squares standing in for the cube-map
// background) for the peer comparison in scripts/compare_povray.sh and
// docs/povray-comparison.md. It is a translation by hand, not generated: if
// scenes/showcase.json changes, change this file too.
//
// How to run: the texture PNGs are referred to by bare file name, so run
// POV-Ray in a folder that holds them (POV-Ray's default file-I/O security only
// reads from the current folder and a few system ones). The comparison script
// does exactly that: it copies this file and scenes/textures/*.png into a
// temporary folder and renders there with
//   povray +Ishowcase.pov +W640 +H360 -A +WT2 -D File_Gamma=sRGB Declare=MaxDepth=5
//
// Coordinates: every number below is the Prism (right-handed) number, unchanged.
// POV-Ray is left-handed; the camera's negative `right` vector mirrors the view,
// so the picture has Prism's orientation (no z flip in the data).
//
// What differs from Prism (details and reasons in docs/povray-comparison.md):
//  * Opaque reflection: Prism adds (1-F)*Local + F*reflection (Schlick F); POV's
//    `reflection { r, 1 falloff 5 }` is the same Schlick F but POV adds the full
//    Local. We scale ambient/diffuse/phong by (1-r) (exact at normal incidence,
//    too bright at grazing angles).
//  * Glass: Prism uses Schlick Fresnel and a one-bounce, local-only reflection
//    (Shade1); POV uses the exact unpolarised Fresnel formula and a full
//    recursive reflection ray. Absorption is exact (fade_power >= 1000 is
//    Beer-Lambert: exp(-(1-fade_color)*d/fade_distance)).
//  * Shadows: Prism's glass sphere and ring block shadow rays completely; POV
//    lets light through transparent surfaces (the glass unrefracted, the ring
//    by its transmit = 1 - alpha).
//  * shadow_ambient: each Prism light is split into a shadow-casting light with
//    (1-shadow_ambient)*E and a `shadowless` light with shadow_ambient*E. POV
//    computes no highlights for shadowless lights, so phong is scaled by
//    1/(1-0.12) (blue highlights end up 2.3% low; no highlight in shadow).
//  * The attenuated point light: POV's 2/(1+(d/D)^p) cannot express
//    1/(1+0.1d+0.05d^2); D=3.9, p=1.8 and a colour factor 0.4646 fit it within
//    1% for d in [2,10] (7% low at d=0, 3% high at d=14).
//  * The ring's alpha: POV does not scale phong by opacity (Prism does).
//  * Skybox: POV has no cube-map background; six huge self-lit squares carry the
//    six faces, mapped by the spec's table (bilinear, clamped at face edges).
//    The sky matches Prism's to the 8-bit value; a miss in Prism is a hit on a
//    sky square in POV.
//  * Textures: POV's bilinear `interpolate 2` with `gamma srgb` decodes and
//    filters like Prism (texel centres at (i+0.5)/W); no mip-maps in either.
//  * Output: POV writes sRGB PNG with File_Gamma=sRGB, same curve as Prism.

#version 3.7;

// The comparison script passes Declare=MaxDepth=D (= prism --max-depth D).
#ifndef (MaxDepth) #declare MaxDepth = 5; #end

global_settings {
  assumed_gamma 1.0        // all colours below are linear, as in Prism
  max_trace_level MaxDepth // = prism --max-depth D: D ray levels, then black
  adc_bailout 0            // Prism has no adaptive depth cut-off
  ambient_light rgb 1
}

// ---------------------------------------------------------------------------
// Helpers

// Rodrigues rotation, right-hand rule about Axis (any length) by Deg degrees:
// world = R * local, as Prism's {"axis": A, "degrees": a}. POV's matrix takes
// the images of the local x, y, z axes (the columns of R) as its rows.
#macro AxisRot(Axis, Deg)
  #local K = vnormalize(Axis);
  #local C = cos(radians(Deg));
  #local S = sin(radians(Deg));
  #local T = 1 - C;
  matrix < T*K.x*K.x + C,     T*K.x*K.y + S*K.z, T*K.x*K.z - S*K.y,
           T*K.x*K.y - S*K.z, T*K.y*K.y + C,     T*K.y*K.z + S*K.x,
           T*K.x*K.z + S*K.y, T*K.y*K.z - S*K.x, T*K.z*K.z + C,
           0, 0, 0 >
#end

#declare Ambient = <0.06, 0.07, 0.09>;          // "ambient"
#declare ShadowAmbient = <0.12, 0.12, 0.14>;    // "shadow_ambient"
// Highlights come from the shadow-casting part only, (1 - 0.12) of each light.
#declare PhongScale = 1 / (1 - 0.12);

// ---------------------------------------------------------------------------
// Camera: position, look_at, up y, fov_y 42 (vertical). POV's `angle` is the
// horizontal field of view; `right` is negative to render a right-handed world.

camera {
  perspective
  location <0.0, 2.4, 9.5>
  up y
  right -x * image_width / image_height
  angle 2 * degrees(atan(tan(radians(42 / 2)) * image_width / image_height))
  look_at <0.0, 0.9, 0.0>
}

// ---------------------------------------------------------------------------
// Background: cube map ["sky_px","sky_nx","sky_py","sky_ny","sky_pz","sky_nz"].
// POV-Ray 3.7 has no cube-map background, so the six faces are six huge
// self-lit squares (a skybox of half-size 1e5 around the origin), each with
// its face image mapped as the format spec's OpenGL table says: for face
// direction A with (sc, tc) along (S, T), the square is 1e5 * (A + S*sc + T*tc),
// sc, tc in [-1, 1], and s = (sc + 1)/2, t = (tc + 1)/2 (t = 0 is the image's
// top row; POV's planar image map has y up, hence -T). The scene is within 10
// units of the origin, so the direction error is < 1e-4 rad (< 0.01 texel).
// `once` clamps samples to the edge texels, as Prism's skybox does. no_shadow:
// the sky never blocks a shadow ray. A miss in Prism is a hit on one of these
// in POV-Ray (counted in its "Rays" the same way). This matched a first version
// that evaluated the table with POV functions in a sky_sphere to within 7/255
// on 0.5% of the pixel values, and traces about 25% faster.

#declare SkyHalf = 1e5;
#macro SkyFace(Image, S, T, A)
  polygon {
    5, SkyHalf * (A - S - T), SkyHalf * (A + S - T), SkyHalf * (A + S + T), SkyHalf * (A - S + T),
       SkyHalf * (A - S - T)
    texture {
      // pattern (s, 1 - t) -> world: x axis to 2L*S, y axis to -2L*T, origin to L*(A - S + T)
      pigment {
        image_map { png Image gamma srgb interpolate 2 once }
        matrix < 2 * SkyHalf * S.x, 2 * SkyHalf * S.y, 2 * SkyHalf * S.z,
                 -2 * SkyHalf * T.x, -2 * SkyHalf * T.y, -2 * SkyHalf * T.z,
                 A.x, A.y, A.z,
                 SkyHalf * (A.x - S.x + T.x), SkyHalf * (A.y - S.y + T.y), SkyHalf * (A.z - S.z + T.z) >
      }
      finish { ambient 0 diffuse 0 emission 1 }
    }
    no_shadow
  }
#end

//       face image     S (sc)  T (tc)  A (ma)   spec table: (sc, tc, ma)
SkyFace("sky_px.png",   -z,     -y,      x)   // +x: (-dz, -dy, dx)
SkyFace("sky_nx.png",    z,     -y,     -x)   // -x: ( dz, -dy, dx)
SkyFace("sky_py.png",    x,      z,      y)   // +y: ( dx,  dz, dy)
SkyFace("sky_ny.png",    x,     -z,     -y)   // -y: ( dx, -dz, dy)
SkyFace("sky_pz.png",    x,     -y,      z)   // +z: ( dx, -dy, dz)
SkyFace("sky_nz.png",   -x,     -y,     -z)   // -z: (-dx, -dy, dz)

// ---------------------------------------------------------------------------
// Lights. Prism: shadowed lights still deliver shadow_ambient * E. POV: each
// light = a shadow-casting part (1 - shadow_ambient) * E plus a shadowless part
// shadow_ambient * E, which sums to E where lit and to shadow_ambient * E in
// shadow, per channel.

#macro PrismLight(Position, E, IsParallel, FadeD, FadeP, LooksLike)
  light_source {
    Position
    color rgb E * (<1, 1, 1> - ShadowAmbient)
    #if (IsParallel) parallel point_at <0, 0, 0> #end
    #if (FadeD > 0) fade_distance FadeD fade_power FadeP #end
    #if (LooksLike) looks_like { LightBall } #end
  }
  light_source {
    Position
    color rgb E * ShadowAmbient
    shadowless
    #if (IsParallel) parallel point_at <0, 0, 0> #end
    #if (FadeD > 0) fade_distance FadeD fade_power FadeP #end
  }
#end

// Light 2's visible sphere (radius 0.15, radiance = its colour, never blocks a
// shadow ray).
#declare LightBall = sphere {
  <0, 0, 0>, 0.15
  texture { pigment { rgb <1.0, 0.8, 0.55> } finish { ambient 0 diffuse 0 emission 1 } }
  no_shadow
}

// 0: directional, direction (-0.55,-0.45,0.70), colour (1,0.94,0.84) * 0.55.
// A parallel light placed far up-sun (nothing is beyond it to cast shadows).
PrismLight(<0.55, 0.45, -0.70> * 1000, <1.0, 0.94, 0.84> * 0.55, true, 0, 0, false)

// 1: point (-5,6.5,6), colour (0.85,0.9,1) * 0.35, no attenuation.
PrismLight(<-5.0, 6.5, 6.0>, <0.85, 0.9, 1.0> * 0.35, false, 0, 0, false)

// 2: point (2.3,3.4,1.6), colour (1,0.8,0.55), E / (1 + 0.1 d + 0.05 d^2),
// radius 0.15. Fitted: 0.4646 * 2 / (1 + (d/3.9)^1.8).
PrismLight(<2.3, 3.4, 1.6>, <1.0, 0.8, 0.55> * 0.4646, false, 3.9, 1.8, true)

// ---------------------------------------------------------------------------
// Materials. Prism: Local = ambient*c + sum E*S*(kd*c*(n.l) + ks*(r.v)^shininess).
// POV: ambient A (times pigment), diffuse kd, phong ks, phong_size shininess.
// A grey `color` that multiplies a texture is folded into ambient and diffuse
// (it does not touch the highlight). For reflect r > 0, POV's variable
// reflection `reflection { r, 1 falloff 5 }` is Schlick's F; the Local term is
// scaled by (1 - r), POV having no angle-dependent (1 - F) on it.

// floor: color 0.6 x checker, uv_scale 1/8, reflect 0.12, specular 0.2, shininess 64
#declare T_Floor = texture {
  // Prism plane uv for normal +y: u = z, v = x (t1 = +z, t2 = +x), times 1/8.
  // Pattern point = (u, 1 - v): the image's x = z/8, y = -x/8 (mod 1).
  pigment {
    image_map { png "checker.png" gamma srgb interpolate 2 }
    matrix < 0, 0, 8,   -8, 0, 0,   0, 1, 0,   0, 0, 0 >
  }
  finish {
    ambient rgb Ambient * 0.6 * (1 - 0.12)
    diffuse 0.6 * (1 - 0.12)
    phong 0.2 * PhongScale * (1 - 0.12) phong_size 64
    reflection { 0.12, 1 falloff 5 }
  }
}

// glass: ior 1.5, absorb (0.18, 0.06, 0.03); the surface itself adds nothing
#declare M_Glass = material {
  texture {
    pigment { rgbt 1 }
    finish { ambient 0 diffuse 0 reflection { 0, 1 fresnel on } conserve_energy }
  }
  interior {
    ior 1.5
    fade_distance 1 fade_power 1001 fade_color rgb <1 - 0.18, 1 - 0.06, 1 - 0.03>
  }
}

// mirror: color (0.9,0.9,0.92), reflect 0.9, diffuse 0.1, specular 0.6, shininess 200
#declare T_Mirror = texture {
  pigment { rgb <0.9, 0.9, 0.92> }
  finish {
    ambient rgb Ambient * (1 - 0.9)
    diffuse 0.1 * (1 - 0.9)
    phong 0.6 * PhongScale * (1 - 0.9) phong_size 200
    reflection { 0.9, 1 falloff 5 }
  }
}

// planet: texture planet, specular 0.25, shininess 40
// Prism: u = 0.5 + atan2(z,x)/2pi, v = 0.5 - asin(y/r)/pi. POV's spherical
// map: u = atan2(z,x)/2pi (mod 1), same v; the 180-degree turn adds the 0.5.
#declare T_Planet = texture {
  pigment {
    image_map { png "planet.png" gamma srgb map_type 1 interpolate 2 }
    rotate 180 * y
  }
  finish { ambient rgb Ambient diffuse 1 phong 0.25 * PhongScale phong_size 40 }
}

// rings: texture perforated (RGBA; alpha becomes transmit), uv_scale (1, 12), specular 0.2
// Prism ring uv: u = (|p| - 1)/(1.5 - 1), v = 0.5 + atan2(z,x)/2pi, v' = 12 v.
// The cylindrical warp maps local p to (atan2(z,x)/2pi, y, |p|); the matrix,
// written before the warp so that it is applied after it, takes that to
// (u, 1 - v') = (2(|p| - 1), -12 atan2/2pi).
#declare T_Rings = texture {
  pigment {
    image_map { png "perforated.png" gamma srgb interpolate 2 }
    matrix < 0, 0, 0.5,   -1/12, 0, 0,   0, 1, 0,   0, 0, 1 >
    warp { cylindrical }
  }
  finish { ambient rgb Ambient diffuse 1 phong 0.2 * PhongScale phong_size 32 }
}

// marble: texture marble on every box face, specular 0.4, shininess 80, reflect 0.05
// Prism box uv (h = 0.6): +-x faces ((z+h)/2h, (h-y)/2h); +-y ((x+h)/2h, (z+h)/2h);
// +-z ((x+h)/2h, (h-y)/2h). A function pattern picks the face (largest |p_i|,
// ties x < y < z) and each face has its own planar map.
#declare BoxFace = function(x, y, z) {
  select(abs(x) - max(abs(y), abs(z)),
    select(abs(y) - abs(z), 5/6, 1/2),
    1/6)
}
#declare P_MarbleX = pigment {
  image_map { png "marble.png" gamma srgb interpolate 2 }
  matrix < 0, 0, 1.2,   0, 1.2, 0,   1, 0, 0,   0, -0.6, -0.6 >
}
#declare P_MarbleY = pigment {
  image_map { png "marble.png" gamma srgb interpolate 2 }
  matrix < 1.2, 0, 0,   0, 0, -1.2,   0, 1, 0,   -0.6, 0, 0.6 >
}
#declare P_MarbleZ = pigment {
  image_map { png "marble.png" gamma srgb interpolate 2 }
  matrix < 1.2, 0, 0,   0, 1.2, 0,   0, 0, 1,   -0.6, -0.6, 0 >
}
#declare T_Marble = texture {
  pigment {
    function { BoxFace(x, y, z) }
    pigment_map {
      [0   P_MarbleX] [1/3 P_MarbleX]
      [1/3 P_MarbleY] [2/3 P_MarbleY]
      [2/3 P_MarbleZ] [1   P_MarbleZ]
    }
  }
  finish {
    ambient rgb Ambient * (1 - 0.05)
    diffuse 1 - 0.05
    phong 0.4 * PhongScale * (1 - 0.05) phong_size 80
    reflection { 0.05, 1 falloff 5 }
  }
}

// copper: color (0.85,0.45,0.25), specular 0.7, shininess 60, reflect 0.25
#declare T_Copper = texture {
  pigment { rgb <0.85, 0.45, 0.25> }
  finish {
    ambient rgb Ambient * (1 - 0.25)
    diffuse 1 - 0.25
    phong 0.7 * PhongScale * (1 - 0.25) phong_size 60
    reflection { 0.25, 1 falloff 5 }
  }
}

// teal: color (0.1,0.55,0.5), specular 0.3, shininess 24
#declare T_Teal = texture {
  pigment { rgb <0.1, 0.55, 0.5> }
  finish { ambient rgb Ambient diffuse 1 phong 0.3 * PhongScale phong_size 24 }
}

// plum: color (0.45,0.15,0.4), specular 0.5, shininess 48
#declare T_Plum = texture {
  pigment { rgb <0.45, 0.15, 0.4> }
  finish { ambient rgb Ambient diffuse 1 phong 0.5 * PhongScale phong_size 48 }
}

// ---------------------------------------------------------------------------
// Objects, in Prism's order (object ids 0..8). Each is built in its local
// frame, textured there, then rotated and moved: world = center + R * local.

// 0 plane: point (0,0,0), normal (0,1,0)
plane { y, 0 texture { T_Floor } }

// 1 sphere: center (-1.5,1,1.2), radius 1, glass
sphere { <0, 0, 0>, 1.0 material { M_Glass } translate <-1.5, 1.0, 1.2> }

// 2 sphere: center (1.9,1,-0.6), radius 1, mirror
sphere { <0, 0, 0>, 1.0 texture { T_Mirror } translate <1.9, 1.0, -0.6> }

// 3 sphere: center (-0.2,1.3,-3), radius 0.8, planet, rotation axis (1,0,-0.5) 30 deg
sphere {
  <0, 0, 0>, 0.8 texture { T_Planet }
  AxisRot(<1, 0, -0.5>, 30) translate <-0.2, 1.3, -3.0>
}

// 4 ring: center (-0.2,1.3,-3), inner 1, outer 1.5 (a disc with a hole in the
// local xz-plane), rings, same rotation as the planet
disc {
  <0, 0, 0>, y, 1.5, 1.0 texture { T_Rings }
  AxisRot(<1, 0, -0.5>, 30) translate <-0.2, 1.3, -3.0>
}

// 5 box: center (-3.3,0.6,2.6), half_size 0.6, marble, rotation axis y 30 deg
box {
  <-0.6, -0.6, -0.6>, <0.6, 0.6, 0.6> texture { T_Marble }
  AxisRot(<0, 1, 0>, 30) translate <-3.3, 0.6, 2.6>
}

// 6 cone: center (4.4,1.6,-1.8), radius 0.6, height 1.6 (open; apex at the
// local origin, radius 0.6 at local y = 1.6), copper, rotation axis x 180 deg
cone {
  <0, 0, 0>, 0, <0, 1.6, 0>, 0.6 open texture { T_Copper }
  AxisRot(<1, 0, 0>, 180) translate <4.4, 1.6, -1.8>
}

// 7 cylinder: center (3.1,0,2.9), radius 0.45, height 1.1 (open tube, local
// y from 0 to 1.1), teal
cylinder { <0, 0, 0>, <0, 1.1, 0>, 0.45 open texture { T_Teal } translate <3.1, 0.0, 2.9> }

// 8 torus: center (-4.6,0.95,-2.4), R 0.65, r 0.22 (axis = local y), plum,
// rotation axis (1,0.2,0) 70 deg
torus {
  0.65, 0.22 texture { T_Plum }
  AxisRot(<1, 0.2, 0>, 70) translate <-4.6, 0.95, -2.4>
}
