#include "search/polish.hpp"

#include <algorithm>
#include <cmath>

#include "search/tolerances.hpp"

namespace spp::search {

using Vec = Eigen::VectorXd;
using Mat = Eigen::MatrixXd;

double residual_of(const EquationSet& eq, double t1, double t2, const Vec& a) {
  const ModalForm& md = eq.modal();
  const Mat N = eq.N(t1, t2);
  const Vec p0 = eq.onset_position(t1, a);
  const double r1 = (N * a).norm() / (N.norm() * a.norm());
  const double r2 = std::abs(md.z().dot(p0)) / (md.z().norm() * std::max(p0.norm(), 1e-300));
  return std::max(r1, r2);
}

void spp_equations(const EquationSet& eq, double t1, double t2, const Vec& a, Vec& F, Mat& J) {
  const ModalForm& md = eq.modal();
  const int m = md.m();
  const Mat N = eq.N(t1, t2);
  F.resize(m + 1);
  F.head(m) = N * a;
  F(m) = md.z().dot(eq.onset_position(t1, a));
  J = Mat::Zero(m + 1, m + 2);
  J.block(0, 0, m, 1) = eq.dN_dt1(t1, t2) * a;
  J.block(0, 1, m, 1) = eq.dN_dt2(t1, t2) * a;
  J.block(0, 2, m, m) = N;
  J(m, 0) = md.z().dot(eq.onset_position_dt1(t1, a));
  J.block(m, 2, 1, m) = eq.onset_position(t1, md.z()).transpose();  // a diagonal map: its row is z's image
}

// Starting vector: a = p0 ./ cos(W t1) from the traced null vector p0 of H when the cosines are not small
// (near the axis t1 = 0, N has two small singular values and its SVD may pick the wrong one), else the SVD.
Polished polish(const EquationSet& eq, double t1, double t2, const Vec& b) {
  const ModalForm& md = eq.modal();
  const int m = md.m();
  Polished out;
  Vec a;
  const Eigen::ArrayXd c1 = (md.omega().array() * t1).cos();
  if (b.size() == m && c1.abs().minCoeff() > kPolishCosFloor) {
    a = (b.array() / c1).matrix().normalized();
  } else {
    Eigen::JacobiSVD<Mat> svd(eq.N(t1, t2), Eigen::ComputeFullV);
    a = svd.matrixV().col(m - 1);
  }
  const Vec aref = a;
  const double t1_start = t1, t2_start = t2;
  double best = residual_of(eq, t1, t2, a);
  out = {false, t1, t2, best, a};
  for (int it = 0; it < kPolishIterations; ++it) {
    Vec F(m + 2), Fs;
    Mat J = Mat::Zero(m + 2, m + 2), Js;
    spp_equations(eq, t1, t2, a, Fs, Js);
    F.head(m + 1) = Fs;
    F(m + 1) = aref.dot(a) - 1.0;
    J.topRows(m + 1) = Js;
    J.block(m + 1, 2, 1, m) = aref.transpose();
    Vec dx = J.fullPivLu().solve(-F);
    // trust region: stay near the candidate (the limit points on the axes attract Newton) and keep t1 > 0
    double alpha = 1.0;
    while (alpha > kPolishMinAlpha && (t1 + alpha * dx(0) < 0.5 * t1 || t2 + alpha * dx(1) < 0.5 * t2 ||
                                       std::hypot(t1 + alpha * dx(0) - t1_start, t2 + alpha * dx(1) - t2_start) >
                                           kPolishReach * (t1_start + t2_start)))
      alpha *= 0.5;
    dx *= alpha;
    t1 += dx(0);
    t2 += dx(1);
    a += dx.tail(m);
    const double res = residual_of(eq, t1, t2, a);
    if (res < best) {
      best = res;
      out = {false, t1, t2, res, a};
    }
    if (dx.head(2).norm() <= kPolishStep * (std::abs(t1) + std::abs(t2))) break;
  }
  out.converged = best < kConvergedResidual;
  return out;
}

}  // namespace spp::search
