// Lab 4 demo: what each broad phase costs as the number of boxes grows, how many queries each
// time-of-impact method spends for a given accuracy, the normals and depths of each narrow-phase
// routine, the contact manifolds of box-box face, edge and corner cases, a shape soup falling with its touching pairs coloured, and a fast body
// tunnelling through a thin wall between two steps.
#include <algorithm>
#include <cmath>
#include <functional>
#include <iostream>
#include <limits>
#include <memory>
#include <random>

#include "physlab/broadphase.hpp"
#include "physlab/collision.hpp"
#include "physlab/demo.hpp"
#include "physlab/error.hpp"
#include "physlab/plot.hpp"

using namespace physlab;

namespace {

const double kNaN = std::numeric_limits<double>::quiet_NaN();

// Appends a polyline (and a NaN column that ends it) to a 3 x n point list.
void appendLine(std::vector<Vec3>& out, std::initializer_list<Vec3> points) {
  out.insert(out.end(), points.begin(), points.end());
  out.push_back(Vec3::Constant(kNaN));
}

// A circle of radius r about c in the plane spanned by the unit vectors u, v.
void appendCircle(std::vector<Vec3>& out, const Vec3& c, const Vec3& u, const Vec3& v, double r) {
  for (int k = 0; k <= 24; ++k) {
    const double t = 2.0 * M_PI * k / 24;
    out.push_back(c + r * (std::cos(t) * u + std::sin(t) * v));
  }
  out.push_back(Vec3::Constant(kNaN));
}

// A wireframe of the posed shape, as line segments separated by NaN columns.
void appendWireframe(std::vector<Vec3>& out, const Shape& shape, const Pose& pose) {
  const Mat3 R = pose.q.toRotationMatrix();
  if (const auto* s = std::get_if<Sphere>(&shape)) {
    for (int k = 0; k < 3; ++k) appendCircle(out, pose.x, R.col(k), R.col((k + 1) % 3), s->radius);
  } else if (const auto* c = std::get_if<Capsule>(&shape)) {
    const std::array<Vec3, 2> ends = c->segment(pose);
    for (const Vec3& e : ends) appendCircle(out, e, R.col(0), R.col(1), c->radius);
    for (int k = 0; k < 4; ++k) {
      const Vec3 side = c->radius * (k < 2 ? 1.0 : -1.0) * R.col(k % 2);
      appendLine(out, {ends[0] + side, ends[1] + side});
    }
  } else if (const auto* b = std::get_if<Box>(&shape)) {
    const ConvexPolyhedron poly = ConvexPolyhedron::box(b->half_extents);
    for (const auto& e : poly.edges) appendLine(out, {pose.toWorld(poly.vertices[e[0]]), pose.toWorld(poly.vertices[e[1]])});
  } else if (const auto* p = std::get_if<ConvexPolyhedron>(&shape)) {
    for (const auto& e : p->edges) appendLine(out, {pose.toWorld(p->vertices[e[0]]), pose.toWorld(p->vertices[e[1]])});
  }
}

Mat3X toMatrix(const std::vector<Vec3>& points) {
  Mat3X m(3, std::max<std::size_t>(points.size(), 1));
  if (points.empty()) m.col(0) = Vec3::Constant(kNaN);
  for (std::size_t i = 0; i < points.size(); ++i) m.col(static_cast<Index>(i)) = points[i];
  return m;
}

// Whether two bodies touch: the narrow phase where the pair has a routine written, else GJK's
// overlap.
bool touching(const CollisionBody& a, const CollisionBody& b) {
  const Aabb ba = aabb(a.shape, a.pose), bb = aabb(b.shape, b.pose);
  if ((ba.max.array() < bb.min.array()).any() || (bb.max.array() < ba.min.array()).any()) return false;
  try {
    return !collide(a.shape, a.pose, b.shape, b.pose).empty();
  } catch (const InvalidInput&) {
    return distance(a.shape, a.pose, b.shape, b.pose).overlap;  // no routine for the pair
  } catch (const NotImplemented&) {
    // The pair's routine is not written yet: GJK answers alone, so that the soup needs one of
    // the two rather than every pair routine
    return distance(a.shape, a.pose, b.shape, b.pose).overlap;
  }
}

// N boxes with centres uniform in a cube of side N^(1/3) m and half-extents uniform in
// [0.18, 0.54] m per axis: the benchmark's scene, in which every box has about 3 neighbours at
// every N, so that the cost of a query shows how a method scales rather than how many pairs exist.
std::vector<Aabb> randomBoxes(int n) {
  std::mt19937_64 rng(2024);
  const double side = std::cbrt(static_cast<double>(n));
  std::uniform_real_distribution<double> position(0.0, side), half(0.18, 0.54);
  std::vector<Aabb> boxes(static_cast<std::size_t>(n));
  for (Aabb& b : boxes) {
    const Vec3 c(position(rng), position(rng), position(rng));
    const Vec3 r(half(rng), half(rng), half(rng));
    b = {c - r, c + r};
  }
  return boxes;
}

// Seconds per query: the fastest of three windows of repeated queries, each about `window`
// seconds long (the machine may be shared; the least disturbed window is the fairest).
double secondsPerQuery(BroadPhase& method, const std::vector<Aabb>& boxes, double window) {
  PairList pairs;
  Stopwatch warm;
  method.findPairs(boxes, pairs);
  const int reps = std::max(1, static_cast<int>(window / std::max(warm.seconds(), 1e-7)));
  double best = std::numeric_limits<double>::infinity();
  for (int w = 0; w < 3; ++w) {
    Stopwatch clock;
    for (int r = 0; r < reps; ++r) method.findPairs(boxes, pairs);
    best = std::min(best, clock.seconds() / reps);
  }
  return best;
}

// Broad-phase cost against N, log-log, with O(N^2) and O(N log N) guides. Brute force stops
// where one query takes about a second; a method whose code is not written yet is skipped.
void broadPhaseChart(const DemoOptions& options, std::vector<std::string>& written) {
  const std::vector<int> sizes = options.quick ? std::vector<int>{100, 316, 1000, 3162, 10000}
                                               : std::vector<int>{100, 316, 1000, 3162, 10000, 31623, 100000};
  const int brute_force_limit = options.quick ? 3162 : 10000;
  const double window = options.quick ? 0.03 : 0.1;
  const std::vector<std::unique_ptr<BroadPhase>> methods = allBroadPhases();
  std::vector<std::vector<Aabb>> scenes;
  for (const int n : sizes) scenes.push_back(randomBoxes(n));

  Chart chart("Broad phase: N random boxes to all overlapping pairs (about 3 per box)", "number of boxes N",
              "time per query [ms]");
  chart.logX().logY();
  Table table({"method", "N", "ms per query", "box tests per box"});
  // The guides pass through the measurements at N = 1000, a size both runs have: far enough
  // from the smallest N, where fixed costs per query still show, and within brute force's reach.
  const int n_anchor = 1000;
  double brute_at_anchor = NAN, fast_at_anchor = NAN;  // ms per query at n_anchor
  for (std::size_t k = 0; k < methods.size(); ++k) {
    BroadPhase& method = *methods[k];
    attempt("broad phase cost, " + method.name(), [&] {
      Series series{method.name(), {}, {}, "linespoints pt 7"};
      for (std::size_t s = 0; s < sizes.size(); ++s) {
        if (k == 0 && sizes[s] > brute_force_limit) break;
        const double ms = 1e3 * secondsPerQuery(method, scenes[s], window);
        series.x.push_back(sizes[s]);
        series.y.push_back(ms);
        if (sizes[s] == n_anchor && k == 0) brute_at_anchor = ms;
        if (sizes[s] == n_anchor && k > 0 && (std::isnan(fast_at_anchor) || ms < fast_at_anchor)) fast_at_anchor = ms;
        if (s + 1 == sizes.size() || (k == 0 && sizes[s + 1] > brute_force_limit)) {
          const double tests_per_box = static_cast<double>(method.overlapTests()) / sizes[s];
          table.add({method.name(), std::to_string(sizes[s]), fmt(ms), fmt(tests_per_box)});
        }
      }
      chart.add(series);
    });
  }
  // Guides: slope 2 through brute force, slope 1 (times log N) through the fastest other method
  // (brute force again while none is written). The quadratic guide stops at 10 s per query, so
  // that it does not stretch the axis far above every measurement.
  if (std::isnan(fast_at_anchor)) fast_at_anchor = brute_at_anchor;
  Series quadratic{"O(N^2)", {}, {}, "lines dt 2 lc rgb 'gray30'"};
  Series nlogn{"O(N log N)", {}, {}, "lines dt 3 lc rgb 'gray50'"};
  for (double n = sizes.front(); n <= sizes.back() * 1.01; n *= std::sqrt(10.0)) {
    const double quadratic_ms = brute_at_anchor * (n / n_anchor) * (n / n_anchor);
    if (quadratic_ms <= 1e4) {
      quadratic.x.push_back(n);
      quadratic.y.push_back(quadratic_ms);
    }
    nlogn.x.push_back(n);
    nlogn.y.push_back(fast_at_anchor * (n * std::log(n)) / (n_anchor * std::log(static_cast<double>(n_anchor))));
  }
  chart.add(quadratic).add(nlogn);
  for (const std::string& path : chart.save(options.out + "/lab04_broad_phase_cost")) written.push_back(path);
  std::cout << "Lab 4 broad phase, cost at the largest N each method ran:\n";
  table.print(std::cout);
}

// Work against accuracy for both methods: the error of the time of impact of two spheres and
// of the bullet at the wall against the number of queries, over tolerances 1e-1 .. 1e-10 m.
void toiChart(const DemoOptions& options, std::vector<std::string>& written, Table& table) {
  Chart chart("Time of impact: error against queries, tolerances 1e-1 to 1e-10 m (exact answers drawn at 1e-17)",
              "queries per step",
              "|t - t_{exact}| [s]");
  chart.logX().logY();
  const double h = 1.0 / 60;
  // Two spheres closing at 12 m/s that touch at t = 0.01 s, and the 300 m/s bullet and wall.
  Pose pa, pb;
  pa.x = Vec3(-0.5 - 0.06, 0.1, 0.0);
  pb.x = Vec3(0.5 + 0.06, 0.0, 0.0);
  const Motion ma{Vec3(6.0, 0.0, 0.0), Vec3::Zero()}, mb{Vec3(-6.0, 0.0, 0.0), Vec3(0.0, 0.0, 3.0)};
  const double dy = 0.1, R = 1.0, closing = 12.0;
  const double spheres_exact = (1.12 - std::sqrt(R * R - dy * dy)) / closing;
  const std::vector<CollisionBody> wall = bulletAndWall(300.0);
  const double wall_exact = (1.0 - 0.01 - 0.05) / 300.0;
  struct Case {
    const char* name;
    ToiResult (*method)(const Shape&, const Pose&, const Motion&, const Shape&, const Pose&, const Motion&, double,
                        double);
  };
  bool drawn = false;
  for (const Case& c : {Case{"bisection", toiBisection}, Case{"conservative advancement", toiConservativeAdvancement}}) {
    drawn |= attempt(std::string("time-of-impact work-precision, ") + c.name, [&] {
      // One key entry and one colour per method; the scene is the line's style, keyed once below
      const std::string colour = " lc rgb '" + methodColour(c.name) + "'";
      Series spheres{c.name, {}, {}, "linespoints pt 7" + colour}, bullet{"", {}, {}, "linespoints pt 4 ps 1.5 dt 2" + colour};
      for (int e = 1; e <= 10; ++e) {
        const double tol = std::pow(10.0, -e);
        const ToiResult s = c.method(Sphere(0.5), pa, ma, Sphere(0.5), pb, mb, h, tol);
        const ToiResult w = c.method(wall[1].shape, wall[1].pose, wall[1].motion, wall[0].shape, wall[0].pose,
                                     wall[0].motion, h, tol);
        spheres.x.push_back(s.queries);
        spheres.y.push_back(std::max(std::abs(s.time - spheres_exact), 1e-17));
        bullet.x.push_back(w.queries);
        bullet.y.push_back(std::max(std::abs(w.time - wall_exact), 1e-17));
        if (e % 3 == 1) {
          table.add({c.name, fmt(tol), std::to_string(s.queries), fmt(std::abs(s.time - spheres_exact)),
                     std::to_string(w.queries), fmt(std::abs(w.time - wall_exact))});
        }
      }
      chart.add(spheres).add(bullet);
    });
  }
  if (!drawn) return;  // both methods are stubs: no chart rather than an empty one
  chart.keyEntry("two spheres", "linespoints pt 7 lc rgb 'gray30'")
      .keyEntry("bullet at a wall", "linespoints pt 4 ps 1.5 dt 2 lc rgb 'gray30'");
  for (const std::string& path : chart.save(options.out + "/lab04_toi_work_precision")) written.push_back(path);
}

// Appends to `out` (a chart's x, y in the world's x, z) the section of a shape by the plane
// y = 0, posed with a turn about y only: a circle, a stadium or a rectangle, ended by a NaN.
void appendSection(Series& out, const Shape& shape, const Pose& pose) {
  const auto put = [&](const Vec3& p) {
    out.x.push_back(p.x());
    out.y.push_back(p.z());
  };
  if (const auto* s = std::get_if<Sphere>(&shape)) {
    for (int k = 0; k <= 48; ++k) put(pose.x + s->radius * Vec3(std::cos(M_PI * k / 24), 0.0, std::sin(M_PI * k / 24)));
  } else if (const auto* c = std::get_if<Capsule>(&shape)) {
    // The hull of the end circles: each direction's point on the circle about the end it faces
    const std::array<Vec3, 2> ends = c->segment(pose);
    const Vec3 axis = ends[1] - ends[0];
    for (int k = 0; k <= 48; ++k) {
      const Vec3 u(std::cos(M_PI * k / 24), 0.0, std::sin(M_PI * k / 24));
      put((u.dot(axis) >= 0.0 ? ends[1] : ends[0]) + c->radius * u);
    }
  } else if (const auto* b = std::get_if<Box>(&shape)) {
    const Vec3& h = b->half_extents;
    for (const auto& [sx, sz] : {std::pair{-1, -1}, {1, -1}, {1, 1}, {-1, 1}, {-1, -1}}) {
      put(pose.toWorld(Vec3(sx * h.x(), 0.0, sz * h.z())));
    }
  }
  out.x.push_back(kNaN);
  out.y.push_back(kNaN);
}

// A plane's trace in y = 0 near `at`, 2.4 m long, hatched on the solid's side.
void appendPlane(Series& out, const Plane& plane, const Vec3& at) {
  const Vec3 n = plane.normal, t(n.z(), 0.0, -n.x());
  const Vec3 p0 = at - (n.dot(at) - plane.offset) * n;
  for (const Vec3& p : std::initializer_list<Vec3>{p0 - 1.2 * t, p0 + 1.2 * t}) {
    out.x.push_back(p.x());
    out.y.push_back(p.z());
  }
  for (int k = -4; k <= 4; ++k) {
    const Vec3 p = p0 + 0.27 * k * t, q = p - 0.15 * n - 0.1 * t;
    out.x.insert(out.x.end(), {kNaN, p.x(), q.x()});
    out.y.insert(out.y.end(), {kNaN, p.z(), q.z()});
  }
  out.x.push_back(kNaN);
  out.y.push_back(kNaN);
}

// An arrow from p along the unit n (in the plane y = 0), 0.5 m long with a head, ended by a NaN.
void appendArrow(Series& out, const Vec3& p, const Vec3& n) {
  const Vec3 tip = p + 0.5 * n, side(n.z(), 0.0, -n.x());
  const Vec3 gap = Vec3::Constant(kNaN);
  for (const Vec3& q : std::initializer_list<Vec3>{p, tip, tip - 0.14 * n + 0.07 * side, gap, tip,
                                                   tip - 0.14 * n - 0.07 * side, gap}) {
    out.x.push_back(q.x());
    out.y.push_back(q.z());
  }
}

// The contacts of the narrow-phase routines on a few pairs cut by the plane y = 0: each pair in a
// cell of its own, its normal (from B to A) an arrow and its depth written at each point, so that
// a normal of the wrong sign or a depth of the wrong size shows at a glance. Each pair is drawn
// as soon as its routine is written; an unwritten one leaves its cell empty but for the reason.
void contactNormalsChart(const DemoOptions& options, std::vector<std::string>& written) {
  struct Pair {
    const char* name;  // the pair, written over its cell
    // Appends A's and B's sections to a and b and returns the manifold, for a cell centred at o
    std::function<Manifold(const Vec3& o, Series& a, Series& b)> collide;
  };
  const auto turned = [](const Vec3& x, double angle) {
    Pose pose;
    pose.x = x;
    pose.q = Quat(Eigen::AngleAxisd(angle, Vec3::UnitY()));
    return pose;
  };
  const std::vector<Pair> pairs = {
      {"sphere-sphere",
       [&](const Vec3& o, Series& a, Series& b) {
         const Sphere sa(0.5), sb(0.6);
         const Pose pa = turned(o + Vec3(0.45, 0.0, 0.7), 0.0), pb = turned(o, 0.0);
         appendSection(a, sa, pa), appendSection(b, sb, pb);
         return collideSphereSphere(sa, pa, sb, pb);
       }},
      {"sphere-plane",
       [&](const Vec3& o, Series& a, Series& b) {
         const Sphere sa(0.5);
         const Vec3 n = Vec3(-0.3, 0.0, 1.0).normalized();
         const Plane plane(n, n.dot(o + Vec3(0.0, 0.0, -0.4)));
         const Pose pa = turned(o, 0.0);
         appendSection(a, sa, pa), appendPlane(b, plane, o);
         return collideSpherePlane(sa, pa, plane);
       }},
      {"sphere-box",
       [&](const Vec3& o, Series& a, Series& b) {
         const Sphere sa(0.4);
         const Box bb(Vec3(0.6, 0.5, 0.4));
         const Pose pb = turned(o + Vec3(-0.2, 0.0, -0.2), 0.3);
         const Pose pa = turned(pb.toWorld(Vec3(0.75, 0.0, 0.55)), 0.0);
         appendSection(a, sa, pa), appendSection(b, bb, pb);
         return collideSphereBox(sa, pa, bb, pb);
       }},
      {"capsule-sphere",
       [&](const Vec3& o, Series& a, Series& b) {
         const Capsule ca(0.3, 0.5);
         const Sphere sb(0.5);
         const Pose pa = turned(o + Vec3(0.0, 0.0, 0.55), 1.2), pb = turned(o + Vec3(0.3, 0.0, -0.05), 0.0);
         appendSection(a, ca, pa), appendSection(b, sb, pb);
         return collideCapsuleSphere(ca, pa, sb, pb);
       }},
      {"capsule-capsule",
       [&](const Vec3& o, Series& a, Series& b) {
         const Capsule ca(0.25, 0.6), cb(0.3, 0.5);
         const Pose pa = turned(o + Vec3(0.1, 0.0, 0.4), 1.2), pb = turned(o + Vec3(0.0, 0.0, -0.35), 0.2);
         appendSection(a, ca, pa), appendSection(b, cb, pb);
         return collideCapsuleCapsule(ca, pa, cb, pb);
       }},
      {"box-plane",
       [&](const Vec3& o, Series& a, Series& b) {
         const Box ba(Vec3(0.6, 0.4, 0.3));
         const Plane ground(Vec3::UnitZ(), o.z() - 0.3);
         const Pose pa = turned(o + Vec3(0.0, 0.0, 0.05), 0.35);
         appendSection(a, ba, pa), appendPlane(b, ground, o);
         return collideBoxPlane(ba, pa, ground);
       }},
      {"box-box",
       [&](const Vec3& o, Series& a, Series& b) {
         const Box ba(Vec3(0.4, 0.4, 0.3)), bb(Vec3(0.7, 0.5, 0.3));
         const Pose pa = turned(o + Vec3(0.2, 0.0, 0.3), 0.5), pb = turned(o + Vec3(0.0, 0.0, -0.35), 0.0);
         appendSection(a, ba, pa), appendSection(b, bb, pb);
         return collideBoxBox(ba, pa, bb, pb);
       }},
  };
  Chart chart("Narrow-phase contacts of pairs cut by the plane y = 0: normal and depth d at each point", "x [m]",
              "z [m]");
  chart.equalAxes().xRange(-1.5, 10.5).yRange(-4.5, 1.8);
  Series a{"A", {}, {}, "lines lw 2 lc rgb '#ff9f1c'"}, b{"B", {}, {}, "lines lw 2 lc rgb '#1f5fbf'"};
  Series points{"contact point", {}, {}, "points pt 7 ps 1.2 lc rgb '#d62728'"};
  Series normals{"normal n, from B to A (0.5 m arrow)", {}, {}, "lines lw 2 lc rgb '#2ca02c'"};
  bool drawn = false;
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    const Vec3 o(3.0 * static_cast<double>(k % 4), 0.0, k < 4 ? 0.0 : -3.1);
    chart.label({o.x() - 1.3, o.z() + 1.45, pairs[k].name});
    drawn |= attempt(std::string("contact normals, ") + pairs[k].name, [&] {
      // Draw nothing of a pair whose routine throws, but the reason in its cell: its sections go
      // in only with its manifold
      Series pair_a = a, pair_b = b;
      Manifold m;
      try {
        m = pairs[k].collide(o, pair_a, pair_b);
      } catch (const NotImplemented& e) {
        // "not implemented: f (see ...)": the name of f, which fits a cell
        const std::string reason = e.what();
        const std::size_t from = reason.find(": ") + 2;
        chart.label({o.x() - 1.3, o.z() + 0.2, "not written yet:"})
            .label({o.x() - 1.3, o.z() - 0.2, reason.substr(from, reason.find(" (see ") - from)});
        throw;
      } catch (const std::exception&) {
        chart.label({o.x() - 1.3, o.z(), "threw: see the output"});
        throw;
      }
      a = std::move(pair_a), b = std::move(pair_b);
      if (m.empty()) chart.label({o.x() - 1.3, o.z() - 1.2, "no contact found"});
      for (int i = 0; i < m.count; ++i) {
        const Vec3& p = m.points[i].position;
        points.x.push_back(p.x());
        points.y.push_back(p.z());
        appendArrow(normals, p, m.normal);
        // Points that differ in y only fall on one another in the picture: one label for them
        bool seen = false;
        for (int j = 0; j < i; ++j) {
          const Vec3& q = m.points[j].position;
          seen |= std::abs(q.x() - p.x()) < 1e-6 && std::abs(q.z() - p.z()) < 1e-6;
        }
        if (!seen) chart.label({p.x(), p.z() - 0.2, "d = " + fmt(m.points[i].depth, 2) + " m"});
      }
    });
  }
  if (!drawn) return;
  chart.add(b).add(a).add(points).add(normals);
  for (const std::string& path : chart.save(options.out + "/lab04_contact_normals")) written.push_back(path);
}

// Box-box manifolds: a face on a face (turned), crossed edges, and a corner into a face.
void manifoldPicture(const DemoOptions& options, std::vector<std::string>& written) {
  attempt("box-box manifolds", [&] {
    Animation picture("Box-box contact manifolds (points red, normals from B to A green)", Vec3(-1.5, -1.5, -1.0),
                      Vec3(1.5, 1.5, 2.0), true);
    const Box a(Vec3(0.6, 0.4, 0.3)), b(Vec3(0.8, 0.8, 0.4));
    Pose pb;
    std::vector<std::pair<Pose, std::string>> cases;
    Pose face;
    face.q = Quat(Eigen::AngleAxisd(0.5, Vec3::UnitZ()));
    face.x = Vec3(0.3, 0.2, 0.4 + 0.3 - 0.05);
    cases.push_back({face, "face on face: the overlap polygon reduced to 4 points"});
    Pose edge;
    edge.q = Quat(Eigen::AngleAxisd(M_PI / 4, Vec3::UnitX())) ;
    Pose pb_edge;
    pb_edge.q = Quat(Eigen::AngleAxisd(M_PI / 4, Vec3::UnitY()));
    const double s2 = std::sqrt(2.0);
    edge.x = Vec3(0.0, 0.0, 0.35 * s2 + 0.4 * s2 - 0.05);
    cases.push_back({edge, "edge on edge: one point between the edges"});
    Pose corner;
    // Turn the corner direction (-1, -1, -1) onto -z: about (1, -1, 0) by acos(1 / sqrt(3))
    corner.q = Quat(Eigen::AngleAxisd(std::acos(1.0 / std::sqrt(3.0)), Vec3(1, -1, 0).normalized()));
    corner.x = Vec3(0.1, -0.1, 0.4 + a.half_extents.norm() - 0.05);
    cases.push_back({corner, "corner into a face: one point"});
    for (std::size_t k = 0; k < cases.size(); ++k) {
      const Box& shape_a = k == 1 ? Box(Vec3(0.6, 0.35, 0.35)) : a;
      const Box& shape_b = k == 1 ? Box(Vec3(0.4, 0.8, 0.4)) : b;
      const Pose& posed_b = k == 1 ? pb_edge : pb;
      const Manifold m = collideBoxBox(shape_a, cases[k].first, shape_b, posed_b);
      std::vector<Vec3> wa, wb, points, normals;
      appendWireframe(wa, shape_a, cases[k].first);
      appendWireframe(wb, shape_b, posed_b);
      for (int i = 0; i < m.count; ++i) {
        points.push_back(m.points[i].position);
        appendLine(normals, {m.points[i].position, m.points[i].position + 0.5 * m.normal});
      }
      picture.addFrame({{toMatrix(wb), "lines lc rgb '#1f5fbf' lw 1.5", "B"},
                        {toMatrix(wa), "lines lc rgb '#ff9f1c' lw 1.5", "A"},
                        {toMatrix(points), "points pt 7 ps 1.5 lc rgb '#d62728'", "contacts"},
                        {toMatrix(normals), "lines lc rgb '#2ca02c' lw 2", "normal"}},
                       cases[k].second + " (" + std::to_string(m.count) + " points)");
    }
    written.push_back(picture.save(options.out + "/lab04_manifolds.gif", 200));
  });
}

// A soup of shapes falling under gravity, no response: touching pairs are drawn red.
void soupAnimation(const DemoOptions& options, std::vector<std::string>& written) {
  attempt("falling shape soup", [&] {
    const std::vector<CollisionBody> start = shapeSoup(options.quick ? 10 : 24, 3.0, 4);
    const Vec3 g(0.0, 0.0, -9.81);
    Animation movie("A shape soup falling ballistically: touching pairs in red", Vec3(-3, -3, -5), Vec3(3, 3, 2), true);
    const int frames = options.quick ? 10 : 50;
    for (int f = 0; f < frames; ++f) {
      const double t = 0.02 * f;
      std::vector<CollisionBody> now = start;
      for (CollisionBody& body : now) {
        body.pose = advance(body.pose, body.motion, t);
        body.pose.x += 0.5 * t * t * g;
      }
      std::vector<bool> hit(now.size(), false);
      int pairs = 0;
      for (std::size_t i = 0; i < now.size(); ++i) {
        for (std::size_t j = i + 1; j < now.size(); ++j) {
          if (touching(now[i], now[j])) hit[i] = hit[j] = true, ++pairs;
        }
      }
      std::vector<Vec3> free, touched;
      for (std::size_t i = 0; i < now.size(); ++i) appendWireframe(hit[i] ? touched : free, now[i].shape, now[i].pose);
      movie.addFrame({{toMatrix(free), "lines lc rgb '#1f5fbf'", "apart"},
                      {toMatrix(touched), "lines lc rgb '#d62728' lw 2", "touching"}},
                     "t = " + fmt(t, 2) + " s, " + std::to_string(pairs) + " touching pairs");
    }
    written.push_back(movie.save(options.out + "/lab04_soup.gif", 8));
  });
}

// The tunnelling case: the bullet's positions at step ends never overlap the wall, while both
// time-of-impact methods find the contact inside the first step. Each method is drawn as soon as
// it is written; without either the chart would show nothing of the lab's code and is left out.
void tunnellingChart(const DemoOptions& options, std::vector<std::string>& written) {
  const double speed = 300.0, h = 1.0 / 60;
  const std::vector<CollisionBody> scene = bulletAndWall(speed);
  Chart chart("A 0.05 m bullet at 300 m/s and a 0.02 m wall, steps of 1/60 s", "time [s]", "bullet centre x [m]");
  Series steps{"bullet at step ends (discrete check: no overlap)", {}, {}, "points pt 7 ps 1.5 lc rgb 'black'"};
  for (int n = 0; n <= 3; ++n) {
    steps.x.push_back(n * h);
    steps.y.push_back(-1.0 + speed * n * h);
  }
  Series wall{"wall (|x| < 0.01 m, widened by the bullet's radius)", {0.0, 3 * h, kNaN, 0.0, 3 * h},
              {-0.06, -0.06, kNaN, 0.06, 0.06}, "lines lc rgb 'gray40'"};
  chart.add(steps).add(wall);
  struct Case {
    const char* name;
    const char* style;
    ToiResult (*method)(const Shape&, const Pose&, const Motion&, const Shape&, const Pose&, const Motion&, double,
                        double);
  };
  bool drawn = false;
  for (const Case& c : {Case{"bisection", "points pt 6 ps 2.5", toiBisection},
                        Case{"conservative advancement", "points pt 2 ps 2", toiConservativeAdvancement}}) {
    drawn |= attempt(std::string("tunnelling, ") + c.name, [&] {
      const ToiResult r = c.method(scene[1].shape, scene[1].pose, scene[1].motion, scene[0].shape, scene[0].pose,
                                   scene[0].motion, h, 1e-6);
      // Each method's time of impact in its own colour, as in the work-precision chart
      chart.add({std::string(c.name) + " (time of impact, " + std::to_string(r.queries) + " queries)", {r.time},
                 {-1.0 + speed * r.time}, c.style});
    });
  }
  if (!drawn) return;
  for (const std::string& path : chart.save(options.out + "/lab04_tunnelling")) written.push_back(path);
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const DemoOptions options = parseDemoOptions(
        argc, argv,
        "Lab 4 demo: broad-phase cost, time-of-impact work-precision, narrow-phase normals and depths, box-box "
        "manifolds, a falling soup, "
        "tunnelling.");
    std::vector<std::string> written;
    broadPhaseChart(options, written);
    Table table({"method", "tolerance [m]", "spheres: queries", "spheres: |t - t_exact| [s]", "bullet: queries",
                 "bullet: |t - t_exact| [s]"});
    toiChart(options, written, table);
    contactNormalsChart(options, written);
    manifoldPicture(options, written);
    soupAnimation(options, written);
    tunnellingChart(options, written);
    reportDemo("Lab 4", written, table, options.out + "/lab04_summary.md");
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "demo_04_collision: " << e.what() << "\n";
    return 1;
  }
}
