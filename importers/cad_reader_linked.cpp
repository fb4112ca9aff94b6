// The library's CAD reader (see cad_reader.h): the OpenCASCADE importer linked into the
// program, or an Unsupported error naming the missing build option. Kept in its own file
// so that a program defining read_cad_file() itself never links this one, nor OpenCASCADE.
#include "importers/cad_reader.h"

#include "importers/input_format.h"
#include "toolkit/core/str_cat.h"

namespace delmesh {

Expected<Plc> read_cad_file(const std::filesystem::path& path, const StepImportOptions& options) {
#ifdef DELMESH_HAVE_OCCT
  return import_step(path, options);
#else
  (void)options;
  return make_error(ErrorCode::Unsupported,
                    cat("'", path.string(), "': this delmesh was built without OpenCASCADE, so ",
                        to_string(detect_input_format(path)), " files cannot be read (configure with DELMESH_WITH_OCCT=ON)"));
#endif
}

}  // namespace delmesh
