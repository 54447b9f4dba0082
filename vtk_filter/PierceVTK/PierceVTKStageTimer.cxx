#include "PierceVTKStageTimer.h"

#include <chrono>
#include <ctime>

namespace pierce_vtk {

namespace {
double Now() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}
// Process CPU time: all threads of the rank.
double CpuNow() { return double(std::clock()) / CLOCKS_PER_SEC; }
}  // namespace

StageTimer::StageTimer() : Wall(Now()), Cpu(CpuNow()) {}

void StageTimer::Stage(const std::string& name) {
  const double wall = Now(), cpu = CpuNow();
  this->Done.push_back({name, wall - this->Wall, cpu - this->Cpu});
  this->Wall = wall;
  this->Cpu = cpu;
}

}  // namespace pierce_vtk
