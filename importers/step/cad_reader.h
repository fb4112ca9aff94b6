// Reading a CAD file into a CadModel: STEP and IGES through XDE (an XCAF document, so
// product names, face names and the assembly placements survive), BREP directly.
// Internal to importers/step/.
#pragma once

#include <filesystem>

#include "importers/step/cad_model.h"
#include "toolkit/core/error.h"
#include "toolkit/core/log.h"

namespace delmesh::step {

/// Reads `path` (format from its extension: .step/.stp, .iges/.igs, .brep/.brp). The
/// assembly tree is flattened: every leaf shape is placed by the product of the
/// locations on its path and added to one compound.
Expected<CadModel> read_cad_file(const std::filesystem::path& path, LogSink* sink);

}  // namespace delmesh::step
