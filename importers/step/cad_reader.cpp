// Reading STEP/IGES through XDE and BREP through BRepTools (see cad_reader.h).
//
// XDE keeps the product structure: free shapes are the roots, assemblies hold
// components that refer to other labels with a location. Leaf (simple) shapes are placed
// by the accumulated location and keep the name of the product they instantiate; faces
// named in the file (sub-shape labels) keep their names. Colours (XCAFDoc_ColorTool,
// surface colour first, then generic) follow the same labels: a shape's colour goes to
// its solids and faces, a face's own colour (a sub-shape label, or an overriding style)
// replaces it on that face. Colours set on assembly instances are not read.
#include "importers/step/cad_reader.h"

#include <algorithm>
#include <cctype>
#include <optional>
#include <string>
#include <utility>

#include <BRepTools.hxx>
#include <BRep_Builder.hxx>
#include <IFSelect_ReturnStatus.hxx>
#include <IGESCAFControl_Reader.hxx>
#include <STEPCAFControl_Reader.hxx>
#include <TCollection_AsciiString.hxx>
#include <TDF_Label.hxx>
#include <TDF_LabelSequence.hxx>
#include <TDataStd_Name.hxx>
#include <TDocStd_Document.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Compound.hxx>
#include <Quantity_Color.hxx>
#include <XCAFDoc_ColorTool.hxx>
#include <XCAFDoc_ColorType.hxx>
#include <XCAFApp_Application.hxx>
#include <XCAFDoc_DocumentTool.hxx>
#include <XCAFDoc_ShapeTool.hxx>

namespace delmesh::step {
namespace {

enum class CadFormat { Step, Iges, Brep, Unknown };

CadFormat format_of(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext == ".step" || ext == ".stp") return CadFormat::Step;
  if (ext == ".iges" || ext == ".igs") return CadFormat::Iges;
  if (ext == ".brep" || ext == ".brp") return CadFormat::Brep;
  return CadFormat::Unknown;
}

std::string label_name(const TDF_Label& label) {
  Handle(TDataStd_Name) name;
  if (!label.FindAttribute(TDataStd_Name::GetID(), name)) return {};
  return TCollection_AsciiString(name->Get()).ToCString();  // UTF-8
}

/// The colour XDE attaches to `label` (surface colour, else generic), as sRGB.
std::optional<Rgb> label_color(const Handle(XCAFDoc_ColorTool)& colors, const TDF_Label& label) {
  Quantity_Color color;
  if (!colors->GetColor(label, XCAFDoc_ColorSurf, color) && !colors->GetColor(label, XCAFDoc_ColorGen, color)) {
    return std::nullopt;
  }
  Rgb rgb{};
  color.Values(rgb[0], rgb[1], rgb[2], Quantity_TOC_sRGB);
  return rgb;
}

class TreeFlattener {
 public:
  TreeFlattener(CadModel& model, BRep_Builder& builder, TopoDS_Compound& compound,
                Handle(XCAFDoc_ColorTool) colors)
      : model_(model), builder_(builder), compound_(compound), colors_(std::move(colors)) {}

  void visit(const TDF_Label& label, const TopLoc_Location& location, const std::string& name,
             int depth) {
    if (depth > 64) return;  // a reference cycle: a malformed file, stop descending
    if (XCAFDoc_ShapeTool::IsAssembly(label)) {
      TDF_LabelSequence components;
      XCAFDoc_ShapeTool::GetComponents(label, components);
      for (Standard_Integer i = 1; i <= components.Length(); ++i) {
        const TDF_Label& component = components.Value(i);
        TDF_Label referred;
        if (!XCAFDoc_ShapeTool::GetReferredShape(component, referred)) continue;
        std::string child_name = label_name(referred);
        if (child_name.empty()) child_name = label_name(component);
        if (child_name.empty()) child_name = name;
        visit(referred, location * XCAFDoc_ShapeTool::GetLocation(component), child_name,
              depth + 1);
      }
      return;
    }
    TopoDS_Shape shape = XCAFDoc_ShapeTool::GetShape(label);
    if (shape.IsNull()) return;
    shape = shape.Moved(location);
    builder_.Add(compound_, shape);
    for (TopExp_Explorer it(shape, TopAbs_SOLID); it.More(); it.Next()) {
      if (!name.empty()) model_.solid_names.Bind(it.Current(), name);
    }
    for (TopExp_Explorer it(shape, TopAbs_FACE); it.More(); it.Next()) {
      if (!name.empty()) model_.face_products.Bind(it.Current(), name);
    }
    if (const std::optional<Rgb> color = label_color(colors_, label)) {
      for (TopExp_Explorer it(shape, TopAbs_SOLID); it.More(); it.Next()) model_.solid_colors.Bind(it.Current(), *color);
      for (TopExp_Explorer it(shape, TopAbs_FACE); it.More(); it.Next()) model_.face_colors.Bind(it.Current(), *color);
    }
    TDF_LabelSequence sub_shapes;
    XCAFDoc_ShapeTool::GetSubShapes(label, sub_shapes);
    for (Standard_Integer i = 1; i <= sub_shapes.Length(); ++i) {
      const std::string sub_name = label_name(sub_shapes.Value(i));
      const std::optional<Rgb> sub_color = label_color(colors_, sub_shapes.Value(i));
      const TopoDS_Shape sub = XCAFDoc_ShapeTool::GetShape(sub_shapes.Value(i));
      if (sub.IsNull()) continue;
      for (TopExp_Explorer it(sub.Moved(location), TopAbs_FACE); it.More(); it.Next()) {
        if (!sub_name.empty()) model_.face_names.Bind(it.Current(), sub_name);
        if (sub_color) model_.face_colors.Bind(it.Current(), *sub_color);
      }
    }
  }

 private:
  CadModel& model_;
  BRep_Builder& builder_;
  TopoDS_Compound& compound_;
  Handle(XCAFDoc_ColorTool) colors_;
};

template <class Reader>
Expected<CadModel> read_with_xde(Reader& reader, const std::filesystem::path& path,
                                 const char* format_name) {
  const std::string file = path.string();
  reader.SetNameMode(true);
  reader.SetColorMode(true);
  reader.SetLayerMode(false);
  if (reader.ReadFile(file.c_str()) != IFSelect_RetDone) {
    return make_error(ErrorCode::ParseError,
                      file + ": not a readable " + format_name + " file (OpenCASCADE reader failed)");
  }
  Handle(TDocStd_Document) document;
  XCAFApp_Application::GetApplication()->NewDocument("MDTV-XCAF", document);
  if (!reader.Transfer(document)) {
    return make_error(ErrorCode::ParseError,
                      file + ": the " + format_name + " file holds no transferable shape");
  }
  const Handle(XCAFDoc_ShapeTool) tool = XCAFDoc_DocumentTool::ShapeTool(document->Main());
  TDF_LabelSequence roots;
  tool->GetFreeShapes(roots);
  CadModel model;
  BRep_Builder builder;
  TopoDS_Compound compound;
  builder.MakeCompound(compound);
  TreeFlattener flattener(model, builder, compound, XCAFDoc_DocumentTool::ColorTool(document->Main()));
  for (Standard_Integer i = 1; i <= roots.Length(); ++i) {
    flattener.visit(roots.Value(i), TopLoc_Location(), label_name(roots.Value(i)), 0);
  }
  XCAFApp_Application::GetApplication()->Close(document);
  model.shape = compound;
  return model;
}

}  // namespace

Expected<CadModel> read_cad_file(const std::filesystem::path& path, LogSink* sink) {
  const std::string file = path.string();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    return make_error(ErrorCode::IoError, file + ": no such file");
  }
  Expected<CadModel> model = make_error(ErrorCode::Unsupported, file + ": unknown CAD format");
  switch (format_of(path)) {
    case CadFormat::Step: {
      STEPCAFControl_Reader reader;
      model = read_with_xde(reader, path, "STEP");
      break;
    }
    case CadFormat::Iges: {
      IGESCAFControl_Reader reader;
      model = read_with_xde(reader, path, "IGES");
      break;
    }
    case CadFormat::Brep: {
      TopoDS_Shape shape;
      BRep_Builder builder;
      if (!BRepTools::Read(shape, file.c_str(), builder) || shape.IsNull()) {
        return make_error(ErrorCode::ParseError, file + ": not a readable BREP file");
      }
      CadModel brep;
      brep.shape = shape;
      model = brep;
      break;
    }
    case CadFormat::Unknown:
      return make_error(ErrorCode::Unsupported,
                        file + ": unknown CAD extension (expected .step/.stp, .iges/.igs or .brep)");
  }
  if (!model) return model;
  if (TopExp_Explorer(model->shape, TopAbs_FACE).More() == Standard_False) {
    return make_error(ErrorCode::InvalidInput, file + ": the file holds no face (nothing to mesh)");
  }
  int solids = 0, faces = 0;
  for (TopExp_Explorer it(model->shape, TopAbs_SOLID); it.More(); it.Next()) ++solids;
  for (TopExp_Explorer it(model->shape, TopAbs_FACE); it.More(); it.Next()) ++faces;
  log(sink, LogLevel::Info,
      file + ": " + std::to_string(solids) + " solids, " + std::to_string(faces) + " faces read");
  return model;
}

}  // namespace delmesh::step
