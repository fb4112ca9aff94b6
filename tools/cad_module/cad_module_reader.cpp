// The delmesh command line's CAD reader (importers/cad_reader.h): loads the CAD import
// module (cad_module.h) the first time a STEP/BREP/IGES file is read, from the place the
// build and the install tree put it relative to the program (bin/delmesh and
// lib/delmesh/libdelmesh_cad.so), and hands the file to it. Linked into the delmesh
// executable only, where it replaces the library's linked reader, so the program itself
// does not need OpenCASCADE's libraries.
#include <dlfcn.h>

#include <string>
#include <system_error>

#include "importers/cad_reader.h"
#include "tools/cad_module/cad_module.h"
#include "toolkit/core/str_cat.h"

namespace delmesh {
namespace {

struct LoadedModule {
  CadModuleEntry entry = nullptr;
  std::string problem;  ///< why the module could not be loaded, when entry is null
};

/// The module's place: DELMESH_CAD_MODULE_FROM_PROGRAM (set by the build) relative to the
/// directory of the running program.
std::filesystem::path module_path() {
  std::error_code error;
  const std::filesystem::path program = std::filesystem::read_symlink("/proc/self/exe", error);
  return (program.parent_path() / DELMESH_CAD_MODULE_FROM_PROGRAM).lexically_normal();
}

LoadedModule load_module() {
  const std::filesystem::path path = module_path();
  // Never unloaded: OpenCASCADE keeps global state for the whole process.
  void* handle = ::dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  const char* failure = handle ? nullptr : ::dlerror();
  if (handle) {
    if (void* symbol = ::dlsym(handle, kCadModuleEntryName)) return {reinterpret_cast<CadModuleEntry>(symbol), {}};
    failure = ::dlerror();
  }
  return {nullptr, cat("the CAD import module '", path.string(), "' cannot be loaded (",
                       failure ? failure : "no reason given",
                       "): STEP/BREP/IGES files are read through it")};
}

}  // namespace

Expected<Plc> read_cad_file(const std::filesystem::path& path, const StepImportOptions& options) {
  static const LoadedModule module = load_module();
  if (!module.entry) return make_error(ErrorCode::Unsupported, cat("'", path.string(), "': ", module.problem));
  Expected<Plc> result = make_error(ErrorCode::Unsupported, "the CAD import module returned nothing");
  module.entry(path, options, result);
  return result;
}

}  // namespace delmesh
