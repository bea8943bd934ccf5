#include "search/bordered_form.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "spp/detail/dense_products.hpp"
#include "spp/detail/tridiagonal.hpp"

namespace spp::search {

PhaseFamily::Point PhaseFamily::at(Eigen::Index k, double t) const {
  if (linear(k)) return {t, 1.0, 0.0};
  if (reciprocal(k)) {
    const double a = amp(k);
    return {-a / t, a / (t * t), -2.0 * a / (t * t * t)};
  }
  if (amp(k) == 0.0) return {0.0, 0.0, 0.0};
  const double w = freq(k), tn = std::tan(w * t + shift(k)), sec2 = 1.0 + tn * tn, a = amp(k);
  return {a * tn, a * w * sec2, 2.0 * a * w * w * sec2 * tn};
}

Eigen::VectorXd PhaseFamily::value(double t) const {
  Eigen::VectorXd v(size());
  for (Eigen::Index k = 0; k < size(); ++k) v(k) = at(k, t).v;
  return v;
}

Eigen::VectorXd PhaseFamily::d1(double t) const {
  Eigen::VectorXd v(size());
  for (Eigen::Index k = 0; k < size(); ++k) v(k) = at(k, t).d1;
  return v;
}

PhaseFamily PhaseFamily::of_modes(const Eigen::VectorXd& freqs, PhaseShape shape) {
  const Eigen::Index m = freqs.size();
  PhaseFamily p{Eigen::VectorXd(m), freqs, Eigen::VectorXd::Zero(m), Eigen::Array<bool, Eigen::Dynamic, 1>(m),
                Eigen::Array<bool, Eigen::Dynamic, 1>::Constant(m, false)};
  for (Eigen::Index k = 0; k < m; ++k) {
    const double f = freqs(k);
    const bool over = shape == PhaseShape::TanOverF;
    p.linear(k) = over && f == 0.0;
    p.amp(k) = over ? (f == 0.0 ? 1.0 : 1.0 / f) : f;
  }
  return p;
}

PhaseFamily PhaseFamily::zeros(Eigen::Index size) {
  return {Eigen::VectorXd::Zero(size), Eigen::VectorXd::Zero(size), Eigen::VectorXd::Zero(size),
          Eigen::Array<bool, Eigen::Dynamic, 1>::Constant(size, false),
          Eigen::Array<bool, Eigen::Dynamic, 1>::Constant(size, false)};
}

namespace {
// tan(f t) (t itself for f = 0) has no zero in [lo, hi] (a border -1/phase of a contact phase tan(f t) / f stays
// finite).
bool no_zero_of_tan(double f, double lo, double hi) {
  if (!(f > 0)) return lo > 0;
  return std::floor(f * hi / std::numbers::pi) < f * lo / std::numbers::pi;
}

// Mode of frequency f stays next to one of its poles over [lo, hi]: |tan(f t)| >= 1 at both ends, same sign (tan is
// increasing between poles, and the box holds none, so no zero lies between).
bool next_to_pole(double f, double lo, double hi) {
  if (!(f > 0)) return false;
  const double a = std::tan(f * lo), b = std::tan(f * hi);
  return (a > 0) == (b > 0) && std::min(std::abs(a), std::abs(b)) >= 1.0;
}
}  // namespace

BorderedForm::BorderedForm(const EquationSet& eq, double lo1, double hi1, double lo2, double hi2) : eq_(eq) {
  const ModalForm& md = eq.modal();
  const Eigen::VectorXd& w = md.omega();
  const Eigen::VectorXd& d = md.d();
  // the onset direction -contact_part(t2) z moves with t2: every contact mode bordered (see the header)
  const bool moving = !eq.onset_direction_fixed();
  // a border -1/phase of a phase tan(f t) / f is f tan(f t - pi/2), of f tan(f t) it is tan(f t - pi/2) / f
  const bool over = eq.phase_shape() == PhaseShape::TanOverF;
  m_ = static_cast<int>(w.size());
  for (int i = 0; i < m_; ++i)
    if (next_to_pole(w(i), lo1, hi1)) flight_modes_.push_back(i);
  for (int j = 0; j < static_cast<int>(d.size()); ++j) {
    if (moving && !no_zero_of_tan(d(j), lo2, hi2)) valid_ = false;
    if (moving || next_to_pole(d(j), lo2, hi2)) contact_modes_.push_back(j);
  }
  const int nf = static_cast<int>(flight_modes_.size()), nc = static_cast<int>(contact_modes_.size());
  const int size = m_ + nf + nc;
  const double half_pi = 0.5 * std::numbers::pi;

  // flight phases, one per coordinate: plain modes omega tan(omega t1) (TanOverF: tan(omega t1) / omega); a bordered
  // mode's own coordinate 0 and its border coordinate -1/f = tan(omega t1 - pi/2) / omega (TanOverF: omega tan(omega t1
  // - pi/2)); contact border coordinates 0
  const PhaseFamily plain_f = PhaseFamily::of_modes(w, eq.phase_shape());
  flight_ = PhaseFamily::zeros(size);
  flight_.amp.head(m_) = plain_f.amp;
  flight_.freq.head(m_) = w;
  flight_.linear.head(m_) = plain_f.linear;
  K0_ = Eigen::MatrixXd::Zero(size, size);
  for (int p = 0; p < nf; ++p) {
    const int i = flight_modes_[p], q = m_ + p;
    flight_.amp(i) = 0.0;
    flight_.linear(i) = false;
    flight_.amp(q) = over ? w(i) : 1.0 / w(i);
    flight_.freq(q) = w(i);
    flight_.shift(q) = -half_pi;
    K0_(i, q) = K0_(q, i) = 1.0;
  }
  // contact phases, one per column of Gx: the plain modes' columns of G (padded with zeros), then one border
  // coordinate per bordered mode
  const int plain_c = static_cast<int>(d.size()) - nc;
  Gx_ = Eigen::MatrixXd::Zero(size, plain_c + nc);
  contact_ = PhaseFamily::zeros(plain_c + nc);
  const PhaseFamily plain_c_phase = PhaseFamily::of_modes(d, eq.phase_shape());
  int col = 0;
  for (int j = 0; j < static_cast<int>(d.size()); ++j) {
    if (std::find(contact_modes_.begin(), contact_modes_.end(), j) != contact_modes_.end()) continue;
    Gx_.col(col).head(m_) = md.G().col(j);
    contact_.amp(col) = plain_c_phase.amp(j);
    contact_.freq(col) = d(j);
    contact_.linear(col) = plain_c_phase.linear(j);
    ++col;
  }
  c_ = Eigen::VectorXd::Zero(size);
  if (!moving) c_.head(m_) = md.z().normalized();
  for (int p = 0; p < nc; ++p, ++col) {
    const int j = contact_modes_[p], q = m_ + nf + p;
    Gx_(q, col) = 1.0;
    contact_.freq(col) = d(j);
    if (d(j) > 0) {
      contact_.amp(col) = over ? d(j) : 1.0 / d(j);
      contact_.shift(col) = -half_pi;
    } else {  // the zero frequency of a TanOverF phase (bordered only when the onset moves): phase t2, border -1 / t2
      contact_.amp(col) = 1.0;
      contact_.reciprocal(col) = true;
    }
    K0_.col(q).head(m_) = md.G().col(j);
    K0_.row(q).head(m_) = md.G().col(j).transpose();
    // c(t2)^T b = -sum_j (g_j^T z) tan(d_j t2) / d_j (g_j^T b) = -sum_j (g_j^T z) nu_j
    if (moving) c_(q) = -md.G().col(j).dot(md.z());
  }
  if (moving && c_.norm() > 0) c_.normalize();  // only its sign is used
}

Eigen::MatrixXd BorderedForm::matrix(double t1, double t2) const {
  Eigen::MatrixXd B = K0_ + detail::congruence(Gx_, contact_.value(t2));
  B.diagonal() += flight_.value(t1);
  return B;
}

std::vector<int> BorderedForm::key() const {
  std::vector<int> k = flight_modes_;
  for (const int j : contact_modes_) k.push_back(m_ + j);
  return k;
}

Eigen::VectorXd BorderedForm::border_values(double t1, double t2) const {
  Eigen::VectorXd v(bordered());
  const size_t nf = flight_modes_.size();
  const Eigen::VectorXd f = eq_.flight_part(t1), c = eq_.contact_eigs(t2);
  for (size_t p = 0; p < nf; ++p) v(p) = f(flight_modes_[p]);
  for (size_t p = 0; p < contact_modes_.size(); ++p) v(nf + p) = c(contact_modes_[p]);
  return v;
}

Eigen::VectorXd BorderedForm::extend(const Eigen::VectorXd& b, double t1, double t2) const {
  Eigen::VectorXd x(size());
  x.head(m_) = b;
  const Eigen::VectorXd lam = border_values(t1, t2);
  const size_t nf = flight_modes_.size();
  for (size_t p = 0; p < nf; ++p) x(m_ + p) = lam(p) * b(flight_modes_[p]);
  for (size_t p = 0; p < contact_modes_.size(); ++p)
    x(m_ + nf + p) = lam(nf + p) * eq_.modal().G().col(contact_modes_[p]).dot(b);
  return x;
}

int BorderedForm::positive_border_values(double t1, double t2) const {
  return static_cast<int>((border_values(t1, t2).array() > 0.0).count());
}

BorderedEigen bordered_eigenpair(const BorderedForm& bf, double t1, double t2, int k) {
  BorderedEigen r;
  const Eigen::VectorXd lam = bf.border_values(t1, t2);
  if (!lam.allFinite()) return r;
  const int kb = k + static_cast<int>((lam.array() > 0.0).count());
  // B balanced by the congruence D B D, D = diag(1, ..., 1, c_q ...) (the same inertia, Schur complement and null
  // vectors up to D): border coordinate q of phase a tan(w t - pi/2) scaled by c_q = 1 / a, so that its entry
  // -c_q^2 / phase = tan(w t - pi/2) / a and its coupling c_q g have H's own scale (omega tan, or tan / omega).
  // Unbalanced, scaling K by f scales H' by sqrt(f) and the border block by 1 / sqrt(f): B's error bound eps |B| then
  // swamps the eigenvalue that carries lambda_k(H) (scale invariance lost: chain5 with K x 1e16 left 26 sign changes
  // unpolished).
  const int m = bf.size() - bf.bordered();
  Eigen::VectorXd D = Eigen::VectorXd::Ones(bf.size());
  const auto balance = [](const PhaseFamily& ph, Eigen::Index k) {
    return ph.amp(k) > 0 && !ph.reciprocal(k) && !ph.linear(k) ? 1.0 / ph.amp(k) : 1.0;
  };
  for (int q = m; q < bf.size(); ++q)  // flight border coordinates (the contact ones have the zero phase there)
    if (bf.flight().amp(q) != 0.0) D(q) = balance(bf.flight(), q);
  for (Eigen::Index col = 0; col < bf.contact().size(); ++col)  // contact border columns: a unit entry below m
    for (int q = m; q < bf.size(); ++q)
      if (bf.Gx()(q, col) != 0.0) D(q) = balance(bf.contact(), col);
  const Eigen::MatrixXd Bs = D.asDiagonal() * bf.matrix(t1, t2) * D.asDiagonal();
  const detail::SymmetricTridiagonal T(Bs);
  if (k < 0 || kb >= T.size()) return r;
  r.lam = T.eigenvalue(kb);
  r.scale = T.norm_bound();
  r.error = 8.0 * T.size() * std::numeric_limits<double>::epsilon() * r.scale;
  const Eigen::VectorXd xs = T.eigenvector(r.lam);
  const double head = xs.head(m).norm();
  if (!(head > 0) || !xs.allFinite()) return r;
  r.b = xs.head(m) / head;
  // slopes of D B D along its unit vector xs: those of B along x = D xs
  const Eigen::VectorXd x = D.cwiseProduct(xs);
  const Eigen::VectorXd y = bf.Gx().transpose() * x;
  r.l1 = bf.flight().d1(t1).dot(x.cwiseProduct(x));
  r.l2 = bf.contact().d1(t2).dot(y.cwiseProduct(y));
  r.ok = r.l1 >= 0 && r.l2 >= 0;
  return r;
}

}  // namespace spp::search
