#pragma once
// The dense check (acceptance/dense_check.hpp) on a dump's rows: where `extract --keep-clouds`
// kept the two clouds, every pair the accept rule accepted is refined by ICP from its motion and
// kept only when the clouds overlap by more than the threshold in force. The same check the loop
// runs on its local maps. Built with the front end.
#include <vector>

#include "acceptance/dense_check.hpp"
#include "datasets/dump_clouds.hpp"
#include "reports/record.hpp"

namespace verifybench {

/// Rows of one dump: each accepted row with a motion (2D: lifted to 3D about z) gets the check's
/// figures (TrialRecord::dense_*); below the threshold it is rejected with a message, and its
/// success (when the criteria require acceptance) becomes false. Other rows are left as they are.
void dense_check_rows(std::vector<TrialRecord>& rows, const DumpClouds& clouds,
                      const DenseCheckParams& params, AcceptParams::Rule rule,
                      const SuccessCriteria& criteria);

}  // namespace verifybench
