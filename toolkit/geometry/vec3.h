// The 3D point type of delmesh. Coordinates are stored as read, bit for bit; every sign
// decision goes through toolkit/predicates on these values (pass `p.data()`).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>  // cross products

namespace delmesh {

using Vec3 = Eigen::Vector3d;

}  // namespace delmesh
