// The CAD import module's entry point (see cad_module.h): import_step behind a C name.
// Only this symbol is exported; the static libraries linked in stay hidden in the module.
#include "tools/cad_module/cad_module.h"

extern "C" __attribute__((visibility("default"))) void delmesh_cad_module_read(
    const std::filesystem::path& path, const delmesh::StepImportOptions& options,
    delmesh::Expected<delmesh::Plc>& result) {
  result = delmesh::import_step(path, options);
}
