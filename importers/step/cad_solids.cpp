// Healing, sewing and gluing of CAD solids (see cad_solids.h).
//
// Sewing: faces outside any solid are sewn with a tolerance of 1e-6 of the model's
// bounding-box diagonal (at least 1e-7), raised to 1e-5 and 1e-4 while free edges
// remain (CAD exports of loose faces often leave gaps of that order); the closed shells of the result become solids
// (ShapeFix_Solid::SolidFromShell orients them outward). Faces that still bound no closed
// shell are refused with a diagnosis of the free edges left (ShapeAnalysis_FreeBounds):
// the loops they form, which of them are planar, and whether free edges come in nearby
// pairs (a gap wider than the sewing tolerance) or alone (faces missing from the file). Gluing: the general fuse of all
// solids splits faces where solids touch and shares the common parts, so an interface
// between two solids becomes a single face that both solids use; solids that overlap in
// volume produce their common part as a separate solid (reported as a warning).
#include "importers/step/cad_solids.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <vector>

#include <BOPAlgo_Builder.hxx>
#include <BRepBndLib.hxx>
#include <BRepAdaptor_Curve.hxx>
#include <BRepBuilderAPI_Sewing.hxx>
#include <BRepLib_FindSurface.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <Bnd_Box.hxx>
#include <ShapeAnalysis_FreeBounds.hxx>
#include <ShapeBuild_ReShape.hxx>
#include <ShapeFix_Shape.hxx>
#include <ShapeFix_Solid.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopTools_ListOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Compound.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Vertex.hxx>
#include <TopoDS_Wire.hxx>
#include <TopTools_IndexedDataMapOfShapeListOfShape.hxx>

namespace delmesh::step {
namespace {

/// Re-keys `names` on the images of their shapes; `images(shape, out)` fills the shapes
/// that replace `shape` (empty when the shape is unchanged, so it keeps its key).
template <class Images>
ShapeNames remap(const ShapeNames& names, TopAbs_ShapeEnum type, Images images) {
  ShapeNames out;
  for (ShapeNames::Iterator it(names); it.More(); it.Next()) {
    TopTools_ListOfShape replaced;
    images(it.Key(), replaced);
    if (replaced.IsEmpty()) {
      out.Bind(it.Key(), it.Value());
      continue;
    }
    for (TopTools_ListOfShape::Iterator r(replaced); r.More(); r.Next()) {
      for (TopExp_Explorer e(r.Value(), type); e.More(); e.Next()) out.Bind(e.Current(), it.Value());
    }
  }
  return out;
}

template <class Images>
void remap_all(CadModel& model, Images images) {
  model.solid_names = remap(model.solid_names, TopAbs_SOLID, images);
  model.face_names = remap(model.face_names, TopAbs_FACE, images);
  model.face_products = remap(model.face_products, TopAbs_FACE, images);
}

double diagonal(const TopoDS_Shape& shape) {
  Bnd_Box box;
  BRepBndLib::Add(shape, box);
  return box.IsVoid() ? 0.0 : std::sqrt(box.SquareExtent());
}

void heal(CadModel& model) {
  ShapeFix_Shape fix(model.shape);
  fix.Perform();
  const Handle(ShapeBuild_ReShape) context = fix.Context();
  remap_all(model, [&](const TopoDS_Shape& s, TopTools_ListOfShape& out) {
    const TopoDS_Shape image = context->Value(s);
    if (!image.IsNull() && !image.IsSame(s)) out.Append(image);
  });
  model.shape = fix.Shape();
}

std::string point_text(const gp_Pnt& p) {
  char buffer[96];
  std::snprintf(buffer, sizeof buffer, "(%.6g, %.6g, %.6g)", p.X(), p.Y(), p.Z());
  return buffer;
}

/// What the free edges left after sewing say about the surface: how many, the closed
/// loops they form (edge count, planarity, a point of each) and whether each has another
/// free edge nearby (a gap the tolerance did not bridge) or none (faces are missing).
std::string describe_free_edges(const TopoDS_Shape& sewn, double tolerance, double diag) {
  TopTools_IndexedDataMapOfShapeListOfShape edge_faces;
  TopExp::MapShapesAndAncestors(sewn, TopAbs_EDGE, TopAbs_FACE, edge_faces);
  std::vector<gp_Pnt> midpoints;
  for (int i = 1; i <= edge_faces.Extent(); ++i) {
    const TopoDS_Edge& edge = TopoDS::Edge(edge_faces.FindKey(i));
    if (edge_faces(i).Extent() != 1 || BRep_Tool::Degenerated(edge)) continue;
    const BRepAdaptor_Curve curve(edge);
    midpoints.push_back(curve.Value(0.5 * (curve.FirstParameter() + curve.LastParameter())));
  }
  // A free edge "has a partner" when another free edge's midpoint is within 1% of the
  // model size: the two sides of a gap.
  const double near = 1e-2 * diag;
  int paired = 0;
  for (std::size_t i = 0; i < midpoints.size(); ++i) {
    for (std::size_t j = 0; j < midpoints.size(); ++j) {
      if (i != j && midpoints[i].Distance(midpoints[j]) < near) {
        ++paired;
        break;
      }
    }
  }
  ShapeAnalysis_FreeBounds bounds(sewn, tolerance, Standard_False, Standard_True);
  std::string loops;
  int loop_count = 0, planar = 0;
  for (TopExp_Explorer it(bounds.GetClosedWires(), TopAbs_WIRE); it.More(); it.Next()) {
    const TopoDS_Wire& wire = TopoDS::Wire(it.Current());
    int edges = 0;
    for (TopExp_Explorer e(wire, TopAbs_EDGE); e.More(); e.Next()) ++edges;
    const bool is_planar = BRepLib_FindSurface(wire, tolerance, Standard_True).Found();
    planar += is_planar ? 1 : 0;
    TopExp_Explorer vertex(wire, TopAbs_VERTEX);
    loops += std::string(loop_count == 0 ? "" : "; ") + std::to_string(edges) + " edges" +
             (is_planar ? ", planar" : "") +
             (vertex.More() ? ", through " + point_text(BRep_Tool::Pnt(TopoDS::Vertex(vertex.Current()))) : "");
    ++loop_count;
  }
  int open_chains = 0;
  for (TopExp_Explorer it(bounds.GetOpenWires(), TopAbs_WIRE); it.More(); it.Next()) ++open_chains;
  std::string text = std::to_string(midpoints.size()) + " free edges remain after sewing with tolerance " +
                     std::to_string(tolerance) + ", forming " + std::to_string(loop_count) +
                     " closed loop(s) [" + loops + "]";
  if (open_chains > 0) text += " and " + std::to_string(open_chains) + " open chain(s)";
  if (loop_count > 0) text += ", " + std::to_string(planar) + " of the loops planar";
  if (paired == 0) {
    text += "; no free edge has another within 1% of the model size, so faces are missing "
            "from the file (holes, not gaps wider than the sewing tolerance)";
  } else {
    text += "; " + std::to_string(paired) +
            " free edges have another within 1% of the model size (gaps wider than the "
            "sewing tolerance)";
  }
  return text;
}

/// Sews the faces that bound no solid. Appends the closed shells as solids to `solids`;
/// returns the number of faces left in open shells or alone, and when there are some
/// fills `diagnosis` (describe_free_edges).
int sew_free_faces(CadModel& model, const std::vector<TopoDS_Face>& free_faces,
                   std::vector<TopoDS_Shape>& solids, LogSink* sink, const std::string& file,
                   std::string& diagnosis) {
  // Tolerances tried in turn until every shell closes: 1e-6, 1e-5, 1e-4 of the diagonal.
  const double diag = diagonal(model.shape);
  double tolerance = 0.0;
  std::unique_ptr<BRepBuilderAPI_Sewing> sewing_ptr;
  for (double relative : {1e-6, 1e-5, 1e-4}) {
    tolerance = std::max(1e-7, relative * diag);
    sewing_ptr = std::make_unique<BRepBuilderAPI_Sewing>(tolerance);
    for (const TopoDS_Face& face : free_faces) sewing_ptr->Add(face);
    sewing_ptr->Perform();
    if (sewing_ptr->NbFreeEdges() == 0) break;
  }
  const BRepBuilderAPI_Sewing& sewing = *sewing_ptr;
  const TopoDS_Shape sewn = sewing.SewedShape();
  remap_all(model, [&](const TopoDS_Shape& s, TopTools_ListOfShape& out) {
    if (s.ShapeType() == TopAbs_FACE && sewing.IsModified(s)) out.Append(sewing.Modified(s));
  });
  int open_faces = 0;
  int closed_shells = 0;
  for (TopExp_Explorer it(sewn, TopAbs_SHELL); it.More(); it.Next()) {
    const TopoDS_Shell shell = TopoDS::Shell(it.Current());
    int faces = 0;
    for (TopExp_Explorer f(shell, TopAbs_FACE); f.More(); f.Next()) ++faces;
    if (!BRep_Tool::IsClosed(shell)) {
      open_faces += faces;
      continue;
    }
    const TopoDS_Solid solid = ShapeFix_Solid().SolidFromShell(shell);
    if (solid.IsNull()) {
      open_faces += faces;
      continue;
    }
    ++closed_shells;
    TopExp_Explorer first_face(solid, TopAbs_FACE);
    if (first_face.More() && model.face_products.IsBound(first_face.Current())) {
      model.solid_names.Bind(solid, model.face_products.Find(first_face.Current()));
    }
    solids.push_back(solid);
  }
  for (TopExp_Explorer it(sewn, TopAbs_FACE, TopAbs_SHELL); it.More(); it.Next()) ++open_faces;
  if (open_faces > 0) diagnosis = describe_free_edges(sewn, tolerance, diag);
  log(sink, LogLevel::Info,
      file + ": sewed " + std::to_string(free_faces.size()) + " loose faces into " +
          std::to_string(closed_shells) + " closed solid(s) with tolerance " +
          std::to_string(tolerance));
  return open_faces;
}

/// Numbers the faces and solids of `solids` (TopExp::MapShapes order) and turns the
/// shape-keyed names into id-keyed ones.
void number_faces_and_solids(CadModel& model, const std::vector<TopoDS_Shape>& solids) {
  BRep_Builder builder;
  TopoDS_Compound compound;
  builder.MakeCompound(compound);
  for (const TopoDS_Shape& s : solids) builder.Add(compound, s);
  TopTools_IndexedMapOfShape faces, solid_map;
  TopExp::MapShapes(compound, TopAbs_FACE, faces);
  TopExp::MapShapes(compound, TopAbs_SOLID, solid_map);
  for (int i = 1; i <= faces.Extent(); ++i) {
    model.face_ids.Bind(faces(i), i);
    if (model.face_names.IsBound(faces(i))) model.face_id_names[i] = model.face_names.Find(faces(i));
  }
  for (int i = 1; i <= solid_map.Extent(); ++i) {
    model.solid_ids.Bind(solid_map(i), i);
    if (model.solid_names.IsBound(solid_map(i))) model.solid_id_names[i] = model.solid_names.Find(solid_map(i));
  }
  model.face_count = faces.Extent();
  model.solid_count = solid_map.Extent();
}

/// Re-keys `ids` on the images `fuse` made of their shapes; a shape made from several
/// keeps the smallest id.
ShapeIds remap_ids(const ShapeIds& ids, int count, TopAbs_ShapeEnum type, BOPAlgo_Builder& fuse) {
  std::vector<TopoDS_Shape> by_id(static_cast<std::size_t>(count) + 1);
  for (ShapeIds::Iterator it(ids); it.More(); it.Next()) by_id[it.Value()] = it.Key();
  ShapeIds out;
  for (int id = 1; id <= count; ++id) {
    if (by_id[id].IsNull()) continue;
    const TopTools_ListOfShape& images = fuse.Modified(by_id[id]);
    if (images.IsEmpty()) {
      if (!fuse.IsDeleted(by_id[id]) && !out.IsBound(by_id[id])) out.Bind(by_id[id], id);
      continue;
    }
    for (TopTools_ListOfShape::Iterator it(images); it.More(); it.Next()) {
      for (TopExp_Explorer e(it.Value(), type); e.More(); e.Next()) {
        if (!out.IsBound(e.Current())) out.Bind(e.Current(), id);
      }
    }
  }
  return out;
}

Expected<void> glue(CadModel& model, std::vector<TopoDS_Shape>& solids, const std::string& file,
                    LogSink* sink) {
  BOPAlgo_Builder fuse;
  TopTools_ListOfShape arguments;
  for (const TopoDS_Shape& s : solids) arguments.Append(s);
  fuse.SetArguments(arguments);
  fuse.SetRunParallel(false);
  fuse.SetNonDestructive(true);
  fuse.Perform();
  if (fuse.HasErrors()) {
    return make_error(ErrorCode::SelfIntersection,
                      file + ": gluing the " + std::to_string(solids.size()) +
                          " solids of the assembly into a conformal model failed (OpenCASCADE "
                          "general fuse); import with gluing off to inspect the parts");
  }
  model.face_ids = remap_ids(model.face_ids, model.face_count, TopAbs_FACE, fuse);
  model.solid_ids = remap_ids(model.solid_ids, model.solid_count, TopAbs_SOLID, fuse);
  const TopoDS_Shape result = fuse.Shape();
  const std::size_t before = solids.size();
  solids.clear();
  for (TopExp_Explorer it(result, TopAbs_SOLID); it.More(); it.Next()) solids.push_back(it.Current());
  if (solids.size() != before) {
    log(sink, LogLevel::Warning,
        file + ": " + std::to_string(before) + " solids overlap; gluing made " +
            std::to_string(solids.size()) + " pieces (a common part takes the id of the first "
            "solid it belongs to)");
  }
  return {};
}

}  // namespace

Expected<void> make_solids(CadModel& model, const std::string& file, bool glue_solids,
                           LogSink* sink) {
  heal(model);
  std::vector<TopoDS_Shape> solids;
  TopTools_IndexedMapOfShape solid_faces;
  for (TopExp_Explorer it(model.shape, TopAbs_SOLID); it.More(); it.Next()) {
    solids.push_back(it.Current());
    TopExp::MapShapes(it.Current(), TopAbs_FACE, solid_faces);
  }
  std::vector<TopoDS_Face> free_faces;
  TopTools_IndexedMapOfShape seen;
  for (TopExp_Explorer it(model.shape, TopAbs_FACE); it.More(); it.Next()) {
    if (solid_faces.Contains(it.Current()) || seen.Contains(it.Current())) continue;
    seen.Add(it.Current());
    free_faces.push_back(TopoDS::Face(it.Current()));
  }
  if (!free_faces.empty()) {
    std::string diagnosis;
    const int open_faces = sew_free_faces(model, free_faces, solids, sink, file, diagnosis);
    if (open_faces > 0) {
      return make_error(ErrorCode::OpenBoundary,
                        file + ": " + std::to_string(open_faces) + " of " +
                            std::to_string(free_faces.size()) +
                            " faces outside any solid do not sew into a closed shell: " +
                            diagnosis + "; delmesh meshes volumes and an open surface bounds none");
    }
  }
  if (solids.empty()) {
    return make_error(ErrorCode::InvalidInput, file + ": the file holds no solid");
  }
  number_faces_and_solids(model, solids);
  if (glue_solids && solids.size() > 1) {
    if (Expected<void> glued = glue(model, solids, file, sink); !glued) return glued;
  }
  BRep_Builder builder;
  TopoDS_Compound compound;
  builder.MakeCompound(compound);
  for (const TopoDS_Shape& s : solids) builder.Add(compound, s);
  model.shape = compound;
  return {};
}

}  // namespace delmesh::step
