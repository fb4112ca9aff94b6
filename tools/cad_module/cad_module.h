// The interface between the delmesh command line and its CAD import module
// (libdelmesh_cad.so): the OpenCASCADE-based STEP/BREP/IGES importer built as a shared
// module that the program loads with dlopen() only when it reads such a file, so that
// the start of every other run does not load and relocate OpenCASCADE's libraries.
// The module and the program are built from the same sources by the same compiler, so
// the entry point passes C++ types; its C name is what dlsym() looks up.
#pragma once

#include <filesystem>

#include "importers/step/step_importer.h"
#include "toolkit/core/error.h"
#include "toolkit/plc/plc.h"

/// The name dlsym() finds the module's entry point under.
inline constexpr char kCadModuleEntryName[] = "delmesh_cad_module_read";

/// The entry point: import_step(path, options) stored into `result`.
extern "C" {
using CadModuleEntry = void (*)(const std::filesystem::path& path, const delmesh::StepImportOptions& options,
                                delmesh::Expected<delmesh::Plc>& result);
}
