#pragma once
// The front end's settings as rows (core/param_rows.hpp): every option of `extract` and of `loop`
// that shapes features and matches is declared here once, so both commands offer the same names
// and ranges (their defaults differ: loop_extract_defaults()).
#include <vector>

#include "core/param_rows.hpp"
#include "frontend/extract.hpp"

namespace verifybench {

/// Pipeline choice, each pipeline's scale settings (voxel, ISS, SHOT, bird's-eye view, ORB, FPFH)
/// and the matcher's, in --help order.
const std::vector<ParamRow<ExtractParams>>& frontend_param_rows();

}  // namespace verifybench
