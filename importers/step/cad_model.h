// The in-memory CAD model the STEP importer works on between its stages (read, repair,
// glue, tessellate): an OpenCASCADE shape plus the names the file gave its solids and
// faces. Internal to importers/step/ (OCCT types; never include from outside this folder).
#pragma once

#include <string>

#include <NCollection_DataMap.hxx>
#include <TopTools_ShapeMapHasher.hxx>
#include <TopoDS_Shape.hxx>

namespace delmesh::step {

/// Shape -> name, keyed by TShape and location (orientation ignored).
using ShapeNames = NCollection_DataMap<TopoDS_Shape, std::string, TopTools_ShapeMapHasher>;

struct CadModel {
  TopoDS_Shape shape;       ///< compound of every placed leaf shape of the file
  ShapeNames solid_names;   ///< solid -> product name
  ShapeNames face_names;    ///< face -> face name (only faces the file names)
  ShapeNames face_products; ///< face -> product name of the leaf shape holding it
};

}  // namespace delmesh::step
