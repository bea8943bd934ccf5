#include "spp/core/parametric.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "spp/core/names.hpp"
#include "spp/detail/invalid.hpp"

namespace spp {

namespace {
template <typename A>
A zero_if_empty(A part, const A& like, const std::string& label) {
  if (part.size() == 0) return A::Zero(like.rows(), like.cols());
  if (part.rows() != like.rows() || part.cols() != like.cols()) {
    std::ostringstream os;
    os << "parametric system: " << label << " is " << part.rows() << " x " << part.cols() << ", the constant part "
       << like.rows() << " x " << like.cols();
    detail::invalid(os.str());
  }
  return part;
}
}  // namespace

ParametricSystem::ParametricSystem(Eigen::MatrixXd M_constant, Eigen::MatrixXd M_mu, Eigen::MatrixXd K_constant,
                                   Eigen::MatrixXd K_mu, Eigen::VectorXd w_constant, Eigen::VectorXd w_mu, double g0,
                                   Parameter parameter, std::string name)
    : M0_(std::move(M_constant)),
      K0_(std::move(K_constant)),
      w0_(std::move(w_constant)),
      g0_(g0),
      parameter_(std::move(parameter)),
      name_(std::move(name)) {
  const std::string& p = parameter_.name;
  if (p.empty()) detail::invalid("parametric system: the parameter needs a name: expected one, got the empty string");
  // (the parameter's name is a key of M, K and w in a file and a column title)
  check_name(p, "parametric system: parameter name");
  check_name(name_, "parametric system: name");
  if (!(std::isfinite(parameter_.min) && std::isfinite(parameter_.max) && parameter_.min < parameter_.max)) {
    std::ostringstream os;
    os << "parametric system: parameter \"" << p << "\" needs finite min < max, got min = " << parameter_.min
       << ", max = " << parameter_.max;
    detail::invalid(os.str());
  }
  M1_ = zero_if_empty(std::move(M_mu), M0_, "M's \"" + p + "\" part");
  K1_ = zero_if_empty(std::move(K_mu), K0_, "K's \"" + p + "\" part");
  w1_ = zero_if_empty(std::move(w_mu), w0_, "w's \"" + p + "\" part");
  if (M1_.isZero(0.0) && K1_.isZero(0.0) && w1_.isZero(0.0))
    detail::invalid(
        "parametric system: parameter \"" + p +
        "\" is declared but M, K and w do not depend on it: expected a non-zero part of M, K or w in it, got "
        "only zero parts");
  // Every check of System (sizes, symmetry, SPD, w != 0) at both ends of the range.
  at(parameter_.min);
  at(parameter_.max);
}

System ParametricSystem::at(double mu) const {
  if (!std::isfinite(mu)) {  // (M(nan) was refused as "M[0][0] must be finite, got nan": the value was the fault)
    std::ostringstream os;
    os << "parametric system: the parameter " << parameter_.name << " must be a finite number, got " << mu;
    detail::invalid(os.str());
  }
  try {
    return System(M0_ + mu * M1_, K0_ + mu * K1_, w0_ + mu * w1_, g0_, name_);
  } catch (const std::invalid_argument& e) {
    std::ostringstream os;
    os << "parametric system at " << parameter_.name << " = " << mu << ": " << e.what();
    detail::invalid(os.str());
  }
}

}  // namespace spp
