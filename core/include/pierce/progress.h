#pragma once
// Progress reporting shared by batch tracing and the analyses: called from worker threads with the number of
// work items finished so far and the total; returning false cancels the analysis, which then
// returns early with `completed == false` in its result.
#include <cstddef>
#include <functional>

namespace pierce {

using Progress = std::function<bool(std::size_t done, std::size_t total)>;

}  // namespace pierce
