#pragma once
// Matrix Market input (M and K exported from MATLAB, scipy or a finite-element code).

#include <Eigen/Dense>
#include <string>

namespace spp {

/// "matrix array|coordinate real|integer general|symmetric", held densely (at most 4e8 entries). Coordinate
/// duplicates are summed (the format's convention, as scipy.io.mmread); a symmetric file stores one triangle (an
/// entry given in both is refused); more or fewer entries than the size line declares, and tokens that are not whole
/// numbers ("1.5xyz"), are refused. Throws std::invalid_argument naming the file and line.
Eigen::MatrixXd read_matrix_market(const std::string& path);

}  // namespace spp
