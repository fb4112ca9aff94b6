// One entry point for every input format delmesh reads: the extension picks the importer
// (input_format.h) and the result is a Plc (notes §2.1.4). Surface meshes go through the
// surface importer (welding, repairs, orientation, exact self-intersection check, shells,
// coplanar merge: surface/surface_importer.h), TetGen files through the TetGen reader,
// CAD files (STEP/BREP/IGES) through read_cad_file (cad_reader.h): the OpenCASCADE
// importer when delmesh is built with it (otherwise an Unsupported error), or the reader
// a program links in its place (the delmesh command line's module loader).
#pragma once

#include <filesystem>

#include "importers/step/step_importer.h"
#include "toolkit/core/error.h"
#include "toolkit/core/log.h"
#include "toolkit/plc/plc.h"

namespace delmesh {

struct ImportOptions {
  /// Surface meshes: vertices closer than this are welded (0: exactly coincident only).
  double weld_tolerance = 0.0;
  /// Surface meshes: merge exactly coplanar adjacent triangles into polygonal facets.
  bool merge_coplanar = true;
  /// Surface meshes: refuse open surfaces (false: import them as they are, to inspect).
  bool require_closed = true;
  /// CAD files: tessellation and assembly options.
  StepImportOptions step;
  /// Warnings about repairs and progress; may be null.
  LogSink* log = nullptr;
};

/// True when this build reads STEP/BREP/IGES.
bool cad_import_available();

/// Reads any supported file into a PLC (not validated here for TetGen files: run
/// validate_plc() on the result).
Expected<Plc> import_file(const std::filesystem::path& path, const ImportOptions& options);

}  // namespace delmesh
