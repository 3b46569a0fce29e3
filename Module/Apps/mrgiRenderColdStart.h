// mrgi-render --timings --frames N (N > 1): the first frame against the
// later ones, stage by stage, with the process's start before it and the
// textures each frame allocated (Documentation/Multiresolution.md, "Cold
// start"; Testing/Benchmarks/cold_start.py reads it).
#ifndef mrgiRenderColdStart_h
#define mrgiRenderColdStart_h

#include "vtkType.h"

#include <map>
#include <string>
#include <vector>

struct StartTimes
{
  double Window; // seconds from main() to a render window with its GL context
  double Scene;  // seconds to build the scene
  double Setup;  // seconds from main() to the first frame
};

/**
 * Print the cold-start table: per stage (GPU ms, `stageTimes` in
 * `stageOrder`) and for the frame's wall time, the first frame's value and
 * the median of the later frames'; the texture allocations (count and
 * bytes per frame) of the first frame and of all later ones. Nothing with
 * fewer than two frames.
 */
void PrintColdStart(const std::vector<std::string>& stageOrder,
  const std::map<std::string, std::vector<double>>& stageTimes, const std::vector<double>& frameTimes,
  const std::vector<vtkTypeInt64>& allocations, const std::vector<vtkTypeInt64>& bytes,
  const StartTimes& start);

#endif
