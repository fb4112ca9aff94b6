// Reading STEP/IGES through XDE and BREP through BRepTools (see cad_reader.h).
//
// XDE keeps the product structure: free shapes are the roots, assemblies hold
// components that refer to other labels with a location. Leaf (simple) shapes are placed
// by the accumulated location and keep the name of the product they instantiate; faces
// named in the file keep their names (STEP: the names of ADVANCED_FACE entities, read with
// read.stepcaf.subshapes.name on; names exporters write for unnamed faces, "NONE" and
// "#<entity id>", are skipped).
//
// Colours are resolved as OpenCASCADE's own presentation of an XDE document does it
// (XCAFPrs::CollectStyleSettings, then a top-down dispatch like XCAFPrs_AISObject's):
// every colour in the document is attached to a placed shape: a product's own colour and
// its sub-shape colours, a component (assembly instance) colour, a SHUO colour (one
// occurrence of a nested component, read with SetSHUOMode) and a colour given by the
// single layer of a shape (read with SetLayerMode). Walking down from the roots, a shape
// takes its own colour if it has one, else the colour of the nearest placed shape above
// it. So an instance colour overrides the colour of the product it places (both are
// attached to the same placed shape; the instance's is collected last), a SHUO colour
// overrides both for its one occurrence, and a colour set on a face or solid of the
// product itself stays on that face or solid. Surface colours take precedence over
// generic ones.
#include "importers/step/cad_reader.h"

#include <algorithm>
#include <cctype>
#include <optional>
#include <string>
#include <type_traits>

#include <BRepTools.hxx>
#include <BRep_Builder.hxx>
#include <IFSelect_ReturnStatus.hxx>
#include <IGESCAFControl_Reader.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <Interface_Static.hxx>
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
#include <TopoDS_Iterator.hxx>
#include <XCAFApp_Application.hxx>
#include <XCAFDoc_DocumentTool.hxx>
#include <XCAFDoc_ShapeTool.hxx>
#include <XCAFPrs.hxx>
#include <XCAFPrs_IndexedDataMapOfShapeStyle.hxx>
#include <XCAFPrs_Style.hxx>

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

/// False for the placeholders exporters write for an unnamed entity: "", "NONE" and
/// "#<digits>".
bool is_real_name(const std::string& name) {
  if (name.empty() || name == "NONE") return false;
  return !(name.size() > 1 && name[0] == '#' &&
           std::all_of(name.begin() + 1, name.end(), [](unsigned char c) { return std::isdigit(c) != 0; }));
}

std::string label_name(const TDF_Label& label) {
  Handle(TDataStd_Name) name;
  if (!label.FindAttribute(TDataStd_Name::GetID(), name)) return {};
  return TCollection_AsciiString(name->Get()).ToCString();  // UTF-8
}

/// Placed shape -> presentation style, for every coloured shape of the document.
using ShapeStyles = XCAFPrs_IndexedDataMapOfShapeStyle;

class TreeFlattener {
 public:
  TreeFlattener(CadModel& model, BRep_Builder& builder, TopoDS_Compound& compound, const ShapeStyles& styles)
      : model_(model), builder_(builder), compound_(compound), styles_(styles) {}

  /// `inherited`: the colour of the nearest coloured placed shape above `label`.
  void visit(const TDF_Label& label, const TopLoc_Location& location, const std::string& name, int depth,
             std::optional<Rgb> inherited) {
    if (depth > 64) return;  // a reference cycle: a malformed file, stop descending
    TopoDS_Shape shape = XCAFDoc_ShapeTool::GetShape(label);
    if (XCAFDoc_ShapeTool::IsAssembly(label)) {
      const std::optional<Rgb> color = shape.IsNull() ? inherited : own_color(shape.Moved(location), inherited);
      TDF_LabelSequence components;
      XCAFDoc_ShapeTool::GetComponents(label, components);
      for (Standard_Integer i = 1; i <= components.Length(); ++i) {
        const TDF_Label& component = components.Value(i);
        TDF_Label referred;
        if (!XCAFDoc_ShapeTool::GetReferredShape(component, referred)) continue;
        std::string child_name = label_name(referred);
        if (child_name.empty()) child_name = label_name(component);
        if (child_name.empty()) child_name = name;
        visit(referred, location * XCAFDoc_ShapeTool::GetLocation(component), child_name, depth + 1, color);
      }
      return;
    }
    if (shape.IsNull()) return;
    shape = shape.Moved(location);
    builder_.Add(compound_, shape);
    for (TopExp_Explorer it(shape, TopAbs_SOLID); it.More(); it.Next()) {
      if (!name.empty()) model_.solid_names.Bind(it.Current(), name);
    }
    for (TopExp_Explorer it(shape, TopAbs_FACE); it.More(); it.Next()) {
      if (!name.empty()) model_.face_products.Bind(it.Current(), name);
    }
    dispatch_colors(shape, inherited);
    TDF_LabelSequence sub_shapes;
    XCAFDoc_ShapeTool::GetSubShapes(label, sub_shapes);
    for (Standard_Integer i = 1; i <= sub_shapes.Length(); ++i) {
      const std::string sub_name = label_name(sub_shapes.Value(i));
      const TopoDS_Shape sub = XCAFDoc_ShapeTool::GetShape(sub_shapes.Value(i));
      if (sub.IsNull() || !is_real_name(sub_name)) continue;
      for (TopExp_Explorer it(sub.Moved(location), TopAbs_FACE); it.More(); it.Next()) {
        model_.face_names.Bind(it.Current(), sub_name);
      }
    }
  }

 private:
  /// The surface colour of the style attached to `placed`, else `inherited`.
  std::optional<Rgb> own_color(const TopoDS_Shape& placed, std::optional<Rgb> inherited) const {
    const XCAFPrs_Style* style = styles_.Seek(placed);
    if (style == nullptr || !style->IsSetColorSurf()) return inherited;
    Rgb rgb{};
    style->GetColorSurf().Values(rgb[0], rgb[1], rgb[2], Quantity_TOC_sRGB);
    return rgb;
  }

  /// Gives every solid and face below `shape` (placed) its colour, top-down.
  void dispatch_colors(const TopoDS_Shape& shape, std::optional<Rgb> inherited) {
    const TopAbs_ShapeEnum type = shape.ShapeType();
    if (type == TopAbs_WIRE || type == TopAbs_EDGE || type == TopAbs_VERTEX) return;
    const std::optional<Rgb> color = own_color(shape, inherited);
    if (type == TopAbs_FACE) {
      if (color) model_.face_colors.Bind(shape, *color);
      return;
    }
    if (type == TopAbs_SOLID && color) model_.solid_colors.Bind(shape, *color);
    for (TopoDS_Iterator it(shape); it.More(); it.Next()) dispatch_colors(it.Value(), color);
  }

  CadModel& model_;
  BRep_Builder& builder_;
  TopoDS_Compound& compound_;
  const ShapeStyles& styles_;
};

template <class Reader>
Expected<CadModel> read_with_xde(Reader& reader, const std::filesystem::path& path,
                                 const char* format_name) {
  const std::string file = path.string();
  reader.SetNameMode(true);
  reader.SetColorMode(true);
  reader.SetLayerMode(true);
  if constexpr (std::is_same_v<Reader, STEPCAFControl_Reader>) {
    reader.SetSHUOMode(true);
    Interface_Static::SetIVal("read.stepcaf.subshapes.name", 1);
  }
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
  ShapeStyles styles;
  for (Standard_Integer i = 1; i <= roots.Length(); ++i) {
    XCAFPrs::CollectStyleSettings(roots.Value(i), TopLoc_Location(), styles);
  }
  TreeFlattener flattener(model, builder, compound, styles);
  for (Standard_Integer i = 1; i <= roots.Length(); ++i) {
    flattener.visit(roots.Value(i), TopLoc_Location(), label_name(roots.Value(i)), 0, std::nullopt);
  }
  XCAFApp_Application::GetApplication()->Close(document);
  model.shape = compound;
  return model;
}

/// Detaches OpenCASCADE's default message printers (which write to stdout, e.g. the IGES
/// reader's entity count) for its lifetime: delmesh reports through its LogSink only.
class OcctMessagesSilenced {
 public:
  OcctMessagesSilenced() : messenger_(Message::DefaultMessenger()), saved_(messenger_->Printers()) {
    messenger_->ChangePrinters().Clear();
  }
  ~OcctMessagesSilenced() { messenger_->ChangePrinters() = saved_; }
  OcctMessagesSilenced(const OcctMessagesSilenced&) = delete;
  OcctMessagesSilenced& operator=(const OcctMessagesSilenced&) = delete;

 private:
  Handle(Message_Messenger) messenger_;
  Message_SequenceOfPrinters saved_;
};

}  // namespace

Expected<CadModel> read_cad_file(const std::filesystem::path& path, LogSink* sink) {
  const std::string file = path.string();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    return make_error(ErrorCode::IoError, file + ": no such file");
  }
  Expected<CadModel> model = make_error(ErrorCode::Unsupported, file + ": unknown CAD format");
  const OcctMessagesSilenced quiet;
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
