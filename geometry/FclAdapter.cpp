// The only translation unit that includes FCL (docs/architecture.md section 1). Facts relied on are
// in docs/fcl-notes.md: GST_LIBCCD always (section 3), meshes first with the normal re-oriented
// (4.1), abs() of sphere-triangle depth (4.2), zero normals dropped (4.3), halfspaces kept out of
// the tree (4.8), own tight + fattened AABBs (4.9, 6), every call wrapped (4.12).
#include <coulomb/geometry/FclAdapter.hpp>

#include <coulomb/geometry/MeshEdges.hpp>

#include <fcl/broadphase/broadphase_dynamic_AABB_tree.h>
#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/convex.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/halfspace.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/distance.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <sstream>
#include <stdexcept>

namespace coulomb::geometry {
namespace {

template <class... Ts>
struct Overloaded : Ts... {
  using Ts::operator()...;
};
// clang before 17 lacks C++20 aggregate deduction (P1816): the C++17 guide keeps it compiling.
template <class... Ts>
Overloaded(Ts...) -> Overloaded<Ts...>;

std::string name(ColliderId id) {
  std::ostringstream out;
  out << "collider " << id.index << "." << id.generation;
  return out.str();
}

std::shared_ptr<fcl::CollisionGeometryd> makeGeometry(const Shape& shape, const std::string& who) {
  return std::visit(
      Overloaded{
          [](const Sphere& s) -> std::shared_ptr<fcl::CollisionGeometryd> {
            return std::make_shared<fcl::Sphered>(s.radius);
          },
          [](const Box& b) -> std::shared_ptr<fcl::CollisionGeometryd> {
            const Eigen::Vector3d side = 2.0 * b.halfExtents;
            return std::make_shared<fcl::Boxd>(side.x(), side.y(), side.z());
          },
          [](const Capsule& c) -> std::shared_ptr<fcl::CollisionGeometryd> {
            return std::make_shared<fcl::Capsuled>(c.radius, 2.0 * c.halfLength);
          },
          [](const Cylinder& c) -> std::shared_ptr<fcl::CollisionGeometryd> {
            return std::make_shared<fcl::Cylinderd>(c.radius, 2.0 * c.halfLength);
          },
          [](const Plane& p) -> std::shared_ptr<fcl::CollisionGeometryd> {
            const double norm = p.normal.norm();  // Halfspace {n.x <= d} with unit n
            return std::make_shared<fcl::Halfspaced>(p.normal / norm, p.offset / norm);
          },
          [&who](const ConvexHull& h) -> std::shared_ptr<fcl::CollisionGeometryd> {
            if (h.triangles.empty())
              throw std::invalid_argument(who + ": convex_hull has no faces (run makeConvexHull)");
            auto vertices =
                std::make_shared<std::vector<fcl::Vector3d>>(h.vertices.begin(), h.vertices.end());
            auto faces = std::make_shared<std::vector<int>>();
            faces->reserve(h.triangles.size() * 4);
            for (const Eigen::Vector3i& t : h.triangles) {
              faces->push_back(3);
              faces->insert(faces->end(), {t[0], t[1], t[2]});
            }
            return std::make_shared<fcl::Convexd>(vertices, static_cast<int>(h.triangles.size()),
                                                  faces, /*throw_if_invalid=*/true);
          },
          [&who](const TriangleMesh& m) -> std::shared_ptr<fcl::CollisionGeometryd> {
            auto model = std::make_shared<fcl::BVHModel<fcl::OBBRSSd>>();
            std::vector<fcl::Vector3d> vertices(m.vertices.begin(), m.vertices.end());
            std::vector<fcl::Triangle> triangles;
            triangles.reserve(m.triangles.size());
            for (const Eigen::Vector3i& t : m.triangles) triangles.emplace_back(t[0], t[1], t[2]);
            if (model->beginModel() != fcl::BVH_OK ||
                model->addSubModel(vertices, triangles) != fcl::BVH_OK ||
                model->endModel() != fcl::BVH_OK)
              throw std::invalid_argument(who + ": FCL could not build the mesh BVH");
            return model;
          }},
      shape);
}

// FCL's CollisionObject keeps its world AABB in a protected member; the tree reads it from there.
// Setting it directly lets Coulomb give rotated primitives a tight box (FCL's own is the
// bounding-sphere cube, docs/fcl-notes.md 4.9) and keep a fattened one while a body rests.
class TreeObject : public fcl::CollisionObjectd {
 public:
  using fcl::CollisionObjectd::CollisionObjectd;
  void setAabb(const fcl::AABBd& box) { aabb = box; }
};

// Tight world AABB of primitives (half-widths from the rotated extents); FCL's for hulls/meshes.
fcl::AABBd tightAabb(const Shape& shape, TreeObject& object) {
  const fcl::Transform3d& tf = object.getTransform();
  const Eigen::Matrix3d abs = tf.linear().cwiseAbs();
  const Eigen::Vector3d axis = tf.linear().col(2);
  Eigen::Vector3d half;
  if (const auto* box = std::get_if<Box>(&shape)) {
    half = abs * box->halfExtents;
  } else if (const auto* sphere = std::get_if<Sphere>(&shape)) {
    half.setConstant(sphere->radius);
  } else if (const auto* capsule = std::get_if<Capsule>(&shape)) {
    half = capsule->halfLength * axis.cwiseAbs() + Eigen::Vector3d::Constant(capsule->radius);
  } else if (const auto* cylinder = std::get_if<Cylinder>(&shape)) {
    const Eigen::Vector3d across = (Eigen::Vector3d::Ones() - axis.cwiseAbs2()).cwiseMax(0.0);
    half = cylinder->halfLength * axis.cwiseAbs() + cylinder->radius * across.cwiseSqrt();
  } else {
    object.computeAABB();  // forgetting it leaves a stale AABB (fcl#40)
    return object.getAABB();
  }
  return fcl::AABBd(tf.translation() - half, tf.translation() + half);
}

// Bitwise equality (not ==: -0.0 and 0.0 may give different signs of zero downstream).
bool sameBits(const double* a, const double* b, std::size_t count) {
  return std::memcmp(a, b, count * sizeof(double)) == 0;
}
bool sameBits(const Pose& a, const Pose& b) {
  return sameBits(a.rotation.coeffs().data(), b.rotation.coeffs().data(), 4) &&
         sameBits(a.position.data(), b.position.data(), 3);
}

bool finite(const fcl::Contactd& c) {
  return c.normal.allFinite() && c.pos.allFinite() && std::isfinite(c.penetration_depth);
}

// One FCL geometry and object: a collider of the scene or a query shape (FclQueryShape).
struct FclEntry {
  ColliderId id;
  std::shared_ptr<const Shape> shape;
  std::shared_ptr<fcl::CollisionGeometryd> geometry;
  std::unique_ptr<TreeObject> object;
  fcl::AABBd fat;  // what the tree holds: the tight AABB grown by margin + slack
  bool hasFat = false;
  bool isPlane = false;
  bool isMesh = false;
  MeshSurface surface;  // a mesh's edges and patches (MeshEdges.hpp)
  // What the transform and boxes were last placed for (FclScene::setPose).
  bool placed = false;
  Pose placedPose;
  double placedSweep = 0.0;

  void build(const std::shared_ptr<const Shape>& newShape, const std::string& who) {
    if (!newShape) throw std::invalid_argument(who + ": has no shape");
    if (auto problem = validateShape(*newShape)) throw std::invalid_argument(who + ": " + *problem);
    shape = newShape;
    isPlane = std::holds_alternative<Plane>(*shape);
    isMesh = std::holds_alternative<TriangleMesh>(*shape);
    if (isMesh) surface = meshSurface(std::get<TriangleMesh>(*shape));
    try {
      geometry = makeGeometry(*shape, who);
    } catch (const std::invalid_argument&) {
      throw;
    } catch (const std::exception& e) {
      throw std::invalid_argument(who + ": FCL rejected the " + shapeKindName(*shape) + ": " +
                                  e.what());
    }
    object = std::make_unique<TreeObject>(geometry);
  }

  void setTransform(const Pose& worldPose) {
    fcl::Transform3d transform = fcl::Transform3d::Identity();
    transform.linear() = worldPose.rotation.normalized().toRotationMatrix();  // fcl#567
    transform.translation() = worldPose.position;
    object->setTransform(transform);
  }
};

FclCollideResult collidePair(const FclEntry& ea, const FclEntry& eb, ColliderId a, ColliderId b,
                             int maxContacts, const FclFaultInjector& inject);
FclDistanceResult distancePair(const FclEntry& ea, const FclEntry& eb, ColliderId a, ColliderId b,
                               const FclFaultInjector& inject);

}  // namespace

struct FclQueryShape::Impl {
  FclEntry entry;
};

struct FclScene::Impl {
  using Entry = FclEntry;

  double margin = 0.0;
  std::map<ColliderId, std::unique_ptr<Entry>> entries;  // unique_ptr: stable user-data address
  fcl::DynamicAABBTreeCollisionManagerd manager;
  std::vector<fcl::CollisionObjectd*> moved;  // left their fat AABB since the last updateTree
  struct Shrunk {
    TreeObject* object;
    fcl::AABBd old;  // the fat box its leaf holds until the next updateTree
  };
  std::vector<Shrunk> shrunk;                         // a fat AABB inside the old one (see place)
  std::vector<fcl::CollisionObjectd*> shrunkObjects;  // kept for its storage
  // Registered at the next updateTree: into an empty tree as one balanced bulk build, since
  // inserting 10 000 leaves one by one into FCL's tree showed up as its main cost.
  std::vector<fcl::CollisionObjectd*> pending;
  std::vector<int> bvhStack;  // meshTrianglesNear's traversal, kept between calls

  Entry& at(ColliderId id) const {
    auto it = entries.find(id);
    if (it == entries.end()) throw std::out_of_range("FclScene: unknown " + name(id));
    return *it->second;  // the map holds unique_ptrs: the entry itself is not const
  }

  // The tree re-inserts a leaf whenever its box changes (docs/fcl-notes.md 6), so each leaf holds
  // a box fattened by `slack` beyond the margin, replaced only when the shape leaves it (Box2D's
  // b2_aabbMargin idea). A resting body then costs no tree work.
  // A fat box is refit too when it has grown stale: wider on some axis than a fresh one by more
  // than twice the slack (the sweep of a fast phase, gone once the body rests, or a turn that
  // narrowed the shape's box). Kept, it would hold neighbours that no longer come near as
  // candidate pairs for as long as the body rests (a settled pile of 1 000 boxes: 7 415 pairs
  // tested each step instead of 1 000). Moving inside its box never refits a body. FCL's tree
  // ignores a leaf's new box when the old one contains it (HierarchyTree::update), so a shrunk
  // box goes in through `shrunk` (updateTree moves the leaf out, then gives it its box).
  void place(Entry& entry, double sweep) {
    const fcl::AABBd tight = tightAabb(*entry.shape, *entry.object);
    const fcl::Vector3d grow = fcl::Vector3d::Constant(margin + sweep);
    const fcl::AABBd needed(tight.min_ - grow, tight.max_ + grow);
    const double slackWidth = 2.0 * margin + 1e-4;
    const auto stale = [&] {
      const fcl::Vector3d excess = (entry.fat.max_ - entry.fat.min_) - (needed.max_ - needed.min_);
      return excess.maxCoeff() > 4.0 * slackWidth;  // a fresh box has 2 slackWidth per axis
    };
    const bool leaves = !entry.hasFat || !entry.fat.contain(needed);
    if (leaves || stale()) {
      const fcl::Vector3d slack = fcl::Vector3d::Constant(slackWidth);
      const fcl::AABBd fresh(needed.min_ - slack, needed.max_ + slack);
      const bool shrinks = entry.hasFat && entry.fat.contain(fresh);
      if (!entry.isPlane) {
        if (shrinks)
          shrunk.push_back({entry.object.get(), entry.fat});
        else
          moved.push_back(entry.object.get());
      }
      entry.fat = fresh;
      entry.hasFat = true;
    }
    entry.object->setAabb(entry.fat);
  }
};

FclScene::FclScene(double aabbMargin) : impl_(std::make_unique<Impl>()) {
  impl_->margin = std::max(0.0, aabbMargin);
  // FCL re-balances 10 leaves on every update with a moved leaf (DynamicAABBTreeCollisionManager::
  // setup); on a swinging 10-link chain that was about 30 % of the broad phase. Without it the
  // tree is still rebuilt top-down once it is max_tree_nonbalanced_level (10) levels deeper than
  // balanced, and the pairs found are the same (they are sorted).
  impl_->manager.tree_incremental_balance_pass = 0;
}
FclScene::~FclScene() = default;
FclScene::FclScene(FclScene&&) noexcept = default;
FclScene& FclScene::operator=(FclScene&&) noexcept = default;

void FclScene::upsert(ColliderId id, const std::shared_ptr<const Shape>& shape) {
  auto it = impl_->entries.find(id);
  if (shape && it != impl_->entries.end() && it->second->shape == shape) return;  // no name built
  auto entry = std::make_unique<Impl::Entry>();
  entry->id = id;
  entry->build(shape, name(id));
  entry->object->setUserData(entry.get());
  impl_->place(*entry, 0.0);

  erase(id);
  if (!entry->isPlane) impl_->pending.push_back(entry->object.get());
  impl_->entries.emplace(id, std::move(entry));
  // The per-step lists hold at most every entry (moved: twice, from upsert and setPose), so a
  // step never grows them.
  const std::size_t count = impl_->entries.size();
  impl_->moved.reserve(2 * count);
  impl_->shrunk.reserve(count);
  impl_->shrunkObjects.reserve(count);
}

void FclScene::erase(ColliderId id) {
  auto it = impl_->entries.find(id);
  if (it == impl_->entries.end()) return;
  fcl::CollisionObjectd* object = it->second->object.get();
  auto& pending = impl_->pending;
  const auto waiting = std::find(pending.begin(), pending.end(), object);
  if (waiting != pending.end())
    pending.erase(waiting);
  else if (!it->second->isPlane)
    impl_->manager.unregisterObject(object);
  auto& moved = impl_->moved;
  moved.erase(std::remove(moved.begin(), moved.end(), object), moved.end());
  auto& shrunk = impl_->shrunk;
  shrunk.erase(std::remove_if(shrunk.begin(), shrunk.end(),
                              [&](const Impl::Shrunk& s) { return s.object == object; }),
               shrunk.end());
  impl_->entries.erase(it);
}

bool FclScene::contains(ColliderId id) const {
  return impl_->entries.count(id) != 0;
}

std::vector<ColliderId> FclScene::ids() const {
  std::vector<ColliderId> out;
  out.reserve(impl_->entries.size());
  for (const auto& [id, entry] : impl_->entries) out.push_back(id);
  return out;
}

void FclScene::setPose(ColliderId id, const Pose& worldPose, double sweep) {
  if (!worldPose.allFinite())
    throw std::invalid_argument(name(id) + ": world pose is not finite (NaN or inf)");
  Impl::Entry& entry = impl_->at(id);
  const double grow = std::isfinite(sweep) ? std::max(0.0, sweep) : 0.0;
  // The pose and sweep of the last call, to the bit (the static ground, a body at rest): the
  // transform and boxes would come out the same (place is idempotent), so they are kept.
  if (entry.placed && sameBits(entry.placedPose, worldPose) &&
      sameBits(&entry.placedSweep, &grow, 1))
    return;
  entry.setTransform(worldPose);
  impl_->place(entry, grow);
  entry.placed = true;
  entry.placedPose = worldPose;
  entry.placedSweep = grow;
}

void FclScene::updateTree() {
  if (!impl_->pending.empty()) {
    impl_->manager.registerObjects(impl_->pending);  // bulk top-down build when the tree is empty
    impl_->pending.clear();
    impl_->manager.setup();
  }
  if (!impl_->shrunk.empty()) {
    // A shrunk leaf is first moved to an empty box outside its old one, which the tree does take
    // (no allocation: the leaf and the map entry stay), then updated with its own box below.
    std::vector<fcl::CollisionObjectd*>& objects = impl_->shrunkObjects;
    objects.clear();
    for (const Impl::Shrunk& s : impl_->shrunk) {
      const fcl::Vector3d away =
          s.old.max_ + fcl::Vector3d::Constant(1.0 + (s.old.max_ - s.old.min_).maxCoeff());
      s.object->setAabb(fcl::AABBd(away, away));
      objects.push_back(s.object);
    }
    impl_->manager.update(objects);
    for (const Impl::Shrunk& s : impl_->shrunk) {
      const auto* entry = static_cast<const Impl::Entry*>(s.object->getUserData());
      s.object->setAabb(entry->fat);
      impl_->moved.push_back(s.object);
    }
    impl_->shrunk.clear();
  }
  impl_->manager.update(impl_->moved);  // only the leaves that left their fat box; no rebalance
  impl_->moved.clear();                 // of the whole tree when nothing moved
}

std::size_t FclScene::size() const {
  return impl_->entries.size();
}

void FclScene::overlappingPairs(std::vector<std::pair<ColliderId, ColliderId>>& pairs) const {
  using Pairs = std::vector<std::pair<ColliderId, ColliderId>>;
  pairs.clear();
  auto onPair = [](fcl::CollisionObjectd* a, fcl::CollisionObjectd* b, void* data) {
    const ColliderId ia = static_cast<const Impl::Entry*>(a->getUserData())->id;
    const ColliderId ib = static_cast<const Impl::Entry*>(b->getUserData())->id;
    static_cast<Pairs*>(data)->emplace_back(std::min(ia, ib), std::max(ia, ib));
    return false;  // keep traversing
  };
  impl_->manager.collide(&pairs, onPair);
  std::sort(pairs.begin(), pairs.end());  // the tree's order changes every frame (fcl#368)
}

Aabb FclScene::worldAabb(ColliderId id) const {
  const fcl::AABBd& box = impl_->at(id).object->getAABB();
  return {box.min_, box.max_};
}

const MeshSurface* FclScene::meshSurface(ColliderId id) const {
  const Impl::Entry& entry = impl_->at(id);
  return entry.isMesh ? &entry.surface : nullptr;
}

void FclScene::meshTrianglesNear(ColliderId mesh, const Aabb& box, std::vector<int>& out) const {
  out.clear();
  const Impl::Entry& entry = impl_->at(mesh);
  if (!entry.isMesh) return;
  const auto& model = static_cast<const fcl::BVHModel<fcl::OBBRSSd>&>(*entry.geometry);
  // The box in the mesh's frame (a box around the rotated box), tested against each node's
  // oriented box by its own enclosing box: conservative, exact enough to prune the tree.
  const fcl::Transform3d& transform = entry.object->getTransform();
  const Eigen::Matrix3d toLocal = transform.linear().transpose();
  const Eigen::Vector3d centre = toLocal * (0.5 * (box.min + box.max) - transform.translation());
  const Eigen::Vector3d half = toLocal.cwiseAbs() * (0.5 * (box.max - box.min));
  auto overlaps = [&](const Eigen::Vector3d& c, const Eigen::Vector3d& h) {
    return ((c - centre).cwiseAbs() - h - half).maxCoeff() <= 0.0;
  };
  std::vector<int>& stack = impl_->bvhStack;
  stack.clear();
  if (model.getNumBVs() > 0) stack.push_back(0);
  while (!stack.empty()) {
    const int id = stack.back();
    stack.pop_back();
    const fcl::BVNode<fcl::OBBRSSd>& node = model.getBV(id);
    const fcl::OBBd& obb = node.bv.obb;
    if (!overlaps(obb.To, obb.axis.cwiseAbs() * obb.extent)) continue;
    if (node.isLeaf()) {
      const fcl::Triangle& t = model.tri_indices[node.primitiveId()];
      Eigen::Vector3d lo = model.vertices[t[0]], hi = lo;
      for (int k = 1; k < 3; ++k) {
        lo = lo.cwiseMin(model.vertices[t[k]]);
        hi = hi.cwiseMax(model.vertices[t[k]]);
      }
      if (overlaps(0.5 * (lo + hi), 0.5 * (hi - lo))) out.push_back(node.primitiveId());
    } else {
      stack.push_back(node.rightChild());
      stack.push_back(node.leftChild());
    }
  }
  std::sort(out.begin(), out.end());
}

FclCollideResult FclScene::collide(ColliderId a, ColliderId b, int maxContacts,
                                   const FclFaultInjector& inject) const {
  return collidePair(impl_->at(a), impl_->at(b), a, b, maxContacts, inject);
}

FclDistanceResult FclScene::distance(ColliderId a, ColliderId b,
                                     const FclFaultInjector& inject) const {
  return distancePair(impl_->at(a), impl_->at(b), a, b, inject);
}

// Queries (SceneQuery.hpp): the tree's boxes are the fattened ones, so these candidates are a
// superset; the exact tests come after.
namespace {

bool halfspaceReaches(const FclEntry& entry, const fcl::AABBd& box) {
  const auto& h = static_cast<const fcl::Halfspaced&>(*entry.geometry);
  const fcl::Halfspaced world = fcl::transform(h, entry.object->getTransform());
  fcl::Vector3d lowest;  // the box corner deepest along -n
  for (int k = 0; k < 3; ++k) lowest[k] = world.n[k] > 0 ? box.min_[k] : box.max_[k];
  return world.n.dot(lowest) <= world.d;
}

bool segmentCrossesBox(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
                       double maxDistance, const fcl::AABBd& box) {
  double enter = 0.0, leave = maxDistance;
  for (int k = 0; k < 3; ++k) {
    if (std::abs(direction[k]) < 1e-300) {
      if (origin[k] < box.min_[k] || origin[k] > box.max_[k]) return false;
      continue;
    }
    const double inv = 1.0 / direction[k];
    double t1 = (box.min_[k] - origin[k]) * inv, t2 = (box.max_[k] - origin[k]) * inv;
    if (t1 > t2) std::swap(t1, t2);
    enter = std::max(enter, t1);
    leave = std::min(leave, t2);
    if (enter > leave) return false;
  }
  return true;
}

using TreeNode = fcl::detail::NodeBase<fcl::AABBd>;

// Depth-first walk of the tree's boxes; `visitLeaf(entry)` for every leaf `enters` accepts.
template <class Enters, class Visit>
void walkTree(const TreeNode* root, const Enters& enters, const Visit& visitLeaf) {
  if (root == nullptr) return;
  std::vector<const TreeNode*> stack{root};
  while (!stack.empty()) {
    const TreeNode* node = stack.back();
    stack.pop_back();
    if (!enters(node->bv)) continue;
    if (node->isLeaf()) {
      const auto* object = static_cast<const fcl::CollisionObjectd*>(node->data);
      visitLeaf(*static_cast<const FclEntry*>(object->getUserData()));
    } else {
      stack.push_back(node->children[1]);
      stack.push_back(node->children[0]);
    }
  }
}

}  // namespace

FclQueryShape::FclQueryShape(const std::shared_ptr<const Shape>& shape)
    : impl_(std::make_unique<Impl>()) {
  if (shape &&
      (std::holds_alternative<Plane>(*shape) || std::holds_alternative<TriangleMesh>(*shape)))
    throw std::invalid_argument(std::string("query shape: a ") + shapeKindName(*shape) +
                                " cannot be a query shape (sphere, box, capsule, cylinder or "
                                "convex_hull)");
  impl_->entry.build(shape, "query shape");
  impl_->entry.setTransform(Pose::identity());
}
FclQueryShape::~FclQueryShape() = default;
FclQueryShape::FclQueryShape(FclQueryShape&&) noexcept = default;
FclQueryShape& FclQueryShape::operator=(FclQueryShape&&) noexcept = default;

void FclQueryShape::setPose(const Pose& worldPose) {
  if (!worldPose.allFinite())
    throw std::invalid_argument("query shape: pose is not finite (NaN or inf)");
  impl_->entry.setTransform(worldPose);
}

Aabb FclQueryShape::worldAabb() const {
  const fcl::AABBd box = tightAabb(*impl_->entry.shape, *impl_->entry.object);
  return {box.min_, box.max_};
}

const Shape& FclQueryShape::shape() const {
  return *impl_->entry.shape;
}

void FclScene::queryAabb(const Aabb& box, std::vector<ColliderId>& out) const {
  out.clear();
  const fcl::AABBd query(box.min, box.max);
  walkTree(
      impl_->manager.getTree().getRoot(), [&](const fcl::AABBd& bv) { return bv.overlap(query); },
      [&](const FclEntry& entry) {
        if (tightAabb(*entry.shape, *entry.object).overlap(query)) out.push_back(entry.id);
      });
  for (const auto& [id, entry] : impl_->entries)
    if (entry->isPlane && halfspaceReaches(*entry, query)) out.push_back(id);
  std::sort(out.begin(), out.end());
}

void FclScene::queryRay(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
                        double maxDistance, std::vector<ColliderId>& out) const {
  out.clear();
  walkTree(
      impl_->manager.getTree().getRoot(),
      [&](const fcl::AABBd& bv) { return segmentCrossesBox(origin, direction, maxDistance, bv); },
      [&](const FclEntry& entry) { out.push_back(entry.id); });
  for (const auto& [id, entry] : impl_->entries)
    if (entry->isPlane) out.push_back(id);
  std::sort(out.begin(), out.end());
}

FclCollideResult FclScene::collide(const FclQueryShape& query, ColliderId b,
                                   int maxContacts) const {
  return collidePair(query.impl_->entry, impl_->at(b), ColliderId{}, b, maxContacts, {});
}

FclDistanceResult FclScene::distance(const FclQueryShape& query, ColliderId b) const {
  return distancePair(query.impl_->entry, impl_->at(b), ColliderId{}, b, {});
}

namespace {

FclCollideResult collidePair(const FclEntry& ea, const FclEntry& eb, ColliderId a, ColliderId b,
                             int maxContacts, const FclFaultInjector& inject) {
  FclCollideResult result;
  const bool swap = eb.isMesh && !ea.isMesh;  // FCL wants the mesh first (docs/fcl-notes.md 4.1)
  const FclEntry& first = swap ? eb : ea;
  const FclEntry& second = swap ? ea : eb;
  try {
    if (inject) inject(a, b);
    fcl::CollisionRequestd request(static_cast<std::size_t>(std::max(1, maxContacts)), true);
    request.gjk_solver_type = fcl::GST_LIBCCD;
    fcl::CollisionResultd raw;
    fcl::collide(first.object.get(), second.object.get(), request, raw);
    std::vector<fcl::Contactd> contacts;
    raw.getContacts(contacts);
    for (const fcl::Contactd& c : contacts) {
      if (!finite(c)) {
        result.contacts.clear();
        result.error = "FCL returned a non-finite contact";
        return result;
      }
      const double length = c.normal.norm();
      if (length < 0.5) continue;  // edge-touching mesh triangles, concentric spheres (4.3)
      // The normal points from c.o1 to c.o2; o1 is not always `first` (4.1).
      const bool fromFirst = c.o1 == first.geometry.get();
      const bool fromA = fromFirst != swap;
      FclContact out;
      out.position = c.pos;
      out.normal = (fromA ? 1.0 : -1.0) * c.normal / length;
      out.depth = std::abs(c.penetration_depth);  // sphere-triangle sign bug (4.2, fcl#569)
      const int t1 = static_cast<int>(c.b1), t2 = static_cast<int>(c.b2);
      const int tFirst = fromFirst ? t1 : t2, tSecond = fromFirst ? t2 : t1;
      out.triangleA = ea.isMesh ? (swap ? tSecond : tFirst) : -1;
      out.triangleB = eb.isMesh ? (swap ? tFirst : tSecond) : -1;
      result.contacts.push_back(out);
    }
  } catch (const std::exception& e) {
    result.contacts.clear();
    result.error = std::string("FCL collide threw: ") + e.what();
  } catch (...) {
    result.contacts.clear();
    result.error = "FCL collide threw a non-standard exception";
  }
  return result;
}

FclDistanceResult distancePair(const FclEntry& ea, const FclEntry& eb, ColliderId a, ColliderId b,
                               const FclFaultInjector& inject) {
  FclDistanceResult result;
  if (ea.isPlane || eb.isPlane) {  // LIBCCD segfaults on halfspace distance (fcl#623)
    result.error = "FCL distance is not available for planes";
    return result;
  }
  try {
    if (inject) inject(a, b);
    fcl::DistanceRequestd request(true);
    request.gjk_solver_type = fcl::GST_LIBCCD;
    fcl::DistanceResultd raw;
    const bool swap = eb.isMesh && !ea.isMesh;  // meshes first, as for collide
    const FclEntry& first = swap ? eb : ea;
    const FclEntry& second = swap ? ea : eb;
    fcl::distance(first.object.get(), second.object.get(), request, raw);
    fcl::Vector3d p1 = raw.nearest_points[0], p2 = raw.nearest_points[1];
    if (first.isMesh && std::holds_alternative<Sphere>(*second.shape)) {
      p1 = first.object->getTransform() * p1;  // mesh-sphere answers in local frames (section 5)
      p2 = second.object->getTransform() * p2;
    }
    result.distance = raw.min_distance;
    result.pointA = swap ? p2 : p1;
    result.pointB = swap ? p1 : p2;
    const int t1 = first.isMesh ? raw.b1 : -1, t2 = second.isMesh ? raw.b2 : -1;
    result.triangleA = swap ? t2 : t1;
    result.triangleB = swap ? t1 : t2;
    if (!std::isfinite(result.distance) || !result.pointA.allFinite() || !result.pointB.allFinite())
      result.error = "FCL distance returned a non-finite value";
  } catch (const std::exception& e) {
    result.error = std::string("FCL distance threw: ") + e.what();
  } catch (...) {
    result.error = "FCL distance threw a non-standard exception";
  }
  return result;
}

}  // namespace

}  // namespace coulomb::geometry
