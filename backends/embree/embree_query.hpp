// Closest-hit and occlusion queries over a scene's objects in double
// precision. Embree's float32 BVH only chooses which bounded objects a ray
// may hit; every hit is computed and compared in double by the primitive
// plugins (prism::intersect_object). Unbounded objects (planes, unclipped
// quadrics) and a few outsized ones are tested beside the BVH, brute force.
// Objects edited in place can be brought up to date without a build from
// scratch (update(), embree_update.hpp).
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include <embree3/rtcore.h>
#include <glm/glm.hpp>

#include "embree_box_filter.hpp"
#include "embree_device.hpp"
#include "embree_view_buffers.hpp"
#include "prism/cpu_render.hpp"

namespace prism::embree {

// Embree's coordinates: world - center, every float box grown by `pad`
// (the error bound is derived in embree_query.cpp).
struct Frame {
  Box3 bounds;           // B: holds every BVH object (their union box, with slack)
  glm::dvec3 center{0};  // C, the middle of B
  glm::dvec3 half{0};    // half extents of B
  double pad = 0;
  Box3 objects;          // in B: holds every box the BVH holds; rays are clipped to it
};

enum class UpdateResult {
  kUpdated,     // the BVH holds the objects' new boxes
  kUnchanged,   // no BVH object's box changed (a material, a brute-force object): nothing to do
  kNeedsBuild,  // a new query must be built; this one was left as it was
};

class EmbreeQuery final : public ObjectQuery {
 public:
  // Builds the BVH over `scene`'s bounded objects; `scene` and `device`
  // must outlive the query. Throws RuntimeError on an Embree error.
  EmbreeQuery(const Scene& scene, Device& device);
  ~EmbreeQuery() override;

  Hit closest(const Ray& ray, double tmin) const override;
  Hit closest_leaving(const Ray& ray, int32_t self) const override;
  void closest_leaving_batch(std::span<const Ray> rays, const int32_t* self, Hit* hits) const override;
  int32_t occluder(const Ray& ray, double tmax) const override;

  // Builds the light buffers of a frame seen from `eye` (embree_view_buffers.hpp)
  // where the scene is small enough for them, reusing those whose camera,
  // light and objects are unchanged. Call before rendering, not during it.
  void prepare_views(const glm::dvec3& eye);
  // Answered from those buffers where they apply, else by closest() and
  // occluder(); the answers are the same either way.
  Hit camera_closest(const Ray& ray) const override;
  // The batch shares one candidate list, from the cone that holds its rays,
  // and calls each plugin once per packet of rays (embree_query.cpp).
  void camera_closest_batch(std::span<const Ray> rays, Hit* hits) const override;
  int32_t light_occluder(size_t light, const Ray& ray, double tmax, KnownClear clear = {}) const override;
  // The keys: a light buffer's cell, kNoCandidates, or kNoCell where no
  // buffer vouches for the ray (embree_view_buffers.hpp).
  void light_keys(size_t light, const RayLanes& rays, int32_t* keys) const override;
  int32_t keyed_light_occluder(size_t light, const Ray& ray, double tmax, KnownClear clear,
                               int32_t key) const override;
  // The rays of one cell share its list, and each plugin is called once per
  // packet of them (embree_query.cpp).
  void keyed_light_occluders(size_t light, const RayLanes& rays, const int32_t* keys, const int32_t* self,
                             const uint8_t* cast, int32_t* blockers) const override;
  // Whether light buffers are in use (for tests and --stats).
  bool has_views() const { return views_.has_value(); }

  // Brings the BVH up to date after the objects `changed` (ids) were edited
  // in place in the scene, layering the moved ones over the main tree
  // (embree_update.hpp), or says that a new build is needed: when the object
  // count changed, when an object went in or out of the BVH (bounded or not,
  // outsized or not) or out of the frame's box B, when the layers' cost
  // would pass kMaxLayeredCost, or when BVH objects moved and `may_layer` is
  // false. Throws RuntimeError on an Embree error, after which the query
  // must not be used.
  UpdateResult update(std::span<const uint32_t> changed, bool may_layer = true);

  const Frame& frame() const { return frame_; }
  // The proxy of embree_update.hpp: 1 until an update moves objects.
  double layered_cost() const;
  size_t moved_count() const { return moved_ ? moved_->ids.size() : 0; }
  size_t bvh_object_count() const { return bvh_ids_.size(); }
  size_t brute_force_count() const { return brute_ids_.size(); }
  size_t geometry_count() const { return main_.ids.empty() ? 0 : 1; }
  // Whether rays are tested against the boxes of few objects instead of Embree's BVH.
  bool filters() const { return filter_.has_value(); }

  struct SceneDeleter {
    void operator()(RTCScene scene) const { rtcReleaseScene(scene); }
  };
  using ScenePtr = std::unique_ptr<RTCSceneTy, SceneDeleter>;

  // The objects of one RTC user geometry.
  struct Group {
    const Object* objects = nullptr;  // scene.objects.data()
    const Frame* frame = nullptr;
    std::span<const int32_t> ids;                // primID -> object id
    const std::vector<uint8_t>* skip = nullptr;  // by object id: nonzero, not here any more
  };

 private:
  // Where an object goes; an object whose kind changes needs a new build.
  enum class Kind : uint8_t { kUnbounded, kRegular, kOutsized };
  Kind kind_of(const Object& object) const;
  void build();
  // A user geometry over `group`'s objects, attached to `scene`; its id.
  unsigned attach_objects(RTCScene scene, Group& group);
  // frame_ for objects inside `bounds`.
  void set_frame(const Box3& bounds);
  // The scene rays are traced in: the main one, or the layers above it.
  RTCScene trace_scene() const { return moved_ ? moved_->top.get() : main_scene_.get(); }
  // [t0, t1]: the part of the ray inside frame_.objects grown by 2 * pad.
  bool clip(const Ray& ray, double& t0, double& t1) const;
  // Whether the double arithmetic that moves the origin to world t = shift
  // stays far inside the padding (else the ray takes the brute-force path).
  bool shift_is_exact_enough(const Ray& ray, double shift) const;
  // The queries through filter_ ("Few objects" in embree_query.cpp), or
  // nothing for a ray the filter cannot take.
  bool filter_takes(const Ray& ray, glm::dvec3& inv) const;
  // closest() that leaves object `skip` out (kMissId: none), written into
  // `best` (its prim only where it holds an object's hit).
  void closest_skipping(const Ray& ray, double tmin, int32_t skip, Hit& best) const;
  void closest_traced(const Ray& ray, double tmin, int32_t skip, Hit& best) const;  // through Embree's BVH
  void closest_filtered(const Ray& ray, double tmin, int32_t skip, const glm::dvec3& inv, Hit& best) const;
  int32_t occluder_filtered(const Ray& ray, double tmax, const glm::dvec3& inv) const;

  // The layers an update adds (embree_update.hpp).
  struct Moved {
    std::vector<int32_t> ids;  // the moved objects, in the order they first moved
    Group group;               // over `ids`
    ScenePtr top;              // the main scene's instance and the moved objects
    unsigned geometry_id = 0;  // the moved objects' user geometry in `top`
  };
  void start_layers();

  // The light buffers of the last prepare_views() and what they were built for.
  struct Views {
    std::vector<BoundSphere> spheres;  // every bounded object
    std::vector<int32_t> unbounded;    // tested for every ray
    std::vector<glm::dvec4> bound_of;  // by object id: its sphere grown for misses_bound (bounded ones)
    double light_reach = 0;            // how far a shadow ray may end from its point light
    double extent = 0;                 // the largest |coordinate| of the objects and lights
    glm::dvec3 eye{0};
    std::optional<ApexCones> camera;  // no cells: a tile's rays are a narrow cone (camera_closest_batch)
    std::vector<Light> lights;                         // as the buffers below were built
    std::vector<std::optional<PointBuffer>> points;    // by light: point lights
    std::vector<std::optional<ParallelBuffer>> parallels;  // by light: directional lights
  };
  void start_views();
  // What the shadow rays toward one light read, looked up once for all of
  // them: the light's cell lists (null where it has no buffer), the
  // unbounded objects and the grown bounding spheres.
  struct LightLists {
    const CellLists* cells = nullptr;
    std::span<const int32_t> unbounded;
    const glm::dvec4* bound_of = nullptr;
    const Object* objects = nullptr;
    // A shadow ray's candidates by its key (a cell, or kNoCandidates).
    std::span<const int32_t> cell(int32_t key) const {
      return key == kNoCandidates ? std::span<const int32_t>{} : (*cells)[size_t(key)];
    }
  };
  LightLists light_lists(size_t light) const;  // views_ must hold buffers
  static int32_t cell_occluder(const LightLists& lists, int32_t key, const Ray& ray, double tmax, KnownClear clear);

  const Scene& scene_;
  Device& device_;
  std::optional<Views> views_;  // empty when there are too many objects for buffers
  bool views_tried_ = false;    // views_ is up to date with the objects
  Frame frame_;
  std::vector<int32_t> bvh_ids_;    // ascending
  std::vector<int32_t> brute_ids_;  // ascending: unbounded objects and outliers
  double outsized_limit_ = 0;       // half sizes above this are outsized
  std::vector<Kind> kinds_;         // by object id, when built
  std::vector<Box3> boxes_;         // by object id: the box the BVH holds now (BVH objects)
  std::vector<uint8_t> moved_ids_;  // by object id: 1 in the moved layer (skipped in main_); empty until layers start
  double built_area_ = 0;           // Σ half_area(box when built), BVH objects
  double now_area_ = 0;             // Σ half_area(box now), BVH objects
  double moved_area_ = 0;           // Σ half_area(box now), moved objects
  std::optional<BoxFilter> filter_;  // few BVH objects: their padded boxes
  Group main_;
  ScenePtr main_scene_;
  std::unique_ptr<Moved> moved_;
};

}  // namespace prism::embree
