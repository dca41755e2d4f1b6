// EmbreeQuery::update: the moved objects' layer (embree_update.hpp).
#include "embree_update.hpp"

#include <algorithm>
#include <limits>

#include "embree_query.hpp"

namespace prism::embree {

double half_area(const Box3& box) {
  const glm::dvec3 e = glm::max(box.hi - box.lo, glm::dvec3(0));
  return e.x * e.y + e.y * e.z + e.z * e.x;
}

Box3 box_union(const Box3& a, const Box3& b) { return Box3{glm::min(a.lo, b.lo), glm::max(a.hi, b.hi)}; }

bool box_contains(const Box3& outer, const Box3& inner) {
  return glm::all(glm::lessThanEqual(outer.lo, inner.lo)) && glm::all(glm::lessThanEqual(inner.hi, outer.hi));
}

Box3 empty_box() {
  constexpr double inf = std::numeric_limits<double>::infinity();
  return Box3{glm::dvec3(inf), glm::dvec3(-inf)};
}

double EmbreeQuery::layered_cost() const {
  return now_area_ > 0.0 ? (built_area_ + moved_area_) / now_area_ : 1.0;
}

namespace {

// An instance of `scene` with the identity transform, attached to `top`; its id.
unsigned attach_instance(RTCDevice device, RTCScene top, RTCScene scene) {
  RTCGeometry instance = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_INSTANCE);
  rtcSetGeometryInstancedScene(instance, scene);
  const float identity[12] = {1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0};  // 3x4, column-major
  rtcSetGeometryTransform(instance, 0, RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR, identity);
  rtcCommitGeometry(instance);
  const unsigned id = rtcAttachGeometry(top, instance);
  rtcReleaseGeometry(instance);  // `top` holds it now
  return id;
}

}  // namespace

void EmbreeQuery::start_layers() {
  moved_ids_.assign(scene_.objects.size(), 0);
  main_.skip = &moved_ids_;
  moved_ = std::make_unique<Moved>();
  moved_->group = Group{scene_.objects.data(), &frame_, {}, nullptr};
  moved_->top.reset(rtcNewScene(device_.get()));
  device_.check("scene creation");
  rtcSetSceneBuildQuality(moved_->top.get(), RTC_BUILD_QUALITY_MEDIUM);
  attach_instance(device_.get(), moved_->top.get(), main_scene_.get());
  moved_->geometry_id = attach_objects(moved_->top.get(), moved_->group);
  device_.check("layer setup");
}

UpdateResult EmbreeQuery::update(std::span<const uint32_t> changed, bool may_layer) {
  const auto& objects = scene_.objects;
  views_tried_ = false;  // edited objects: their spheres (outliers' too) are built again by prepare_views
  if (objects.size() != kinds_.size()) return UpdateResult::kNeedsBuild;
  std::vector<int32_t> moving;  // BVH objects whose box changed
  for (uint32_t index : changed) {
    if (index >= objects.size() || kind_of(objects[index]) != kinds_[index]) return UpdateResult::kNeedsBuild;
    // Unbounded objects and outliers are tested beside the BVH: the plugins read the scene.
    if (!std::ranges::binary_search(bvh_ids_, static_cast<int32_t>(index))) continue;
    const Box3& now = objects[index].world_bounds;
    if (now.lo == boxes_[index].lo && now.hi == boxes_[index].hi) continue;
    if (!box_contains(frame_.bounds, now)) return UpdateResult::kNeedsBuild;  // a new frame moves every box
    moving.push_back(static_cast<int32_t>(index));
  }
  if (moving.empty()) return UpdateResult::kUnchanged;
  if (!may_layer) return UpdateResult::kNeedsBuild;
  std::ranges::sort(moving);  // `changed` should be unique already; the sums below need it
  moving.erase(std::unique(moving.begin(), moving.end()), moving.end());

  double now_area = now_area_;
  double moved_area = moved_area_;
  for (int32_t id : moving) {
    const double before = half_area(boxes_[id]);
    const double after = half_area(objects[id].world_bounds);
    now_area += after - before;
    moved_area += after - (!moved_ids_.empty() && moved_ids_[id] != 0 ? before : 0.0);
  }
  if (now_area > 0.0 && built_area_ + moved_area > kMaxLayeredCost * now_area) return UpdateResult::kNeedsBuild;

  if (!moved_) start_layers();
  now_area_ = now_area;
  moved_area_ = moved_area;
  main_.objects = moved_->group.objects = objects.data();
  for (int32_t id : moving) {
    boxes_[id] = objects[id].world_bounds;
    if (filter_) filter_->set_box(id, boxes_[id]);
    frame_.objects = box_union(frame_.objects, boxes_[id]);
    if (moved_ids_[id] != 0) continue;
    moved_ids_[id] = 1;
    moved_->ids.push_back(id);
  }
  moved_->group.ids = moved_->ids;
  RTCGeometry geometry = rtcGetGeometry(moved_->top.get(), moved_->geometry_id);
  rtcSetGeometryUserPrimitiveCount(geometry, static_cast<unsigned>(moved_->ids.size()));
  rtcCommitGeometry(geometry);
  rtcCommitScene(moved_->top.get());
  device_.check("BVH update");
  return UpdateResult::kUpdated;
}

}  // namespace prism::embree
