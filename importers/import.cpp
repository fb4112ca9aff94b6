// Dispatch of import_file() on the input format (see import.h).
#include "importers/import.h"

#include "importers/cad_reader.h"
#include "importers/input_format.h"
#include "importers/surface/surface_importer.h"
#include "importers/tetgen/tetgen_reader.h"
#include "toolkit/core/str_cat.h"

namespace delmesh {

bool cad_import_available() {
#ifdef DELMESH_HAVE_OCCT
  return true;
#else
  return false;
#endif
}

Expected<Plc> import_file(const std::filesystem::path& path, const ImportOptions& options) {
  const InputFormat format = detect_input_format(path);
  switch (format) {
    case InputFormat::Step:
    case InputFormat::Brep:
    case InputFormat::Iges: {
      StepImportOptions step = options.step;
      if (!step.log) step.log = options.log;
      return read_cad_file(path, step);
    }
    case InputFormat::Stl:
    case InputFormat::Off:
    case InputFormat::Obj:
    case InputFormat::Ply: {
      SurfaceImportOptions surface;
      surface.weld_tolerance = options.weld_tolerance;
      surface.merge_coplanar = options.merge_coplanar;
      surface.require_closed = options.require_closed;
      surface.log = options.log;
      return import_surface(path, surface);
    }
    case InputFormat::TetgenPoly: return read_tetgen(path, TetgenFileKind::Poly);
    case InputFormat::TetgenSmesh: return read_tetgen(path, TetgenFileKind::Smesh);
    case InputFormat::Node: return read_tetgen(path, TetgenFileKind::Node);
    case InputFormat::Unknown: break;
  }
  return make_error(ErrorCode::Unsupported,
                    cat("'", path.string(),
                        "': unknown file type (expected .step .stp .brep .iges .igs .stl .off .obj .ply "
                        ".poly .smesh .node)"));
}

}  // namespace delmesh
