// Lab 3 demo: how orientation representations and integrators drift, the Dzhanibekov flip,
// cost against accuracy for a torque-free body, and a tumbling box with its fixed L.
#include <algorithm>
#include <cmath>
#include <functional>
#include <iostream>

#include "physlab/demo.hpp"
#include "physlab/error.hpp"
#include "physlab/integrators.hpp"
#include "physlab/plot.hpp"
#include "physlab/rigid.hpp"
#include "physlab/special_functions.hpp"

using namespace physlab;

namespace {

const Mat3 kInertia = Vec3(1.0, 2.0, 3.0).asDiagonal();
const Vec3 kOmega0(0.4, 1.0, 0.6);  // body frame, a generic tumble

// Line style of one curve: the colour names the integrator, the dash pattern the orientation
// form, so that nine curves stay legible (gnuplot's default palette repeats after eight).
std::string curveStyle(Method method, int form) {
  return "lines lc rgb '" + methodColour(methodName(method)) + "' dt " + std::to_string(form + 1);
}

// Relative drift of the body-frame angular momentum magnitude |R^T L| from |L_0|. World L is
// constant exactly (Ldot = 0 in the momentum form), so all its drift comes from R leaving the
// rotations. Exact zeros are lifted to 1e-17 so that they stay visible on the log axis.
double momentumDrift(const Mat3& R, const Vec3& L, double L0) {
  return std::max(std::abs((R.transpose() * L).norm() - L0) / L0, 1e-17);
}

// Relative energy and angular momentum drift over time for the quaternion form and both matrix
// forms.
void driftCharts(const DemoOptions& options, std::vector<std::string>& written, Table& table) {
  const RigidBody body(1.0, kInertia);
  const double h = 0.01, T = options.quick ? 10.0 : 60.0;
  const long steps = std::lround(T / h);
  // With no torque symplectic Euler's kick changes nothing: its curves lie on explicit Euler's.
  Chart energy("Torque-free body, h = 0.01: kinetic energy drift (symplectic Euler = explicit Euler here)",
               "time [s]", "|E - E_0| / E_0");
  Chart constraint("Torque-free body, h = 0.01: drift off the rotation group (no correction)",
                   "time [s]", "| |q| - 1 |   or   |R^T R - 1|");
  Chart momentum("Torque-free body, h = 0.01: body-frame angular momentum drift (world L is exact)",
                 "time [s]", "| |R^T L| - |L_0| | / |L_0|");
  energy.logY();
  constraint.logY();
  momentum.logY();
  std::vector<Series> drift;  // the momentum chart's curves, drawn after the merges below
  for (Method method : {Method::ExplicitEuler, Method::SymplecticEuler, Method::RK4}) {
    const std::string m = methodName(method);
    attempt(m + " (quaternion)", [&] {
      RigidBodySystem sys(body);
      for (bool renormalize : {true, false}) {
        sys.setRenormalize(renormalize);
        VecX X = sys.makeState(Vec3::Zero(), Quat::Identity(), Vec3::Zero(), kInertia * kOmega0);
        const double E0 = sys.kineticEnergy(X), L0 = X.segment<3>(10).norm();
        Series e{m + ", quaternion", {}, {}, curveStyle(method, 0)},
            c{m + ", |q| - 1", {}, {}, curveStyle(method, 0)}, l{m + ", quaternion", {}, {}, curveStyle(method, 0)};
        Integrator integrator(method);
        for (long n = 1; n <= steps; ++n) {
          integrator.step(sys, X, h);
          if (n % 20 == 0) {
            e.x.push_back(n * h);
            e.y.push_back(std::abs(sys.kineticEnergy(X) - E0) / E0);
            c.x.push_back(n * h);
            c.y.push_back(std::abs(orientationOf(X).norm() - 1.0));
            l.x.push_back(n * h);
            l.y.push_back(momentumDrift(orientationOf(X).toRotationMatrix(), X.segment<3>(10), L0));
          }
        }
        if (renormalize) {
          table.add({m, "quaternion, renormalised", fmt(e.y.back()), fmt(l.y.back())});
          energy.add(e);
          drift.push_back(l);
        } else {
          constraint.add(c);
        }
      }
    });
    for (bool gs : {false, true}) {
      const std::string form = gs ? "matrix + Gram-Schmidt" : "matrix";
      attempt(m + " (" + form + ")", [&] {
        const RotationMatrixSystem sys(body, gs);
        VecX X = sys.makeState(Vec3::Zero(), Quat::Identity(), Vec3::Zero(), kInertia * kOmega0);
        const double E0 = sys.kineticEnergy(X), L0 = X.segment<3>(15).norm();
        Series e{m + ", " + form, {}, {}, curveStyle(method, gs ? 2 : 1)},
            c{m + ", |R^T R - 1|", {}, {}, curveStyle(method, 1)}, l{m + ", " + form, {}, {}, curveStyle(method, gs ? 2 : 1)};
        Integrator integrator(method);
        for (long n = 1; n <= steps; ++n) {
          integrator.step(sys, X, h);
          if (n % 20 == 0) {
            e.x.push_back(n * h);
            e.y.push_back(std::abs(sys.kineticEnergy(X) - E0) / E0);
            c.x.push_back(n * h);
            c.y.push_back(sys.orthonormalityError(X));
            l.x.push_back(n * h);
            l.y.push_back(momentumDrift(Eigen::Map<const Mat3>(X.data() + 3), X.segment<3>(15), L0));
          }
        }
        table.add({m, form, fmt(e.y.back()), fmt(l.y.back())});
        energy.add(e);
        drift.push_back(l);
        if (!gs) constraint.add(c);
      });
    }
  }
  for (const auto& p : energy.save(options.out + "/lab03_energy_drift")) written.push_back(p);
  for (const auto& p : constraint.save(options.out + "/lab03_constraint_drift")) written.push_back(p);
  // Readable without the text: curves at round-off become one band (their largest value at each
  // time), and symplectic Euler, the same as explicit Euler without torque, is named, not drawn
  Series band{"round-off (quaternion, Gram-Schmidt)", {}, {}, "lines lw 1 lc rgb 'gray40'"};
  int merged = 0;
  for (const Series& l : drift) {
    const bool roundoff = !l.y.empty() && *std::max_element(l.y.begin(), l.y.end()) < 1e-13;
    const bool twin = l.title.rfind(methodName(Method::SymplecticEuler), 0) == 0 &&
                      std::any_of(drift.begin(), drift.end(), [&](const Series& o) {
                        return o.title == methodName(Method::ExplicitEuler) + l.title.substr(methodName(Method::SymplecticEuler).size()) &&
                               o.y == l.y;
                      });
    if (roundoff) {
      if (band.x.empty()) band.x = l.x, band.y.assign(l.y.size(), 0.0);
      for (std::size_t i = 0; i < std::min(band.y.size(), l.y.size()); ++i) {
        band.y[i] = std::max(band.y[i], std::max(l.y[i], 1e-17));  // an exact 0 would leave the log axis
      }
      ++merged;
    } else if (!twin) {
      Series kept = l;
      if (l.title.rfind(methodName(Method::ExplicitEuler), 0) == 0) kept.title += " (= symplectic)";
      momentum.add(kept);
    }
  }
  if (merged > 0) momentum.add(band);
  for (const auto& p : momentum.save(options.out + "/lab03_momentum_drift")) written.push_back(p);
}

// Body-frame omega = I_body^-1 R^T L of a quaternion state.
Vec3 omegaBody(const VecX& X) {
  const Mat3 R = orientationOf(X).normalized().toRotationMatrix();
  return kInertia.inverse() * (R.transpose() * X.segment<3>(10));
}

// First flip time (first sign change of body-frame omega_2) of a torque-free spin started at
// body-frame omega0 = (w1, w2, 0) with I1 < I2 < I3: Euler's equations give w2 ~ sn(lambda t + K, k),
// so the sign change comes at t = K(k) / lambda (derivation in the handout, section 7).
double flipTime(const Vec3& I, const Vec3& w) {
  const double twoE = w.dot(I.cwiseProduct(w)), L2 = I.cwiseProduct(w).squaredNorm();
  const double lambda = std::sqrt((I[1] - I[0]) * (twoE * I[2] - L2) / (I[0] * I[1] * I[2]));
  const double k = std::sqrt((I[2] - I[1]) * (L2 - twoE * I[0]) / ((I[1] - I[0]) * (twoE * I[2] - L2)));
  return completeEllipticK(k) / lambda;
}

void dzhanibekovChart(const DemoOptions& options, std::vector<std::string>& written) {
  const RigidBodySystem sys(RigidBody(1.0, kInertia));
  Chart chart("Dzhanibekov effect: I = diag(1, 2, 3), omega_0 = (10^{-3}, 1, 0), RK4 h = 10^{-3}",
              "time [s]", "body-frame angular velocity [rad/s]");
  Series w1{"omega_1", {}, {}, "lines"}, w2{"omega_2 (intermediate axis)", {}, {}, "lines"},
      w3{"omega_3", {}, {}, "lines"};
  attempt("Dzhanibekov", [&] {
    VecX X = sys.makeState(Vec3::Zero(), Quat::Identity(), Vec3::Zero(), kInertia * Vec3(1e-3, 1.0, 0.0));
    Integrator rk4(Method::RK4);
    const double h = 1e-3;
    for (long n = 1; n <= std::lround((options.quick ? 30.0 : 60.0) / h); ++n) {
      rk4.step(sys, X, h);
      if (n % 50 == 0) {
        const Vec3 w = omegaBody(X);
        for (auto [s, value] : {std::pair{&w1, w.x()}, std::pair{&w2, w.y()}, std::pair{&w3, w.z()}}) {
          s->x.push_back(n * h);
          s->y.push_back(value);
        }
      }
    }
  });
  const double t_flip = flipTime(kInertia.diagonal(), Vec3(1e-3, 1.0, 0.0));
  chart.add(w1).add(w2).add(w3).mark({t_flip, "first flip, K(k) / lambda = " + fmt(t_flip, 4) + " s"});
  for (const auto& p : chart.save(options.out + "/lab03_dzhanibekov")) written.push_back(p);
}

void workPrecisionChart(const DemoOptions& options, std::vector<std::string>& written) {
  const RigidBodySystem sys(RigidBody(1.0, kInertia));
  const VecX X0 = sys.makeState(Vec3::Zero(), Quat::Identity(), Vec3::Zero(), kInertia * kOmega0);
  const double T = 5.0;
  VecX reference = X0;
  Integrator rk4(Method::RK4);
  if (!attempt("reference", [&] { for (int n = 0; n < 50000; ++n) rk4.step(sys, reference, T / 50000); })) return;
  Chart chart("Work-precision: torque-free body over 5 s", "wall time [s]", "orientation error [rad]");
  chart.logX().logY();
  for (Method method : {Method::ExplicitEuler, Method::SymplecticEuler, Method::Midpoint, Method::RK4,
                        Method::Verlet}) {
    Series s{methodName(method), {}, {}, "linespoints"};
    attempt(methodName(method), [&] {
      for (int level = 0; level < (options.quick ? 5 : 8); ++level) {
        const long steps = 50L << level;
        VecX X = X0;
        Integrator integrator(method);
        Stopwatch clock;
        for (long n = 0; n < steps; ++n) integrator.step(sys, X, T / steps);
        s.x.push_back(clock.seconds());
        s.y.push_back(orientationOf(X).normalized().angularDistance(orientationOf(reference).normalized()));
      }
    });
    chart.add(s);
  }
  for (const auto& p : chart.save(options.out + "/lab03_work_precision")) written.push_back(p);
}

// The 12 edges of a box of edge lengths `size` at pose (x, R). Two NaN columns follow each edge:
// the animation writes a blank line per NaN column, and in 3D gnuplot joins blocks separated by
// a single blank line into a mesh (drawing face diagonals); two blank lines keep edges apart.
Mat3X boxEdges(const Vec3& x, const Mat3& R, const Vec3& size) {
  Mat3X lines(3, 48);
  Index c = 0;
  for (int axis = 0; axis < 3; ++axis) {
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    for (double su : {-0.5, 0.5}) {
      for (double sv : {-0.5, 0.5}) {
        Vec3 a = Vec3::Zero();
        a[u] = su * size[u];
        a[v] = sv * size[v];
        Vec3 b = a;
        a[axis] = -0.5 * size[axis];
        b[axis] = 0.5 * size[axis];
        lines.col(c++) = x + R * a;
        lines.col(c++) = x + R * b;
        lines.col(c++) = Vec3::Constant(NAN);
        lines.col(c++) = Vec3::Constant(NAN);
      }
    }
  }
  return lines;
}

void tumblingBox(const DemoOptions& options, std::vector<std::string>& written) {
  const Vec3 size(0.4, 1.0, 1.6);
  const RigidBody body(1.0, (1.0 / 12.0) * Vec3(size.y() * size.y() + size.z() * size.z(),
                                                size.x() * size.x() + size.z() * size.z(),
                                                size.x() * size.x() + size.y() * size.y()).asDiagonal());
  const RigidBodySystem sys(body);
  VecX X = sys.makeState(Vec3::Zero(), Quat::Identity(), Vec3::Zero(), body.inertia_body * Vec3(0.05, 3.0, 0.05));
  Animation animation("Box tumbling about its intermediate axis; L (red) stays fixed", Vec3(-1.2, -1.2, -1.2),
                      Vec3(1.2, 1.2, 1.2), true);
  Integrator rk4(Method::RK4);
  const int frames = options.quick ? 30 : 90;
  attempt("tumbling box", [&] {
    for (int f = 0; f < frames; ++f) {
      for (int n = 0; n < 10; ++n) rk4.step(sys, X, 0.01);
      const Mat3 R = orientationOf(X).normalized().toRotationMatrix();
      Mat3X L(3, 2);
      L.col(0).setZero();
      L.col(1) = X.segment<3>(10).normalized();
      animation.addFrame({{boxEdges(X.head<3>(), R, size), "lines lw 2 lc rgb '#3366aa'", "box"},
                          {L, "lines lw 3 lc rgb '#cc2222'", "L / |L|"}},
                         "t = " + fmt((f + 1) * 0.1, 3) + " s");
    }
    written.push_back(animation.save(options.out + "/lab03_tumbling_box.gif", 6));
  });
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const DemoOptions options = parseDemoOptions(
        argc, argv, "Lab 3 demo: orientation drift, the Dzhanibekov flip, work-precision, a tumbling box.");
    std::vector<std::string> written;
    Table table({"integrator", "orientation", "final |E - E0| / E0", "final | |R^T L| - |L0| | / |L0|"});
    driftCharts(options, written, table);
    dzhanibekovChart(options, written);
    workPrecisionChart(options, written);
    tumblingBox(options, written);
    reportDemo("Lab 3", written, table, options.out + "/lab03_summary.md");
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "demo_03_rigid_bodies: " << e.what() << "\n";
    return 1;
  }
}
