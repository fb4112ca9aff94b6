// import_step: the stages of the CAD importer in order (read with XDE, make closed and
// glued solids, tessellate into a PLC). See step_importer.h for the contract and
// cad_reader.h, cad_solids.h and cad_to_plc.h for each stage.
#include "importers/step/step_importer.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <string>
#include <utility>

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
/// Triangles of non-planar faces with a smaller angle are bisected (surface_refinement.h),
/// unless StepImportOptions::surface_min_angle_deg asks for another bound.
constexpr double kSurfaceMinAngleDeg = 20.0;
/// The largest bound StepImportOptions::surface_min_angle_deg may ask for (the
/// bisection-and-flip refinement is not known to end above 30 degrees in the plane).
constexpr double kMaxSurfaceMinAngleDeg = 30.0;
/// Refinement never splits edges shorter than this fraction of the chordal deflection.
constexpr double kMinEdgeLengthFactor = 0.05;
/// Default plane tolerance (StepImportOptions::relative_plane_tolerance): far below any
/// CAD tolerance (OpenCASCADE's Precision::Confusion, 1e-7, is 1e-9 of a 100 mm part),
/// far above the rounding of placed coordinates (about 1e-16 of them).
constexpr double kDefaultRelativePlaneTolerance = 1e-10;

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

std::string short_number(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.3g", value);
  return buffer;
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
  parameters.min_angle_deg = options.surface_min_angle_deg > 0.0 ? options.surface_min_angle_deg : kSurfaceMinAngleDeg;
  parameters.min_edge_length = kMinEdgeLengthFactor * parameters.linear_deflection;
  parameters.plane_merge_tolerance =
      (options.relative_plane_tolerance < 0.0 ? kDefaultRelativePlaneTolerance : options.relative_plane_tolerance) *
      diagonal;
  step::TessellationReport report;
  start = std::chrono::steady_clock::now();
  Expected<Plc> plc = step::tessellate_to_plc(*model, parameters, file, report, options.log);
  if (parameters.min_angle_deg > kSurfaceMinAngleDeg &&
      (!plc || report.refinement_reverted || report.faces_excluded_from_refinement > 0)) {
    // A bound above the default that makes refinement give up on faces (they keep
    // BRepMesh's triangles, far worse than the default bound would leave them: the torus
    // of occt-screw at 26 degrees), or fails, is dropped for the default when that
    // excludes fewer faces or succeeds.
    step::TessellationParameters fallback = parameters;
    fallback.min_angle_deg = kSurfaceMinAngleDeg;
    step::TessellationReport fallback_report;
    Expected<Plc> retry = step::tessellate_to_plc(*model, fallback, file, fallback_report, options.log);
    const auto excluded = [](const step::TessellationReport& r) {
      return r.refinement_reverted ? std::numeric_limits<int>::max() : r.faces_excluded_from_refinement;
    };
    if (retry && (!plc || excluded(fallback_report) < excluded(report))) {
      log(options.log, LogLevel::Info,
          file + ": surface refinement at " + short_number(parameters.min_angle_deg) + " degrees " +
              (plc ? "excluded " + std::to_string(report.faces_excluded_from_refinement) + " face(s)"
                   : std::string("failed")) +
              ", at the default " +
              short_number(kSurfaceMinAngleDeg) + " degrees " +
              std::to_string(fallback_report.faces_excluded_from_refinement) + ": the default bound is used");
      plc = std::move(retry);
      report = std::move(fallback_report);
      parameters = fallback;
    }
  }
  log(options.log, LogLevel::Info, file + ": tessellated in " + std::to_string(seconds_since(start)) + " s");
  if (plc && report.coordinate_plane_values_merged > 0) {
    log(options.log, LogLevel::Warning,
        file + ": " + std::to_string(report.coordinate_plane_values_merged) +
            " coordinate-plane value(s) merged into another within the plane tolerance " +
            short_number(parameters.plane_merge_tolerance) +
            " (relative to the model size; vertices of those faces snapped onto one plane)");
  }
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
  if (options.relative_linear_deflection >= 1.0 || options.angular_deflection_deg >= 180.0 ||
      !(options.relative_plane_tolerance < 1e-3) || !(options.surface_min_angle_deg <= kMaxSurfaceMinAngleDeg)) {
    return make_error(ErrorCode::InvalidOption,
                      "STEP import: relative deflection must be < 1, angular deflection < 180 degrees, "
                      "relative plane tolerance < 1e-3 and surface minimum angle at most 30 degrees");
  }
  try {
    return run(path, options);
  } catch (const Standard_Failure& failure) {
    return make_error(ErrorCode::InvalidInput, path.string() + ": OpenCASCADE failed: " +
                                                   std::string(failure.GetMessageString()));
  }
}

}  // namespace delmesh
