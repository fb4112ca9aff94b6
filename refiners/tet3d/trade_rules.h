// The limits the polish's trades are judged by (sliver_improvement.h, step 5 "trades at
// held tets"; notes §4.4 and §2.2.4): the dihedral window, the extreme angles of the tets
// touching a small input angle when the trades started, the share of the least window
// sine those tets keep, the least gain, which vertices touch a small angle and the bound
// test. Shared by the joint moves (joint_move.h) and the flip trades (flip_trade.h).
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "toolkit/geometry/vec3.h"

namespace delmesh::tet3d {

struct TradeRules {
  double low_deg = 0.0, high_deg = 180.0;
  double obtuse_scale = 1.0;  ///< window_obtuse_scale of the window (toolkit/quality)
  /// The extreme dihedral angles of the tets touching a small angle when the trades started.
  double trade_min_deg = 0.0, trade_max_deg = 180.0;
  double trade_fraction = 0.5;
  double min_gain = 1e-4;
  /// Per vertex id, nonzero where it touches a small input angle (small_angles.h); ids
  /// beyond it touch none.
  const std::vector<std::uint8_t>* at_small_angle = nullptr;
  /// Does a tet of the region break a radius-edge or volume bound?
  std::function<bool(int, const Vec3&, const Vec3&, const Vec3&, const Vec3&)> breaks_bounds;
};

}  // namespace delmesh::tet3d
