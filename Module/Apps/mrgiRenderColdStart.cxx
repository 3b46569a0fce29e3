#include "mrgiRenderColdStart.h"

#include <algorithm>
#include <cstdio>

//------------------------------------------------------------------------------
void PrintColdStart(const std::vector<std::string>& stageOrder,
  const std::map<std::string, std::vector<double>>& stageTimes, const std::vector<double>& frameTimes,
  const std::vector<vtkTypeInt64>& allocations, const std::vector<vtkTypeInt64>& bytes,
  const StartTimes& start)
{
  if (frameTimes.size() < 2)
  {
    return;
  }
  auto rest = [](const std::vector<double>& v) {
    std::vector<double> later(v.begin() + 1, v.end());
    std::sort(later.begin(), later.end());
    const size_t n = later.size();
    return n % 2 ? later[n / 2] : 0.5 * (later[n / 2 - 1] + later[n / 2]);
  };
  std::printf("%-24s %12s %12s\n", "cold start", "first ms", "steady ms");
  std::printf("  %-22s %12.1f\n", "start to window", start.Window * 1e3);
  std::printf("  %-22s %12.1f\n", "scene build", start.Scene * 1e3);
  std::printf("  %-22s %12.1f\n", "start to first frame", start.Setup * 1e3);
  for (const std::string& name : stageOrder)
  {
    const std::vector<double>& t = stageTimes.at(name);
    if (t.size() == frameTimes.size())
    {
      std::printf("  %-22s %12.3f %12.3f\n", name.c_str(), t[0], rest(t));
    }
  }
  std::printf("  %-22s %12.3f %12.3f\n", "frame (wall)", frameTimes[0], rest(frameTimes));
  vtkTypeInt64 laterCount = 0, laterBytes = 0;
  for (size_t f = 1; f < allocations.size(); ++f)
  {
    laterCount += allocations[f];
    laterBytes += bytes[f];
  }
  std::printf("textures allocated: first frame %lld (%.1f MiB), later frames %lld (%.1f MiB)\n",
    static_cast<long long>(allocations[0]), static_cast<double>(bytes[0]) / 1048576.0,
    static_cast<long long>(laterCount), static_cast<double>(laterBytes) / 1048576.0);
}
