#pragma once
// Matrix Market input (M and K exported from MATLAB, scipy or a finite-element code) and output (sparse models).
// Cost: linear in the file's size; a dense read holds n^2 doubles (8 n^2 bytes), a sparse one its non-zeros.

#include <Eigen/Dense>
#include <Eigen/SparseCore>
#include <string>

namespace spp {

/// "matrix array|coordinate real|integer general|symmetric", held densely (at most 4e8 entries). Coordinate
/// duplicates are summed (the format's convention, as scipy.io.mmread); a symmetric file stores one triangle (an
/// entry given in both is refused); more or fewer entries than the size line declares, and tokens that are not whole
/// numbers ("1.5xyz"), are refused. Throws std::invalid_argument naming the file and line.
/// expected_size >= 0: as for read_sparse_matrix_market below (checked on the size line, before the n^2 allocation).
Eigen::MatrixXd read_matrix_market(const std::string& path, long expected_size = -1);

/// The same file held sparse (any size; a symmetric file is expanded to both triangles; stored zeros dropped).
/// expected_size >= 0: the file must declare expected_size x expected_size, checked on its size line, before anything
/// of that size is allocated (a 1 kB file declaring 1e8 x 1e8 took 3.9 GB before its entries were found wanting).
Eigen::SparseMatrix<double> read_sparse_matrix_market(const std::string& path, long expected_size = -1);

/// "coordinate real symmetric" (the lower triangle of A, A assumed symmetric) or "general" text of A, 17 digits (reads
/// back bit for bit); `comment` (one line, may be empty) goes after the banner.
std::string matrix_market_text(const Eigen::SparseMatrix<double>& A, bool symmetric, const std::string& comment = "");

}  // namespace spp
