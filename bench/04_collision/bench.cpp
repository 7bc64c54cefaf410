// Lab 4 benchmark: the broad phases on one scene of random boxes at N = 10^2 ... 10^5 (ms per
// query and pairs found per second), side by side with Bullet's btDbvtBroadphase and FCL's
// DynamicAABBTreeCollisionManager when they are installed, which must report the same number of
// pairs; then box-box narrow-phase calls per second against Bullet's btBoxBoxDetector and FCL.
// A query is the whole job from a list of boxes to the set of overlapping pairs, for every
// engine: ours from the box vector (objects and buffers reused, as a world would), Bullet from a
// fresh broadphase to which every box is added, FCL from an emptied manager that registers
// every box again. Writes charts/lab04_bench.md and the log-log chart charts/lab04_broad_phase.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <iostream>
#include <memory>
#include <random>

#include "physlab/broadphase.hpp"
#include "physlab/collision.hpp"
#include "physlab/demo.hpp"
#include "physlab/plot.hpp"

#include "../support/goals.hpp"

#ifdef PHYSLAB_HAVE_BULLET
#include <BulletCollision/BroadphaseCollision/btDbvtBroadphase.h>
#include <BulletCollision/CollisionDispatch/btBoxBoxDetector.h>
#include <btBulletCollisionCommon.h>
#include <LinearMath/btScalar.h>
#endif

#ifdef PHYSLAB_HAVE_FCL
#include <fcl/broadphase/broadphase_dynamic_AABB_tree.h>
#include <fcl/config.h>
#include <fcl/geometry/shape/box.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/collision_object.h>
#endif

using namespace physlab;
using physlab::bench::printGoal;

namespace {

// One box of the scene: centre c and half-extents r. Every engine is given exactly min = c - r
// and max = c + r (FCL computes the same doubles from a box of side 2r at translation c).
struct SceneBox {
  Vec3 c, r;
};

// N boxes with centres uniform in a cube of side N^(1/3) m (one centre per cubic metre) and
// half-extents uniform in [0.18, 0.54] m per axis. Two boxes overlap when their centres are
// closer than the sum of the half-extents on every axis, which for these sizes and this
// density gives each box about 3 neighbours at every N.
std::vector<SceneBox> makeScene(int n, unsigned seed) {
  std::mt19937_64 rng(seed);
  const double side = std::cbrt(static_cast<double>(n));
  std::uniform_real_distribution<double> position(0.0, side), half(0.18, 0.54);
  std::vector<SceneBox> scene(static_cast<std::size_t>(n));
  for (SceneBox& b : scene) {
    b.c = Vec3(position(rng), position(rng), position(rng));
    b.r = Vec3(half(rng), half(rng), half(rng));
  }
  return scene;
}

std::vector<Aabb> toAabbs(const std::vector<SceneBox>& scene) {
  std::vector<Aabb> boxes;
  for (const SceneBox& b : scene) boxes.push_back({b.c - b.r, b.c + b.r});
  return boxes;
}

struct Timing {
  double seconds = NAN;  // per query, best window
  long pairs = -1;       // pairs the engine reported
};

// Runs `query` once to warm up (caches, buffers, the pair count), then `windows` windows of
// enough repetitions to last about `window_seconds`, and keeps the fastest window's time per
// query: the machine is shared, and the least disturbed window is the fairest for every engine.
Timing measure(const std::function<long()>& query, int windows, double window_seconds) {
  Timing t;
  Stopwatch warm;
  t.pairs = query();
  const double once = std::max(warm.seconds(), 1e-7);
  const int reps = std::max(1, static_cast<int>(window_seconds / once));
  t.seconds = INFINITY;
  for (int w = 0; w < windows; ++w) {
    Stopwatch clock;
    long pairs = 0;
    for (int r = 0; r < reps; ++r) pairs = query();
    t.seconds = std::min(t.seconds, clock.seconds() / reps);
    if (pairs != t.pairs) throw std::runtime_error("a query changed its answer between runs");
  }
  return t;
}

#ifdef PHYSLAB_HAVE_BULLET
// Bullet: a fresh dynamic-tree broadphase, every box added as a proxy, then the pairs computed.
class BulletBroadPhase {
 public:
  explicit BulletBroadPhase(const std::vector<SceneBox>& scene) : scene_(scene) {}
  long query() {
    auto broadphase = std::make_unique<btDbvtBroadphase>();
    for (std::size_t i = 0; i < scene_.size(); ++i) {
      const SceneBox& b = scene_[i];
      const Vec3 lo = b.c - b.r, hi = b.c + b.r;
      broadphase->createProxy(btVector3(lo.x(), lo.y(), lo.z()), btVector3(hi.x(), hi.y(), hi.z()),
                              BOX_SHAPE_PROXYTYPE, nullptr, btBroadphaseProxy::DefaultFilter,
                              btBroadphaseProxy::AllFilter, &dispatcher_);
    }
    broadphase->calculateOverlappingPairs(&dispatcher_);
    const long pairs = broadphase->getOverlappingPairCache()->getNumOverlappingPairs();
    previous_ = std::move(broadphase);  // destroyed at the next query, not inside this one's time
    return pairs;
  }

 private:
  const std::vector<SceneBox>& scene_;
  btDefaultCollisionConfiguration config_;
  btCollisionDispatcher dispatcher_{&config_};
  std::unique_ptr<btDbvtBroadphase> previous_;
};
#endif

#ifdef PHYSLAB_HAVE_FCL
// FCL: the manager emptied, every box registered again (a bulk top-down build), then the pairs
// reported to a callback that counts them.
class FclBroadPhase {
 public:
  explicit FclBroadPhase(const std::vector<SceneBox>& scene) {
    for (const SceneBox& b : scene) {
      auto shape = std::make_shared<fcl::Boxd>(2.0 * b.r.x(), 2.0 * b.r.y(), 2.0 * b.r.z());
      fcl::Transform3d pose = fcl::Transform3d::Identity();
      pose.translation() = b.c;
      objects_.push_back(std::make_unique<fcl::CollisionObjectd>(shape, pose));
      pointers_.push_back(objects_.back().get());
    }
  }
  long query() {
    manager_.clear();
    manager_.registerObjects(pointers_);
    manager_.setup();
    long pairs = 0;
    manager_.collide(&pairs, [](fcl::CollisionObjectd*, fcl::CollisionObjectd*, void* count) {
      ++*static_cast<long*>(count);
      return false;  // keep going
    });
    return pairs;
  }

 private:
  std::vector<std::unique_ptr<fcl::CollisionObjectd>> objects_;
  std::vector<fcl::CollisionObjectd*> pointers_;
  fcl::DynamicAABBTreeCollisionManagerd manager_;
};
#endif

// Two configurations of a moving scene: every box displaced by its own small step (up to 2 cm
// per axis, about 5% of a box), the motion of one time step. A timed "step" moves every box to
// the other configuration and finds the pairs, so each engine redoes the same work every step.
struct MovingScene {
  std::vector<SceneBox> a, b;
  std::vector<Aabb> boxes_a, boxes_b;
};

MovingScene makeMovingScene(const std::vector<SceneBox>& scene) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> step(-0.02, 0.02);
  MovingScene m{scene, scene, toAabbs(scene), {}};
  for (SceneBox& box : m.b) box.c += Vec3(step(rng), step(rng), step(rng));
  m.boxes_b = toAabbs(m.b);
  return m;
}

#ifdef PHYSLAB_HAVE_BULLET
// Bullet's intended use: proxies kept, setAabb per moved box, then calculateOverlappingPairs.
// Its tree holds enlarged ("fat") boxes and removes stale pairs a few per call, so its cache holds
// a superset of the overlapping pairs; the exact ones are counted with the proxies' own boxes.
class BulletMoving {
 public:
  explicit BulletMoving(const std::vector<SceneBox>& scene) {
    for (const SceneBox& b : scene) {
      const Vec3 lo = b.c - b.r, hi = b.c + b.r;
      proxies_.push_back(broadphase_.createProxy(btVector3(lo.x(), lo.y(), lo.z()), btVector3(hi.x(), hi.y(), hi.z()),
                                                 BOX_SHAPE_PROXYTYPE, nullptr, btBroadphaseProxy::DefaultFilter,
                                                 btBroadphaseProxy::AllFilter, &dispatcher_));
    }
    broadphase_.calculateOverlappingPairs(&dispatcher_);
  }
  long step(const std::vector<SceneBox>& scene) {
    for (std::size_t i = 0; i < scene.size(); ++i) {
      const Vec3 lo = scene[i].c - scene[i].r, hi = scene[i].c + scene[i].r;
      broadphase_.setAabb(proxies_[i], btVector3(lo.x(), lo.y(), lo.z()), btVector3(hi.x(), hi.y(), hi.z()), &dispatcher_);
    }
    broadphase_.calculateOverlappingPairs(&dispatcher_);
    long exact = 0;
    const btBroadphasePairArray& cache = broadphase_.getOverlappingPairCache()->getOverlappingPairArray();
    for (int k = 0; k < cache.size(); ++k) {
      const btBroadphaseProxy* p = cache[k].m_pProxy0;
      const btBroadphaseProxy* q = cache[k].m_pProxy1;
      exact += TestAabbAgainstAabb2(p->m_aabbMin, p->m_aabbMax, q->m_aabbMin, q->m_aabbMax);
    }
    return exact;
  }

 private:
  btDefaultCollisionConfiguration config_;
  btCollisionDispatcher dispatcher_{&config_};
  btDbvtBroadphase broadphase_;
  std::vector<btBroadphaseProxy*> proxies_;
};
#endif

#ifdef PHYSLAB_HAVE_FCL
// FCL's intended use: objects moved (translation and AABB recomputed), update() refits the tree.
class FclMoving {
 public:
  explicit FclMoving(const std::vector<SceneBox>& scene) {
    for (const SceneBox& b : scene) {
      auto shape = std::make_shared<fcl::Boxd>(2.0 * b.r.x(), 2.0 * b.r.y(), 2.0 * b.r.z());
      fcl::Transform3d pose = fcl::Transform3d::Identity();
      pose.translation() = b.c;
      objects_.push_back(std::make_unique<fcl::CollisionObjectd>(shape, pose));
      pointers_.push_back(objects_.back().get());
    }
    manager_.registerObjects(pointers_);
    manager_.setup();
  }
  long step(const std::vector<SceneBox>& scene) {
    for (std::size_t i = 0; i < scene.size(); ++i) {
      objects_[i]->setTranslation(scene[i].c);
      objects_[i]->computeAABB();
    }
    manager_.update();
    long pairs = 0;
    manager_.collide(&pairs, [](fcl::CollisionObjectd*, fcl::CollisionObjectd*, void* count) {
      ++*static_cast<long*>(count);
      return false;  // keep going
    });
    return pairs;
  }

 private:
  std::vector<std::unique_ptr<fcl::CollisionObjectd>> objects_;
  std::vector<fcl::CollisionObjectd*> pointers_;
  fcl::DynamicAABBTreeCollisionManagerd manager_;
};
#endif

// Our methods in the moving-box table (sort and sweep, BVH, grid, k-d tree, incremental tree);
// the peers' rows follow them, Bullet's first.
constexpr std::size_t kOurMovingMethods = 5;

// One engine's results over the sizes, for the table and the chart.
struct Row {
  std::string engine, method;
  std::string label;       // short legend entry for the chart
  std::vector<Timing> at;  // one per size
};

// Pairs of boxes at random poses for the narrow phase: half-extents in [0.2, 0.6] m, B's centre
// within 1.2 m of A's on each axis, so that about half of the pairs touch.
struct BoxPairCase {
  Vec3 ha, hb;
  Pose pa, pb;
};

std::vector<BoxPairCase> makeBoxPairs(int count) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> half(0.2, 0.6), offset(-1.2, 1.2);
  std::normal_distribution<double> normal;
  std::vector<BoxPairCase> cases(static_cast<std::size_t>(count));
  for (BoxPairCase& c : cases) {
    c.ha = Vec3(half(rng), half(rng), half(rng));
    c.hb = Vec3(half(rng), half(rng), half(rng));
    c.pa.q = Quat(normal(rng), normal(rng), normal(rng), normal(rng)).normalized();
    c.pb.x = Vec3(offset(rng), offset(rng), offset(rng));
    c.pb.q = Quat(normal(rng), normal(rng), normal(rng), normal(rng)).normalized();
  }
  return cases;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const DemoOptions options = parseDemoOptions(
        argc, argv, "Lab 4 benchmark: broad phases against Bullet's and FCL's dynamic AABB trees.");
    const std::vector<int> sizes = options.quick ? std::vector<int>{100, 1000, 10000}
                                                 : std::vector<int>{100, 316, 1000, 3162, 10000, 31623, 100000};
    const int windows = options.quick ? 2 : 5;
    const double window_seconds = options.quick ? 0.02 : 0.15;
    const int brute_force_limit = 10000;  // 5e7 tests per query; 10^5 boxes would take ~10 s each

    std::vector<Row> rows;
    const std::vector<std::unique_ptr<BroadPhase>> methods = allBroadPhases();
    for (const auto& m : methods) rows.push_back({"PhysLab", m->name(), m->name(), {}});
    Row sap_update{"PhysLab", "sort and sweep, update (boxes unmoved)", "sort and sweep, update (unmoved)", {}};
    Row bvh_refit{"PhysLab", "BVH, refit (boxes unmoved)", "BVH, refit (unmoved)", {}};
#ifdef PHYSLAB_HAVE_BULLET
    const std::string bullet = "Bullet " + std::to_string(btGetVersion() / 100) + "." + std::to_string(btGetVersion() % 100);
    Row bullet_row{bullet, "btDbvtBroadphase", "Bullet btDbvt", {}};
#endif
#ifdef PHYSLAB_HAVE_FCL
    Row fcl_row{std::string("FCL ") + FCL_VERSION, "DynamicAABBTreeCollisionManager", "FCL AABB tree", {}};
#endif

    bool counts_agree = true;
    std::vector<std::vector<Timing>> moving_steps;  // per table size: one Timing per engine
    for (const int n : sizes) {
      const std::vector<SceneBox> scene = makeScene(n, 2024);
      const std::vector<Aabb> boxes = toAabbs(scene);
      long reference = -1;
      for (std::size_t k = 0; k < methods.size(); ++k) {
        BroadPhase& method = *methods[k];
        if (k == 0 && n > brute_force_limit) {
          rows[k].at.push_back(Timing{});
          continue;
        }
        PairList pairs;
        const Timing t = measure([&] {
          method.findPairs(boxes, pairs);
          return static_cast<long>(pairs.size());
        }, windows, window_seconds);
        if (reference < 0) reference = t.pairs;
        counts_agree = counts_agree && t.pairs == reference;
        rows[k].at.push_back(t);
      }
      {  // the incremental paths on an unmoved scene: the floor of a step with temporal coherence
        SweepAndPrune sap;
        Bvh bvh;
        PairList pairs;
        sap.build(boxes, pairs);
        bvh.build(boxes, pairs);
        sap_update.at.push_back(measure([&] {
          sap.update(boxes, pairs);
          return static_cast<long>(pairs.size());
        }, windows, window_seconds));
        bvh_refit.at.push_back(measure([&] {
          bvh.refit(boxes, pairs);
          return static_cast<long>(pairs.size());
        }, windows, window_seconds));
      }
#ifdef PHYSLAB_HAVE_BULLET
      BulletBroadPhase bullet_phase(scene);
      bullet_row.at.push_back(measure([&] { return bullet_phase.query(); }, windows, window_seconds));
      counts_agree = counts_agree && bullet_row.at.back().pairs == reference;
#endif
#ifdef PHYSLAB_HAVE_FCL
      FclBroadPhase fcl_phase(scene);
      fcl_row.at.push_back(measure([&] { return fcl_phase.query(); }, windows, window_seconds));
      counts_agree = counts_agree && fcl_row.at.back().pairs == reference;
#endif
      if (n == 1000 || n == 10000 || n == 100000) {
        // Moving boxes: two steps per measured call (to configuration b, back to a), so that
        // every call does the same work; the pair counts of both steps are summed.
        const MovingScene moving = makeMovingScene(scene);
        SweepAndPrune sap;
        Bvh bvh;
        PairList pairs;
        sap.build(moving.boxes_a, pairs);
        bvh.build(moving.boxes_a, pairs);
        const auto ours = [&](const std::function<void(const std::vector<Aabb>&)>& find) {
          return measure([&] {
            find(moving.boxes_b);
            long total = static_cast<long>(pairs.size());
            find(moving.boxes_a);
            return total + static_cast<long>(pairs.size());
          }, windows, window_seconds);
        };
        std::vector<Timing> step;
        step.push_back(ours([&](const std::vector<Aabb>& boxes_now) { sap.update(boxes_now, pairs); }));
        step.push_back(ours([&](const std::vector<Aabb>& boxes_now) { bvh.refit(boxes_now, pairs); }));
        step.push_back(ours([&](const std::vector<Aabb>& boxes_now) { methods[2]->findPairs(boxes_now, pairs); }));
        step.push_back(ours([&](const std::vector<Aabb>& boxes_now) { methods[4]->findPairs(boxes_now, pairs); }));
        IncrementalBroadPhase incremental;  // built on configuration a, like the peers below
        incremental.findPairs(moving.boxes_a, pairs);
        step.push_back(ours([&](const std::vector<Aabb>& boxes_now) { incremental.findPairs(boxes_now, pairs); }));
#ifdef PHYSLAB_HAVE_BULLET
        BulletMoving bullet_moving(moving.a);
        step.push_back(measure([&] { return bullet_moving.step(moving.b) + bullet_moving.step(moving.a); },
                               windows, window_seconds));
#endif
#ifdef PHYSLAB_HAVE_FCL
        FclMoving fcl_moving(moving.a);
        step.push_back(measure([&] { return fcl_moving.step(moving.b) + fcl_moving.step(moving.a); },
                               windows, window_seconds));
#endif
        for (const Timing& t : step) counts_agree = counts_agree && t.pairs == step.front().pairs;
        moving_steps.push_back(step);
      }
      std::cout << "N = " << n << ": " << reference << " pairs (" << fmt(2.0 * reference / n) << " per box)\n";
    }
    rows.push_back(sap_update);
    rows.push_back(bvh_refit);
#ifdef PHYSLAB_HAVE_BULLET
    rows.push_back(bullet_row);
#endif
#ifdef PHYSLAB_HAVE_FCL
    rows.push_back(fcl_row);
#endif

    // Table at N = 10^3, 10^4, 10^5: ms per query, and pairs found per second.
    std::vector<std::string> header = {"engine", "method"};
    std::vector<std::size_t> columns;
    for (std::size_t s = 0; s < sizes.size(); ++s) {
      if (sizes[s] == 1000 || sizes[s] == 10000 || sizes[s] == 100000) {
        columns.push_back(s);
        header.push_back("N = " + std::to_string(sizes[s]) + ": ms per query");
        header.push_back("pairs per second");
      }
    }
    header.push_back("pairs reported");
    Table table(header);
    for (const Row& row : rows) {
      std::vector<std::string> cells = {row.engine, row.method};
      std::string counts;
      for (std::size_t s : columns) {
        const Timing& t = row.at[s];
        const bool ran = std::isfinite(t.seconds);
        cells.push_back(ran ? fmt(1e3 * t.seconds) : "-");
        cells.push_back(ran ? fmt(t.pairs / t.seconds) : "-");
        counts += (counts.empty() ? "" : " / ") + (ran ? std::to_string(t.pairs) : std::string("-"));
      }
      cells.push_back(counts);
      table.add(cells);
    }

    // Moving boxes: ms per step (half a measured call) at each table size.
    std::vector<std::string> moving_header = {"engine", "per step"};
    for (std::size_t s : columns) moving_header.push_back("N = " + std::to_string(sizes[s]) + ": ms per step");
    moving_header.push_back("pairs per step (mean)");
    Table moving_table(moving_header);
    std::vector<std::pair<std::string, std::string>> moving_rows = {
        {"PhysLab", "sort and sweep: update (insertion sort)"},
        {"PhysLab", "BVH: refit"},
        {"PhysLab", "uniform grid: from scratch"},
        {"PhysLab", "k-d tree: from scratch"},
        {"PhysLab", "incremental AABB tree: findPairs (fat boxes, kept pairs)"}};
#ifdef PHYSLAB_HAVE_BULLET
    moving_rows.push_back({bullet, "btDbvtBroadphase: setAabb + calculateOverlappingPairs"});
#endif
#ifdef PHYSLAB_HAVE_FCL
    moving_rows.push_back({std::string("FCL ") + FCL_VERSION, "DynamicAABBTreeCollisionManager: update + collide"});
#endif
    for (std::size_t e = 0; e < moving_rows.size(); ++e) {
      std::vector<std::string> cells = {moving_rows[e].first, moving_rows[e].second};
      std::string counts;
      for (const std::vector<Timing>& at : moving_steps) {
        cells.push_back(fmt(1e3 * at[e].seconds / 2));
        counts += (counts.empty() ? "" : " / ") + fmt(at[e].pairs / 2.0, 6);
      }
      cells.push_back(counts);
      moving_table.add(cells);
    }

    // The chart: cost per query against N, log-log, with O(N^2) and O(N log N) guides.
    Chart chart("Broad phase: N random boxes to all overlapping pairs", "number of boxes N",
                "time per query [ms]");
    chart.logX().logY();
    for (const Row& row : rows) {
      // Colours name the method (the demo's too); an update of unmoved boxes is dashed
      const bool update = row.label.find("unmoved") != std::string::npos;
      Series series{row.label, {}, {}, update ? "linespoints pt 6 dt 2" : "linespoints pt 7"};
      for (std::size_t s = 0; s < sizes.size(); ++s) {
        if (std::isfinite(row.at[s].seconds)) {
          series.x.push_back(sizes[s]);
          series.y.push_back(1e3 * row.at[s].seconds);
        }
      }
      chart.add(series);
    }
    // Guides through the grid's cost at the smallest N: slopes 2 and 1 (times log N).
    const double n0 = sizes.front(), t0 = 1e3 * rows[2].at.front().seconds;
    Series quadratic{"O(N^2)", {}, {}, "lines dt 2 lc rgb 'gray30'"};
    Series nlogn{"O(N log N)", {}, {}, "lines dt 3 lc rgb 'gray50'"};
    for (double n = n0; n <= sizes.back() * 1.01; n *= std::sqrt(10.0)) {
      quadratic.x.push_back(n);
      quadratic.y.push_back(t0 * (n / n0) * (n / n0));
      nlogn.x.push_back(n);
      nlogn.y.push_back(t0 * (n * std::log(n)) / (n0 * std::log(n0)));
    }
    chart.add(quadratic).add(nlogn);
    const std::vector<std::string> chart_paths = chart.save(options.out + "/lab04_broad_phase");

    // Narrow phase: box-box calls per second on the same random pairs for every engine.
    const std::vector<BoxPairCase> cases = makeBoxPairs(options.quick ? 200 : 2000);
    Table narrow({"engine", "box-box test", "calls per second", "pairs in contact"});
    std::vector<Box> our_boxes;  // made (and validated) once, like the peers' shapes
    for (const BoxPairCase& c : cases) {
      our_boxes.emplace_back(c.ha);
      our_boxes.emplace_back(c.hb);
    }
    const Timing ours_box = measure([&] {
      long touching = 0;
      for (std::size_t k = 0; k < cases.size(); ++k) {
        touching += !collideBoxBox(our_boxes[2 * k], cases[k].pa, our_boxes[2 * k + 1], cases[k].pb).empty();
      }
      return touching;
    }, windows, window_seconds);
    narrow.add({"PhysLab", "collideBoxBox (SAT + clipping)", fmt(cases.size() / ours_box.seconds),
                std::to_string(ours_box.pairs) + " of " + std::to_string(cases.size())});
#ifdef PHYSLAB_HAVE_BULLET
    double bullet_box_seconds = 0.0;
    {
      struct Count : btDiscreteCollisionDetectorInterface::Result {
        int points = 0;
        void setShapeIdentifiersA(int, int) override {}
        void setShapeIdentifiersB(int, int) override {}
        void addContactPoint(const btVector3&, const btVector3&, btScalar) override { ++points; }
      };
      const auto toBullet = [](const Pose& p) {
        return btTransform(btQuaternion(p.q.x(), p.q.y(), p.q.z(), p.q.w()), btVector3(p.x.x(), p.x.y(), p.x.z()));
      };
      std::vector<std::unique_ptr<btBoxShape>> shapes;
      for (const BoxPairCase& c : cases) {
        shapes.push_back(std::make_unique<btBoxShape>(btVector3(c.ha.x(), c.ha.y(), c.ha.z())));
        shapes.push_back(std::make_unique<btBoxShape>(btVector3(c.hb.x(), c.hb.y(), c.hb.z())));
      }
      const Timing t = measure([&] {
        long touching = 0;
        for (std::size_t k = 0; k < cases.size(); ++k) {
          btBoxBoxDetector detector(shapes[2 * k].get(), shapes[2 * k + 1].get());
          btDiscreteCollisionDetectorInterface::ClosestPointInput input;
          input.m_transformA = toBullet(cases[k].pa);
          input.m_transformB = toBullet(cases[k].pb);
          Count count;
          detector.getClosestPoints(input, count, nullptr);
          touching += count.points > 0;
        }
        return touching;
      }, windows, window_seconds);
      narrow.add({bullet, "btBoxBoxDetector", fmt(cases.size() / t.seconds),
                  std::to_string(t.pairs) + " of " + std::to_string(cases.size())});
      std::cout << "box-box calls, PhysLab time / Bullet time: " << fmt(ours_box.seconds / t.seconds) << "\n";
      bullet_box_seconds = t.seconds;
    }
#else
    narrow.add({"Bullet", "not installed", "-", "-"});
#endif
#ifdef PHYSLAB_HAVE_FCL
    {
      std::vector<std::unique_ptr<fcl::CollisionObjectd>> objects;
      for (const BoxPairCase& c : cases) {
        for (const auto& [h, p] : {std::pair<Vec3, Pose>{c.ha, c.pa}, std::pair<Vec3, Pose>{c.hb, c.pb}}) {
          fcl::Transform3d pose = fcl::Transform3d::Identity();
          pose.linear() = p.q.toRotationMatrix();
          pose.translation() = p.x;
          objects.push_back(std::make_unique<fcl::CollisionObjectd>(
              std::make_shared<fcl::Boxd>(2.0 * h.x(), 2.0 * h.y(), 2.0 * h.z()), pose));
        }
      }
      const fcl::CollisionRequestd request(4, true);  // up to 4 contacts, with points: a manifold
      const Timing t = measure([&] {
        long touching = 0;
        for (std::size_t k = 0; k < cases.size(); ++k) {
          fcl::CollisionResultd result;
          touching += fcl::collide(objects[2 * k].get(), objects[2 * k + 1].get(), request, result) > 0;
        }
        return touching;
      }, windows, window_seconds);
      narrow.add({std::string("FCL ") + FCL_VERSION, "collide(Box, Box), 4 contacts", fmt(cases.size() / t.seconds),
                  std::to_string(t.pairs) + " of " + std::to_string(cases.size())});
      std::cout << "box-box calls, PhysLab time / FCL time: " << fmt(ours_box.seconds / t.seconds) << "\n";
    }
#else
    narrow.add({"FCL", "not installed", "-", "-"});
#endif

    // Ratios to the peers at the largest N, for the summary line.
    const std::size_t last = sizes.size() - 1;
    for (const Row& peer : rows) {
      if (peer.engine == "PhysLab") continue;
      for (std::size_t k = 1; k < methods.size(); ++k) {
        std::cout << "N = " << sizes[last] << ", " << rows[k].method << " time / " << peer.engine << " time: "
                  << fmt(rows[k].at[last].seconds / peer.at[last].seconds) << "\n";
      }
    }
    std::cout << (counts_agree ? "every engine reported the same pair count at every N\n"
                               : "WARNING: the engines disagree on the pair count (see the last column)\n");
    std::cout << "Lab 4 benchmark: broad phase, one query from N random boxes to all overlapping pairs\n";
    table.print(std::cout);
    std::cout << "\nLab 4 benchmark: moving boxes (every box moves up to 2 cm per axis per step)\n";
    moving_table.print(std::cout);
    std::cout << "\nLab 4 benchmark: narrow phase, " << cases.size() << " box pairs at random poses\n";
    narrow.print(std::cout);
    // One Markdown file with both tables: the broad phase's, then the narrow phase's.
    const std::string path = table.saveMarkdown(options.out + "/lab04_bench.md");
    const std::string moving_path = moving_table.saveMarkdown(options.out + "/lab04_bench_moving.md");
    const std::string narrow_path = narrow.saveMarkdown(options.out + "/lab04_bench_narrow.md");
    {
      std::ifstream moving_file(moving_path), narrow_file(narrow_path);
      std::ofstream out(path, std::ios::app);
      out << "\nMoving boxes: every box moves up to 2 cm per axis per step.\n\n" << moving_file.rdbuf();
      out << "\nNarrow phase: " << cases.size() << " box pairs at random poses.\n\n" << narrow_file.rdbuf();
    }
    std::remove(moving_path.c_str());
    std::remove(narrow_path.c_str());
    std::cout << "wrote " << path << "\n";
    for (const std::string& p : chart_paths) std::cout << "wrote " << p << "\n";

    // The goals (issue 23): our best moving-box method at or below Bullet's dynamic tree at every
    // table size, and our box-box calls per second at or above Bullet's.
    for (std::size_t k = 0; k < moving_steps.size(); ++k) {
      const std::vector<Timing>& at = moving_steps[k];
      double best = at[0].seconds;
      for (std::size_t e = 1; e < kOurMovingMethods; ++e) best = std::min(best, at[e].seconds);
      const std::string what = "moving-box broad phase at N = " + std::to_string(sizes[columns[k]]) + ", ms per step";
#ifdef PHYSLAB_HAVE_BULLET
      printGoal(what, fmt(1e3 * best / 2), fmt(1e3 * at[kOurMovingMethods].seconds / 2) + " (Bullet's dynamic tree)",
                best <= at[kOurMovingMethods].seconds);
#else
      printGoal(what, fmt(1e3 * best / 2), "Bullet's (not installed in this run)", false);
#endif
    }
#ifdef PHYSLAB_HAVE_BULLET
    printGoal("box-box narrow phase, calls per second", fmt(cases.size() / ours_box.seconds),
              fmt(cases.size() / bullet_box_seconds) + " (Bullet's btBoxBoxDetector)",
              ours_box.seconds <= bullet_box_seconds);
#else
    printGoal("box-box narrow phase, calls per second", fmt(cases.size() / ours_box.seconds),
              "Bullet's (not installed in this run)", false);
#endif
    return counts_agree ? 0 : 1;
  } catch (const std::exception& e) {
    std::cerr << "bench_04_collision: " << e.what() << "\n";
    return 1;
  }
}
