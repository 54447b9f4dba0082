#pragma once
// Stage times of one filter run, for the run report of PierceVTKDistributed.h and the MPI bench.
#include <string>
#include <vector>

namespace pierce_vtk {

// Wall-clock and CPU time (of the whole process, all threads) of the stages of one filter run
// (gather, BVH build, trace...).
class StageTimer {
public:
  struct Times {
    std::string name;
    double wall, cpu;  // seconds
  };
  StageTimer();
  // Ends the current stage, named `name`, and starts the next.
  void Stage(const std::string& name);
  const std::vector<Times>& Stages() const { return this->Done; }

private:
  std::vector<Times> Done;
  double Wall, Cpu;
};

}  // namespace pierce_vtk
