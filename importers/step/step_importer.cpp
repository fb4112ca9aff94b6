// import_step: the stages of the CAD importer in order (read with XDE, make closed and
// glued solids, tessellate into a PLC). See step_importer.h for the contract and
// cad_reader.h, cad_solids.h and cad_to_plc.h for each stage.
#include "importers/step/step_importer.h"

#include <chrono>
#include <cmath>
#include <numbers>
#include <string>

#include <BRepBndLib.hxx>
#include <Bnd_Box.hxx>
#include <Standard_Failure.hxx>

#include "importers/step/cad_reader.h"
#include "importers/step/cad_solids.h"
#include "importers/step/cad_to_plc.h"

namespace delmesh {
namespace {

/// Default chordal deflection: 1/1000 of the bounding-box diagonal.
constexpr double kDefaultRelativeDeflection = 1e-3;
/// Default angular deflection: 20 degrees (BRepMesh's own default is 0.5 rad).
constexpr double kDefaultAngleDeg = 20.0;
/// Triangles of non-planar faces with a smaller angle are bisected (surface_refinement.h).
constexpr double kSurfaceMinAngleDeg = 20.0;
/// Refinement never splits edges shorter than this fraction of the chordal deflection.
constexpr double kMinEdgeLengthFactor = 0.05;

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

Expected<Plc> run(const std::filesystem::path& path, const StepImportOptions& options) {
  const std::string file = path.string();
  auto start = std::chrono::steady_clock::now();
  Expected<step::CadModel> model = step::read_cad_file(path, options.log);
  if (!model) return model.error();
  log(options.log, LogLevel::Info, file + ": read in " + std::to_string(seconds_since(start)) + " s");
  start = std::chrono::steady_clock::now();
  if (Expected<void> solids = step::make_solids(*model, file, options.glue_assembly, options.log);
      !solids) {
    return solids.error();
  }
  log(options.log, LogLevel::Info,
      file + ": healed, sewn and glued in " + std::to_string(seconds_since(start)) + " s");
  Bnd_Box box;
  BRepBndLib::Add(model->shape, box);
  const double diagonal = std::sqrt(box.SquareExtent());
  if (!(diagonal > 0.0) || !std::isfinite(diagonal)) {
    return make_error(ErrorCode::DegenerateInput, file + ": the model has no extent");
  }
  step::TessellationParameters parameters;
  const double relative = options.relative_linear_deflection > 0.0 ? options.relative_linear_deflection
                                                                    : kDefaultRelativeDeflection;
  const double degrees = options.angular_deflection_deg > 0.0 ? options.angular_deflection_deg
                                                               : kDefaultAngleDeg;
  parameters.linear_deflection = relative * diagonal;
  parameters.angular_deflection = degrees * std::numbers::pi / 180.0;
  parameters.min_angle_deg = kSurfaceMinAngleDeg;
  parameters.min_edge_length = kMinEdgeLengthFactor * parameters.linear_deflection;
  step::TessellationReport report;
  start = std::chrono::steady_clock::now();
  Expected<Plc> plc = step::tessellate_to_plc(*model, parameters, file, report, options.log);
  log(options.log, LogLevel::Info, file + ": tessellated in " + std::to_string(seconds_since(start)) + " s");
  if (options.surface_summary && plc) {
    StepSurfaceSummary& summary = *options.surface_summary;
    summary.faces_refined = report.faces_refined;
    summary.faces_excluded = report.faces_excluded_from_refinement;
    summary.reverted = report.refinement_reverted;
    summary.min_angle_before_deg = report.min_unforced_angle_before_deg;
    summary.min_angle_after_deg = report.min_unforced_angle_after_deg;
    summary.min_angle_away_from_small_corners_deg = report.min_angle_away_from_small_corners_deg;
    for (const step::TessellationReport::RefinedFace& face : report.refined_faces) {
      if (!face.excluded && face.min_angle_away_from_small_corners_deg < parameters.min_angle_deg) {
        ++summary.faces_below_bound;
      }
    }
  }
  return plc;
}

}  // namespace

Expected<Plc> import_step(const std::filesystem::path& path, const StepImportOptions& options) {
  if (options.relative_linear_deflection >= 1.0 || options.angular_deflection_deg >= 180.0) {
    return make_error(ErrorCode::InvalidOption,
                      "STEP import: relative deflection must be < 1 and angular deflection < 180 degrees");
  }
  try {
    return run(path, options);
  } catch (const Standard_Failure& failure) {
    return make_error(ErrorCode::InvalidInput, path.string() + ": OpenCASCADE failed: " +
                                                   std::string(failure.GetMessageString()));
  }
}

}  // namespace delmesh
