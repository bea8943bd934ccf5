#include "spp/search/root_map.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

#include "search/tolerances.hpp"
#include "spp/detail/invalid.hpp"
#include "spp/detail/symmetric_eigen.hpp"
#include "spp/modal/equation_set.hpp"
#include "spp/modal/modal.hpp"

namespace spp {

void RootMapOptions::validate() const {
  constexpr const char* where = "root map options";
  if (!(t1_min >= 0.0) || !std::isfinite(t1_min)) detail::invalid_option(where, "t1_min", t1_min, ">= 0 and finite");
  if (!(t2_min >= 0.0) || !std::isfinite(t2_min)) detail::invalid_option(where, "t2_min", t2_min, ">= 0 and finite");
  if (!(t1_max > t1_min) || !std::isfinite(t1_max))
    detail::invalid_option(where, "t1_max", t1_max, "> t1_min and finite");
  if (!(t2_max > t2_min) || !std::isfinite(t2_max))
    detail::invalid_option(where, "t2_max", t2_max, "> t2_min and finite");
  if (t1_points < 16 || t1_points > 100000) detail::invalid_option(where, "t1_points", t1_points, "in [16, 100000]");
  if (t2_points < 16 || t2_points > 100000) detail::invalid_option(where, "t2_points", t2_points, "in [16, 100000]");
  if (min_cell_points < 2 || min_cell_points > 10000)
    detail::invalid_option(where, "min_cell_points", min_cell_points, "in [2, 10000]");
  if (!(pole_margin >= 0.0 && pole_margin < 0.25))
    detail::invalid_option(where, "pole_margin", pole_margin, "in [0, 0.25)");
}

std::string RootMapProgress::line() const {
  std::ostringstream os;
  os << "cells " << cells_done << " / " << cells_total;
  if (cells_total > 0) os << " (" << 100 * cells_done / cells_total << "%)";
  os << ", " << evaluations << " points, " << std::fixed;
  os.precision(1);
  os << seconds << " s";
  if (cells_done > 0 && cells_done < cells_total)
    os << ", ~" << std::max(1.0, std::round(seconds / cells_done * (cells_total - cells_done))) << " s left";
  return os.str();
}

namespace {

/// sign(det A) * min |lambda(A)| of a symmetric matrix (0 for an empty one is never used: m >= 1 here).
double signed_min_eigenvalue(const Eigen::MatrixXd& A) {
  if (A.rows() == 0) return 1.0;
  const detail::SymmetricEigen es = detail::symmetric_eigen(A, /*vectors=*/false);
  const Eigen::VectorXd& lam = es.values;
  int negatives = 0;
  double smallest = std::abs(lam(0));
  for (Eigen::Index k = 0; k < lam.size(); ++k) {
    negatives += lam(k) < 0.0;
    smallest = std::min(smallest, std::abs(lam(k)));
  }
  return negatives % 2 ? -smallest : smallest;
}

/// Cells of [lo, hi] cut by the poles: (begin, end) pairs.
std::vector<std::pair<double, double>> cells_between(double lo, double hi, const std::vector<double>& poles) {
  std::vector<std::pair<double, double>> out;
  double a = lo;
  for (double p : poles) {
    if (p > a) out.emplace_back(a, p);
    a = std::max(a, p);
  }
  if (hi > a) out.emplace_back(a, hi);
  return out;
}

/// The sampled part of a cell [a, b]: off its pole lines by pole_margin of its width.
std::pair<double, double> sampled_part(double a, double b, bool pole_at_a, bool pole_at_b, const RootMapOptions& o) {
  const double margin = o.pole_margin * (b - a);
  return {pole_at_a ? a + margin : a, pole_at_b ? b - margin : b};
}

int points_in(double length, double step, int min_points) {
  return std::max(min_points, static_cast<int>(std::min(std::ceil(length / step), 1e6)) + 1);
}

/// The grid step along one axis: the points of all its cells (each at least min_points, the others in proportion to
/// the cell's length) sum to about `points`, so that the whole map has about t1_points x t2_points, spread over the
/// cells in proportion to their area. (Each cell used to take its own ceil(length / step) + 1 >= min_cell_points
/// with step = window / (points - 1): a 20-dof chain's fundamental box, 51 339 cells mostly narrower than a step,
/// took 1 959 105 points for 400 x 400 asked, 12x; found by an attack on issue 13.) When the cells alone need more
/// than `points` at min_points each, every cell has min_points.
double axis_step(const std::vector<double>& lengths, int points, int min_points) {
  double total = 0.0;
  for (double l : lengths) total += l;
  auto count = [&](double step) {
    long n = 0;
    for (double l : lengths) n += points_in(l, step, min_points);
    return n;
  };
  double lo = total / (points - 1) / 2.0, hi = 2.0 * total;  // count(lo) > points when any cell is sampled by step
  if (count(hi) >= points) return hi;                        // min_points everywhere
  for (int k = 0; k < 100 && hi - lo > 1e-15 * hi; ++k) {    // the smallest step whose count is at most points
    const double mid = 0.5 * (lo + hi);
    (count(mid) <= points ? hi : lo) = mid;
  }
  return hi;
}

Eigen::VectorXd cell_grid(double lo, double hi, const RootMapOptions& o, double step) {
  Eigen::VectorXd t = Eigen::VectorXd::LinSpaced(points_in(hi - lo, step, o.min_cell_points), lo, hi);
  // Lower ends at 0 are the trivial line t1 = 0 (H singular for every t2) or pure flight: step off them.
  if (t(0) == 0.0) t(0) = search::kOffAxis * (t(1) - t(0));
  return t;
}

}  // namespace

RootMap root_map(const System& system, const RootMapOptions& options) {
  options.validate();
  return root_map(ModalForm(system), options);
}

RootMap root_map(const ModalForm& modal, const RootMapOptions& options) {
  options.validate();
  const std::unique_ptr<EquationSet> eq = make_equations(modal, Symmetry::Axial);  // eqs. (5.1a-b)
  RootMap map;
  map.flight_poles = modal.flight_poles(options.t1_min, options.t1_max);
  map.contact_poles = modal.contact_poles(options.t2_min, options.t2_max);

  // P: orthonormal basis of z-perp (the last m-1 columns of a Householder Q of z).
  const int m = modal.m();
  Eigen::MatrixXd P(m, std::max(0, m - 1));
  if (m > 1) {
    Eigen::HouseholderQR<Eigen::MatrixXd> qr(modal.z());
    P = qr.householderQ() * Eigen::MatrixXd::Identity(m, m).rightCols(m - 1);
  }

  auto is_pole = [](const std::vector<double>& poles, double t) {
    return std::find(poles.begin(), poles.end(), t) != poles.end();
  };
  // each cell's sampled part, and the step that spreads about t1_points x t2_points over them
  auto parts = [&](const std::vector<double>& poles, double lo, double hi) {
    std::vector<std::pair<double, double>> out;
    for (const auto& [a, b] : cells_between(lo, hi, poles))
      out.push_back(sampled_part(a, b, is_pole(poles, a), is_pole(poles, b), options));
    return out;
  };
  const auto cols = parts(map.flight_poles, options.t1_min, options.t1_max);
  const auto rows = parts(map.contact_poles, options.t2_min, options.t2_max);
  auto lengths = [](const std::vector<std::pair<double, double>>& cells) {
    std::vector<double> out;
    for (const auto& [a, b] : cells) out.push_back(b - a);
    return out;
  };
  const double step1 = axis_step(lengths(cols), options.t1_points, options.min_cell_points);
  const double step2 = axis_step(lengths(rows), options.t2_points, options.min_cell_points);
  // Progress: reported between rows, about every 0.2 s, and once at the end; a false answer stops the map there (the
  // cell being sampled is dropped, the cells done are kept).
  using Clock = std::chrono::steady_clock;
  const Clock::time_point start = Clock::now();
  Clock::time_point last_report = start;
  const long cells_total = static_cast<long>(rows.size() * cols.size());
  auto report = [&](long evaluations) {
    RootMapProgress p;
    p.cells_done = static_cast<long>(map.cells.size());
    p.cells_total = cells_total;
    p.evaluations = evaluations;
    p.seconds = std::chrono::duration<double>(Clock::now() - start).count();
    last_report = Clock::now();
    return options.progress(p);
  };
  constexpr std::chrono::milliseconds kReportEvery{200};
  for (const auto& [b2, e2] : rows) {
    const Eigen::VectorXd t2 = cell_grid(b2, e2, options, step2);
    for (const auto& [b1, e1] : cols) {
      RootMapCell cell;
      cell.t1 = cell_grid(b1, e1, options, step1);
      cell.t2 = t2;
      cell.symmetric.resize(t2.size(), cell.t1.size());
      cell.onset.resize(t2.size(), cell.t1.size());
      for (Eigen::Index i = 0; i < t2.size(); ++i) {
        if (options.progress && Clock::now() - last_report >= kReportEvery &&
            !report(map.evaluations + i * cell.t1.size())) {
          map.unsampled_cells = cells_total - static_cast<long>(map.cells.size());
          return map;
        }
        const Eigen::MatrixXd C = eq->contact_part(t2(i));
        for (Eigen::Index j = 0; j < cell.t1.size(); ++j) {
          Eigen::MatrixXd H = C;
          H.diagonal() += eq->flight_part(cell.t1(j));
          cell.symmetric(i, j) = signed_min_eigenvalue(H);
          cell.onset(i, j) = signed_min_eigenvalue(P.transpose() * H * P);
        }
      }
      map.evaluations += t2.size() * cell.t1.size();
      map.cells.push_back(std::move(cell));
    }
  }
  if (options.progress) report(map.evaluations);  // the end: its answer changes nothing
  return map;
}

}  // namespace spp
