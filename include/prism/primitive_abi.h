/* Prism primitive-plugin ABI.
 *
 * A primitive plugin is a shared object exporting one C function,
 * `prism_primitive_entry`, that returns a pointer to a static descriptor
 * table. The loader reads `abi_version` (always the first member) before it
 * touches anything else and refuses a table whose version differs.
 *
 * The plugin describes its JSON fields declaratively; the core parses and
 * range-checks them (so every type gets the same JSON-path error messages)
 * and hands the plugin a flat array of doubles, field after field. The
 * plugin packs those into its parameter record (std430-compatible, doubles),
 * which every backend stores and passes back unchanged.
 *
 * Intersection works in the object's local frame: for a plugin with
 * PRISM_PRIMITIVE_TRANSFORMABLE the core moves the ray by `center` and
 * `rotation` before calling it (rotations keep `t`). Hit first, shading
 * later: `intersect` returns `t` plus whatever the plugin needs, and
 * `surface` computes point, normal and uv for the winning hit only.
 *
 * Version 2 added `refine`: a polish of an ill-conditioned winning hit in
 * extended precision (grazing rays, hits far from the object's origin).
 *
 * Version 3 added the packet entries `intersect_packet` and
 * `occluded_packet`: up to PRISM_PACKET_SIZE rays in one call, so a packet
 * tracer (Embree's rtcIntersect16) pays one call per candidate object for a
 * whole packet instead of one per ray. The SDK's `describe_primitive`
 * builds both from the scalar `intersect`; a plugin may supply its own.
 *
 * Version 4 added `intersect_float`: the same query computed in float32, the
 * CPU model of what a float GPU kernel computes once the host has re-centred
 * the ray in double (`--precision float` on the reference backend). A plugin
 * written in the shared dialect gets it from the float instantiation of its
 * one source (the SDK's PRISM_SHARED_INTERSECT); a hand-written plugin gets
 * its double `intersect` there (describe_primitive's default), which a
 * caller can recognise by the equal pointers.
 *
 * Version 5 added `bounding_sphere` (optional): a sphere that holds the
 * primitive, tighter than the one around its box for round shapes (a
 * sphere's own radius, not sqrt(3) times it), so a CPU backend passes fewer
 * candidate objects on to `intersect`.
 *
 * Version 6 added `occluded`: the occlusion test of one ray, which a plugin
 * may answer without solving for the hit (the torus stops once a root is
 * bracketed inside the interval). The SDK's `describe_primitive` builds it
 * from `intersect`; a plugin may supply its own.
 * A plugin built against an older version is refused at load with a
 * message that says to rebuild it against this SDK.
 */
#ifndef PRISM_PRIMITIVE_ABI_H
#define PRISM_PRIMITIVE_ABI_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define PRISM_PRIMITIVE_ABI_VERSION 6u
#define PRISM_PRIMITIVE_ENTRY_SYMBOL "prism_primitive_entry"
#define PRISM_EXPORT __attribute__((visibility("default")))

/* Kinds of field value. */
typedef enum PrismFieldKind {
  PRISM_FIELD_NUMBER = 0,        /* one JSON number */
  PRISM_FIELD_ARRAY = 1,         /* exactly `count` JSON numbers */
  PRISM_FIELD_ARRAY_OR_NULL = 2  /* `count` entries, each a number or null (null reads as `null_value`) */
} PrismFieldKind;

/* Field flags. */
#define PRISM_FIELD_REQUIRED 1u      /* no default; missing is an error */
#define PRISM_FIELD_MIN_EXCLUSIVE 2u /* each entry must be > min (else >= min) */
#define PRISM_FIELD_NONZERO 4u       /* an array that must not be all zeros */
#define PRISM_FIELD_LENGTH 8u        /* a length or coordinate: |entry| <= 1e7 */

typedef struct PrismField {
  const char* name;
  uint32_t kind;           /* PrismFieldKind */
  uint32_t count;          /* entries; 1 for PRISM_FIELD_NUMBER */
  uint32_t flags;
  double min;              /* per entry; -INFINITY for none */
  double max;              /* per entry; +INFINITY for none */
  double null_value;       /* what null reads as (ARRAY_OR_NULL) */
  const double* defaults;  /* `count` entries, NULL when required */
  const char* doc;         /* one line of documentation for the field */
} PrismField;

/* Descriptor flags. */
#define PRISM_PRIMITIVE_TRANSFORMABLE 1u /* accepts `center` and `rotation` */
/* The whole object lies on or behind the tangent plane at each of its
 * surface points: the boundary of a convex solid (sphere, box) or a flat
 * shape (plane, ring). A ray that leaves one of its points on the outward
 * side (the offset origin and the direction both in front of the outward
 * normal) cannot meet it again, so the CPU backends skip the object in the
 * shadow rays from its own front-facing hits. Optional (0: not claimed). */
#define PRISM_PRIMITIVE_CONVEX 2u

typedef struct PrismRay {
  double origin[3];
  double dir[3]; /* unit length */
} PrismRay;

/* The same local-frame ray in extended precision (long double: x87 80-bit
 * on x86-64, binary128 on aarch64), for `refine`: the world ray moved by a
 * rotation computed in that precision, `dir` normalised in it. */
typedef struct PrismRayExt {
  long double origin[3];
  long double dir[3];
} PrismRayExt;

/* Rays of one packet in the local frame, structure of arrays: lane i is
 * origin[axis][i], dir[axis][i], tmin[i], tmax[i]. Only the lanes whose bit
 * is set in the `active` mask passed beside it are meaningful. */
#define PRISM_PACKET_SIZE 16u
typedef struct PrismRayPacket {
  double origin[3][PRISM_PACKET_SIZE];
  double dir[3][PRISM_PACKET_SIZE]; /* unit length */
  double tmin[PRISM_PACKET_SIZE];
  double tmax[PRISM_PACKET_SIZE];
} PrismRayPacket;

typedef struct PrismHit {
  double t;
  double data[3]; /* plugin-private, read back by `surface` */
  uint32_t part;  /* plugin-private (a face, a root index...) */
  uint32_t flags; /* PRISM_HIT_*: what the core asks of `surface`; 0 from `intersect` */
} PrismHit;

/* PrismHit.flags, set by the core on the hit it passes to `surface`. */
/* The caller will not read uv (the hit's material has no texture): the
 * plugin may leave uv at 0 and skip computing it. Point and normal must be
 * exactly what they are without the bit. A plugin that ignores the bit
 * loses nothing but the time (a new bit, not a new ABI version). */
#define PRISM_HIT_SKIP_UV 1u

typedef struct PrismSurface {
  double point[3];  /* hit point in the local frame, re-projected onto the surface */
  double normal[3]; /* outward normal, local frame, any length; all zero where undefined */
  double uv[2];
} PrismSurface;

typedef struct PrismError {
  char field[64];    /* the offending field's name, "" for the object as a whole */
  char message[192]; /* e.g. "must be < major_radius (1), got 2" */
} PrismError;

typedef struct PrismPrimitiveDesc {
  uint32_t abi_version; /* PRISM_PRIMITIVE_ABI_VERSION; must stay the first member */
  uint32_t desc_size;   /* sizeof(PrismPrimitiveDesc) as the plugin was built */
  const char* type_name;      /* the JSON `type`, e.g. "torus" */
  const char* plugin_version; /* e.g. "1.0.0" */
  uint32_t flags;             /* PRISM_PRIMITIVE_* */
  uint32_t field_count;
  const PrismField* fields;
  uint32_t record_size; /* bytes of the packed parameter record, a multiple of 16 */
  uint32_t reserved;

  /* Cross-field checks after the per-field ones; 0 = valid, else fill `err`. */
  int (*validate)(const double* values, PrismError* err);
  /* Pack checked values into the parameter record (record_size bytes, 16-aligned). */
  void (*pack)(const double* values, void* record);
  /* Local-frame bounding box; returns 0 when the primitive is unbounded. */
  int (*bounds)(const void* record, double lo[3], double hi[3]);
  /* Closest hit with tmin < t <= tmax; returns 1 and fills `hit`, else 0. */
  int (*intersect)(const void* record, const PrismRay* ray, double tmin, double tmax, PrismHit* hit);
  /* The same query for `count` rays; found[i] is 1 where hits[i] is valid. */
  void (*intersect_batch)(const void* record, size_t count, const PrismRay* rays, const double* tmin,
                          const double* tmax, PrismHit* hits, uint8_t* found);
  /* Point, outward normal and uv of a hit returned by `intersect` for `ray`. */
  void (*surface)(const void* record, const PrismRay* ray, const PrismHit* hit, PrismSurface* out);

  /* GPU slots (NULL: the plugin has no GPU intersector). `glsl_source` is
   * GLSL 4.50 placed after the core GLSL library (core/glsl/library.glsl)
   * and defines, for `rec` the index of the record's first double in
   * `prism_records` and the same local-frame ray the CPU functions get:
   *   bool <glsl_prefix>_intersect(uint rec, PrismRay ray, double tmin, double tmax, out PrismHit hit);
   *   void <glsl_prefix>_surface(uint rec, PrismRay ray, PrismHit hit, out PrismSurface s);
   * with the semantics of `intersect` and `surface` above. A line
   * `// prism:require <module>` asks for an optional core GLSL module
   * (core/glsl/<module>.glsl); all other global names start with the prefix. */
  const char* glsl_source;
  const char* glsl_prefix;

  /* Optional (NULL: none). Polishes a hit that `intersect` returned for the
   * double-rounded version of `ray`: Newton steps on the surface's implicit
   * equation, evaluated in extended precision, from hit->t. Updates hit->t
   * and whatever `surface` reads from the hit (data, part), and leaves the
   * hit unchanged when the polish does not converge to the same root. The
   * core calls it only for a winning hit whose double t is ill-conditioned:
   * an input rounding of one ulp moves it by more than ~1e-11 relative
   * (see prism::surface_of). */
  void (*refine)(const void* record, const PrismRayExt* ray, PrismHit* hit);

  /* Version 3, required. The closest hit of every active lane with
   * tmin < t <= tmax, exactly as `intersect` answers that lane's ray: fills
   * hits[i] for the lanes hit and returns their mask (a subset of `active`). */
  uint32_t (*intersect_packet)(const void* record, const PrismRayPacket* rays, uint32_t active, PrismHit* hits);
  /* The mask of active lanes hit with tmin < t < tmax (an occlusion test:
   * a hit at exactly tmax, the light, does not count). */
  uint32_t (*occluded_packet)(const void* record, const PrismRayPacket* rays, uint32_t active);

  /* Version 4, required. The contract of `intersect` (the same local-frame
   * ray and bounds, in double; a hit with tmin < t <= tmax, t in double),
   * computed in float32: the ray is rounded to float (nearest), tmin up and
   * tmax down (so every float t the plugin accepts lies in the double
   * bounds), and the plugin's float instantiation answers. Only the hit and
   * its t are float: `surface` reads the hit in double as usual (the hit's
   * data, a local point for some plugins, then carries float rounding).
   * Equal to `intersect` for a plugin without a float instantiation. */
  int (*intersect_float)(const void* record, const PrismRay* ray, double tmin, double tmax, PrismHit* hit);

  /* Version 5, optional (NULL: the core takes the sphere around `bounds`).
   * A sphere in the local frame that holds every point of the primitive
   * (every point `surface` reports for a hit of `intersect`, up to
   * rounding): its centre and radius.
   * Returns 0 when the primitive is unbounded. The core keeps whichever of
   * this sphere and the box's is smaller. A sphere that misses part of the
   * primitive makes backends miss hits there: `prism plugin check` tests it. */
  int (*bounding_sphere)(const void* record, double center[3], double* radius);

  /* Version 6, required. 1 where the ray meets the primitive with
   * tmin < t < tmax, else 0: exactly whether `intersect` finds a hit with
   * t < tmax on the same ray and bounds (a hit at exactly tmax, the light,
   * does not count), but the plugin need not find where. The CPU backends'
   * shadow rays ask this, not `intersect`. */
  int (*occluded)(const void* record, const PrismRay* ray, double tmin, double tmax);
} PrismPrimitiveDesc;

typedef const PrismPrimitiveDesc* (*PrismPrimitiveEntryFn)(void);

#ifdef __cplusplus
}
#endif

#endif /* PRISM_PRIMITIVE_ABI_H */
