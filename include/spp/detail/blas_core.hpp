#pragma once
// Which OpenBLAS kernels a process should ask for (src/detail/dense_products.cpp, next to the other OpenBLAS calls).

namespace spp::detail {

/// The OpenBLAS kernel set a process should ask for through the environment variable OPENBLAS_CORETYPE: "SkylakeX"
/// (AVX-512F) or "Haswell" (AVX2) where the loaded OpenBLAS runs its generic SSE3 kernels ("Prescott", its fallback
/// for a CPU model it does not know: OpenBLAS 0.3.21 on Intel family 6 model 207, this project's machine, where the
/// SkylakeX kernels halve the CPU time of a 300-dof certified window); empty otherwise, when OPENBLAS_CORETYPE is set,
/// or with another BLAS. OpenBLAS reads the variable once, when it is loaded: build/spp re-executes itself with it.
const char* blas_core_advice();

}  // namespace spp::detail
