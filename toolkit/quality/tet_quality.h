// Element quality measures of tetrahedra (notes §1.2 and §3.1: circumradius-to-shortest-
// edge ratio; §4.4: dihedral angles and slivers), and a mesh-wide quality report with the
// histograms printed by the CLI and written to --stats files.
//
// These are measurements for reporting and for ordering refinement queues, computed in
// floating point; no topological or validity decision is made from them (those use
// toolkit/predicates).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "toolkit/geometry/vec3.h"
#include "toolkit/mesh3d/tetra_mesh.h"

namespace delmesh {

/// det[b-a, c-a, d-a] / 6: positive for delmesh's orientation.
double signed_volume(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);
/// Radius of the circumscribed sphere. Where the double determinant of a nearly flat tet
/// rounds to zero or the radius overflows, recomputed in long double; infinity for a tet
/// flat to that precision as well.
double circumradius(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);
/// Length of the shortest of the six edges.
double shortest_edge(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);
/// Circumradius over shortest edge: sqrt(6)/4 ~ 0.612 for the regular tet.
double radius_edge_ratio(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);
/// The six interior dihedral angles in degrees, at edges ab, ac, ad, bc, bd, cd.
std::array<double, 6> dihedral_angles_deg(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);
/// The smallest and largest of dihedral_angles_deg(a, b, c, d), bit for bit, with two
/// arc cosines instead of six (the arc cosine decreases: the smallest angle has the
/// largest cosine). The quality report and the .vtu writer run it on every tet.
std::pair<double, double> dihedral_extremes_deg(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);

/// The smallest sine of the six dihedral angles: 6V * |e| / (|n1| |n2|) at each edge e
/// between faces of normals n1, n2 (sin = 3 V |e| / (2 A1 A2)). Small for angles near 0
/// and near 180 degrees alike (slivers, caps, needles), negative for inverted tets; the
/// objective of mesh improvement (notes §2.2.4, Freitag and Ollivier-Gooch).
double min_dihedral_sine(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);

/// The sines of the six dihedral angles (at edges ab, ac, ad, bc, bd, cd), those of the
/// obtuse angles multiplied by `obtuse_scale`: with obtuse_scale = window_obtuse_scale(low,
/// high) an angle at either end of the window [low, high] scores sin(low), so the smallest
/// value ranks tets by how far they reach out of the window on either side (the plain
/// sine ranks an angle of 150 degrees with one of 30). A degenerate face gives 0.
std::array<double, 6> window_dihedral_sines(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d,
                                            double obtuse_scale);
/// The smallest of window_dihedral_sines(a, b, c, d, obtuse_scale), negative (the signed
/// volume term) for flat and inverted tets; min_dihedral_sine itself, bit for bit, when
/// obtuse_scale is 1.
double min_window_dihedral_sine(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, double obtuse_scale);
/// sin(low) / sin(180 - high) for a window with both ends (0 < low, high < 180), else 1.
double window_obtuse_scale(double low_deg, double high_deg);

/// Does the tet have a dihedral angle below low_deg or above high_deg?
bool dihedral_outside(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, double low_deg,
                      double high_deg);

struct TetQualityReport {
  std::size_t tets = 0;
  double total_volume = 0.0;
  double min_volume = 0.0;
  double min_dihedral_deg = 0.0;
  double max_dihedral_deg = 0.0;
  /// Largest and mean radius-edge ratio over the tets whose ratio is finite.
  double max_radius_edge = 0.0;
  double mean_radius_edge = 0.0;
  /// Tets whose radius-edge ratio is infinite (flat to long double precision: see
  /// circumradius): left out of the max and mean, counted in the last histogram bin and
  /// above every bound.
  std::size_t flat_ratio_tets = 0;
  /// Radius-edge histogram: bin upper bounds, and counts (last bin is everything above).
  std::vector<double> radius_edge_bounds{0.7, 0.8, 0.9, 1.0, 1.1, 1.2, 1.414, 2.0, 4.0};
  std::vector<std::size_t> radius_edge_counts;
  /// Minimum-dihedral histogram in 10-degree bins [0,10), [10,20), ... [60,70.53].
  std::array<std::size_t, 8> min_dihedral_counts{};
  /// Maximum-dihedral histogram in 10-degree bins [70.53,80), [80,90), ... [170,180].
  std::array<std::size_t, 11> max_dihedral_counts{};
  /// Tets with a dihedral angle outside [low, high] (the `dihedral_window` given).
  std::size_t outside_dihedral_window = 0;
  /// Tets whose radius-edge ratio exceeds the given bound.
  std::size_t above_radius_edge = 0;
};

/// Quality of every tet of `mesh`. `radius_edge_bound` and the dihedral window feed the
/// two counters above.
TetQualityReport tet_quality_report(const TetraMesh& mesh, double radius_edge_bound = 2.0,
                                    double dihedral_low_deg = 0.0, double dihedral_high_deg = 180.0);

/// The same over the tets i with (selection[i] != 0) == selected only (selection has one
/// entry per tet, e.g. MeshResult::tet_at_small_angle; missing entries count as 0).
TetQualityReport tet_quality_report(const TetraMesh& mesh, const std::vector<std::uint8_t>& selection, bool selected,
                                    double radius_edge_bound = 2.0, double dihedral_low_deg = 0.0,
                                    double dihedral_high_deg = 180.0);

/// The three reports of one mesh that the CLI prints: over every tet, over the selected
/// tets and over the others.
struct TetQualitySplit {
  TetQualityReport all, selected, unselected;
};

/// tet_quality_report(mesh, ...), tet_quality_report(mesh, selection, true, ...) and
/// tet_quality_report(mesh, selection, false, ...), equal to them field for field, from
/// one pass that measures each tet once.
TetQualitySplit tet_quality_split(const TetraMesh& mesh, const std::vector<std::uint8_t>& selection,
                                  double radius_edge_bound = 2.0, double dihedral_low_deg = 0.0,
                                  double dihedral_high_deg = 180.0);

/// Is the tet outside the dihedral window [low_deg, high_deg] as tet_quality_report
/// counts it (angles from dihedral_angles_deg; a NaN angle counts as outside)? Decided on
/// the extremes of dihedral_extremes_deg, two arc cosines instead of six.
bool outside_dihedral_window(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, double low_deg,
                             double high_deg);

}  // namespace delmesh
