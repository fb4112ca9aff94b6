// Turning a read CAD model into closed solids ready to tessellate: heal (ShapeFix_Shape),
// sew faces that bound no solid into shells (BRepBuilderAPI_Sewing) and close them into
// solids (ShapeFix_Solid), then glue the solids of an assembly with OCCT's general fuse
// (BOPAlgo_Builder) so that touching faces become one shared face. Names follow every
// step through the operations' histories. Internal to importers/step/.
#pragma once

#include <string>

#include "importers/step/cad_model.h"
#include "toolkit/core/error.h"
#include "toolkit/core/log.h"

namespace delmesh::step {

/// Replaces `model.shape` by a compound of solids. Faces that bound no solid and cannot
/// be sewn into a closed shell are refused with ErrorCode::OpenBoundary (delmesh meshes
/// volumes: an open surface has no inside). `file` only names the input in messages.
Expected<void> make_solids(CadModel& model, const std::string& file, bool glue, LogSink* sink);

}  // namespace delmesh::step
