// The in-memory CAD model the STEP importer works on between its stages (read, repair,
// glue, tessellate): an OpenCASCADE shape plus the names the file gave its solids and
// faces. Internal to importers/step/ (OCCT types; never include from outside this folder).
#pragma once

#include <array>
#include <map>
#include <string>

#include <NCollection_DataMap.hxx>
#include <TopTools_ShapeMapHasher.hxx>
#include <TopoDS_Shape.hxx>

namespace delmesh::step {

/// Shape -> name, keyed by TShape and location (orientation ignored).
using ShapeNames = NCollection_DataMap<TopoDS_Shape, std::string, TopTools_ShapeMapHasher>;
/// sRGB colour components in [0, 1].
using Rgb = std::array<double, 3>;
/// Shape -> colour, keyed the same way.
using ShapeColors = NCollection_DataMap<TopoDS_Shape, Rgb, TopTools_ShapeMapHasher>;
/// Shape -> id, keyed the same way.
using ShapeIds = NCollection_DataMap<TopoDS_Shape, int, TopTools_ShapeMapHasher>;

struct CadModel {
  TopoDS_Shape shape;       ///< compound of every placed leaf shape of the file
  ShapeNames solid_names;   ///< solid -> product name
  ShapeNames face_names;    ///< face -> face name (only faces the file names)
  ShapeNames face_products; ///< face -> product name of the leaf shape holding it
  ShapeColors solid_colors; ///< solid -> colour of its shape (XDE surface or generic colour)
  ShapeColors face_colors;  ///< face -> its own colour, else its shape's

  // Set by make_solids. Ids are 1-based indices in TopExp::MapShapes order of the closed
  // solids before gluing; faces split by gluing keep the id of the face they come from,
  // and an interface face shared by two solids keeps the smaller of its two ids. Pieces
  // of overlapping solids keep the id of the first solid they belong to.
  ShapeIds face_ids;
  ShapeIds solid_ids;
  std::map<int, std::string> face_id_names;   ///< face id -> name
  std::map<int, std::string> solid_id_names;  ///< solid id -> product name
  std::map<int, Rgb> face_id_colors;          ///< face id -> colour
  std::map<int, Rgb> solid_id_colors;         ///< solid id -> colour
  int face_count = 0;   ///< number of face ids
  int solid_count = 0;  ///< number of solid ids
};

}  // namespace delmesh::step
