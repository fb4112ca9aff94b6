// The default improvement run (see default_improvement.h).
#include "refiners/tet3d/default_improvement.h"

namespace delmesh::tet3d {

ImprovementTarget default_improvement_target() {
  ImprovementTarget target;
  target.min_dihedral_deg = kDefaultMinDihedralDeg;
  target.max_dihedral_deg = 180.0;
  target.strict_bounds = true;
  target.small_angle_holds = false;
  target.max_passes = kDefaultMaxPasses;
  target.tries_per_bad_tet = kDefaultTriesPerBadTet;
  return target;
}

ImprovementStats improve_default(RefineState& state) { return improve_slivers(state, default_improvement_target()); }

}  // namespace delmesh::tet3d
