#pragma once
// Every file spp reads or writes (include/spp/io/): systems, results of solve / continue / verify, CSV, Matrix
// Market, atomic writes. The JSON library is private to the implementation (src/io/json.hpp).

#include "spp/io/continuation_file.hpp"
#include "spp/io/csv.hpp"
#include "spp/io/files.hpp"
#include "spp/io/layout_file.hpp"
#include "spp/io/matrix_market.hpp"
#include "spp/io/modes_file.hpp"
#include "spp/io/result_file.hpp"
#include "spp/io/system_file.hpp"
#include "spp/io/verify_file.hpp"
