// The CAD reader that import_file() hands STEP/BREP/IGES files to. It is chosen when the
// program is linked, not at run time: the importers library defines it as the OpenCASCADE
// importer linked in (cad_reader_linked.cpp: import_step, or an Unsupported error in a
// build without OpenCASCADE), and a program that defines read_cad_file() in one of its own
// object files replaces it (the delmesh command line loads the importer as a module only
// when it reads a CAD file: tools/cad_module/cad_module_reader.cpp), so that program does
// not link OpenCASCADE at all.
#pragma once

#include <filesystem>

#include "importers/step/step_importer.h"
#include "toolkit/core/error.h"
#include "toolkit/plc/plc.h"

namespace delmesh {

/// Reads a CAD file (.step/.stp, .brep, .iges/.igs) into a PLC, as import_step does.
Expected<Plc> read_cad_file(const std::filesystem::path& path, const StepImportOptions& options);

}  // namespace delmesh
