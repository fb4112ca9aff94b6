// Surface meshes (STL, OFF, OBJ, PLY) to validated PLCs (notes §2.1.4).
//
// Pipeline, each step explicit and reported:
//   1. parse into a polygon soup, coordinates exactly as stored (surface_soup.h);
//   2. weld vertices: exactly coincident ones by default; with weld_tolerance > 0, every
//      pair closer than the tolerance (transitively), each cluster taking the coordinates
//      of its lowest-numbered vertex;
//   3. documented repairs, each unambiguous: faces that collapse to fewer than three
//      distinct vertices are dropped; exact duplicate faces (same vertex set) are dropped,
//      keeping the first; zero-area faces (collinear vertices) are dropped only when every
//      edge they touch still lies on exactly two faces afterwards;
//   4. topology: an edge on one face (open surface) or on three or more (non-manifold)
//      refuses the input, listing the edges and their faces with coordinates;
//   5. orientation: faces are made consistent across every edge (breadth-first per
//      connected shell); then each shell is turned so that its signed volume is positive
//      (outward normals); a shell that cannot be oriented is refused;
//   6. coplanar merge (merge_coplanar): edge-adjacent faces of one shell whose vertices
//      are exactly coplanar (orient3d) and that are not folded onto each other are merged
//      into one polygonal facet when the union is bounded by simple loops (one outer
//      loop, holes with a hole point found from an exactly verified ear of the hole
//      loop); otherwise the faces stay as they are. Then the exact intersection check of
//      the facets (validate_plc): offending pairs are listed with the coordinates of
//      their faces;
//   7. shells: exact ray-parity containment decides nesting; a shell inside an odd number
//      of others bounds a cavity, which becomes a volume hole (NestedShells::Holes) or a
//      region of its own (NestedShells::Regions); every material region gets a region
//      point (id 1, 2, ... in shell order) found by exact point-in-shell tests;
//   8. vertices used by no facet (interior to merged facets) are removed.
// Facet markers are the shell number (1, 2, ...).
#pragma once

#include <cstdint>
#include <filesystem>
#include <string_view>

#include "importers/surface/surface_soup.h"
#include "toolkit/core/error.h"
#include "toolkit/core/log.h"
#include "toolkit/plc/plc.h"

namespace delmesh {

enum class NestedShells : std::uint8_t {
  Holes,    ///< a cavity (shell inside an odd number of others) is a volume hole
  Regions,  ///< every shell's inside is a region of its own
};

struct SurfaceImportOptions {
  /// Vertices closer than this are welded (0: exactly coincident vertices only).
  double weld_tolerance = 0.0;
  /// Merge exactly coplanar adjacent faces into polygonal facets.
  bool merge_coplanar = true;
  /// Refuse open surfaces; false imports them as they are (for inspection, not meshing).
  bool require_closed = true;
  /// Run the exact intersection check (step 6).
  bool check_intersections = true;
  /// What a shell nested in another becomes.
  NestedShells nested_shells = NestedShells::Holes;
  /// Offending faces or edges listed in an error message (the rest are counted).
  std::size_t max_listed = 10;
  LogSink* log = nullptr;
};

/// What the import did, for the caller to report.
struct SurfaceImportReport {
  std::size_t input_vertices = 0;
  std::size_t input_faces = 0;
  std::size_t welded_vertices = 0;      ///< vertices after welding
  std::size_t collapsed_dropped = 0;    ///< faces with fewer than 3 distinct vertices
  std::size_t duplicates_dropped = 0;   ///< exact duplicate faces
  std::size_t zero_area_dropped = 0;    ///< collinear faces whose removal kept the surface closed
  std::size_t faces_reoriented = 0;     ///< faces flipped for consistent outward orientation
  std::size_t shells = 0;
  std::size_t cavities = 0;             ///< shells that bound a cavity
  std::size_t merged_facets = 0;        ///< facets made of more than one input face
};

/// Reads and converts a surface mesh file (format from the extension: .stl .off .obj .ply).
Expected<Plc> import_surface(const std::filesystem::path& path, const SurfaceImportOptions& options,
                             SurfaceImportReport* report = nullptr);

/// Steps 2-9 on a parsed soup; `file_name` names the input in errors.
Expected<Plc> surface_to_plc(const SurfaceSoup& soup, std::string_view file_name,
                             const SurfaceImportOptions& options, SurfaceImportReport* report = nullptr);

}  // namespace delmesh
