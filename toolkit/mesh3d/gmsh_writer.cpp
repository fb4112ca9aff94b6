// Gmsh .msh writer, format 4.1 (default) or 2.2, ASCII. Each facet marker becomes a
// surface entity with a named physical group (dim 2), each region a volume entity with a
// named physical group (dim 3), so solvers that read physical groups see the CAD face
// and solid names. Physical tags must be positive: marker m > 0 keeps tag m; markers
// <= 0 get fresh tags above the largest positive marker (likewise for regions).
#include <algorithm>
#include <limits>
#include <map>

#include "toolkit/io/text_writer.h"
#include "toolkit/mesh3d/tetra_mesh_writer.h"

namespace delmesh {

namespace {

/// value -> positive tag, in increasing value order.
std::map<int, int> positive_tags(const std::vector<int>& values) {
  std::map<int, int> tags;
  int next = 1;
  for (int v : values) next = std::max(next, v + 1);
  for (int v : values) tags.emplace(v, 0);
  for (auto& [v, tag] : tags) tag = v > 0 ? v : next++;
  return tags;
}

struct Box {
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity());
  Vec3 hi = Vec3::Constant(-std::numeric_limits<double>::infinity());
  void add(const Vec3& p) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
};

}  // namespace

Expected<void> write_gmsh(const std::filesystem::path& path, const TetraMesh& mesh, int version) {
  if (version != 41 && version != 22)
    return make_error(ErrorCode::InvalidOption, "Gmsh format version must be 4.1 or 2.2");
  std::vector<int> regions(mesh.tets.size());
  for (std::size_t i = 0; i < mesh.tets.size(); ++i) regions[i] = mesh.region_of(i);
  std::vector<int> markers = mesh.boundary_markers;
  markers.resize(mesh.boundary_faces.size(), 0);
  const std::map<int, int> region_tag = positive_tags(regions);
  const std::map<int, int> marker_tag = positive_tags(markers);

  TextWriter out(path);
  out.put(version == 41 ? "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n" : "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n");
  out.put("$PhysicalNames\n").line(static_cast<std::uint64_t>(region_tag.size() + marker_tag.size()));
  for (const auto& [m, tag] : marker_tag) out.put("2 ").put(tag).put(" \"").put(marker_label(mesh, m)).put("\"\n");
  for (const auto& [r, tag] : region_tag) out.put("3 ").put(tag).put(" \"").put(region_label(mesh, r)).put("\"\n");
  out.put("$EndPhysicalNames\n");

  if (version == 22) {
    out.put("$Nodes\n").line(static_cast<std::uint64_t>(mesh.points.size()));
    for (std::size_t i = 0; i < mesh.points.size(); ++i)
      out.line(static_cast<std::uint64_t>(i + 1), mesh.points[i].x(), mesh.points[i].y(), mesh.points[i].z());
    out.put("$EndNodes\n$Elements\n").line(static_cast<std::uint64_t>(markers.size() + regions.size()));
    std::uint64_t id = 1;
    for (std::size_t i = 0; i < markers.size(); ++i) {
      const int tag = marker_tag.at(markers[i]);
      const auto& f = mesh.boundary_faces[i];
      out.line(id++, 2, 2, tag, tag, f[0] + 1, f[1] + 1, f[2] + 1);
    }
    for (std::size_t i = 0; i < regions.size(); ++i) {
      const int tag = region_tag.at(regions[i]);
      const auto& t = mesh.tets[i];
      out.line(id++, 4, 2, tag, tag, t[0] + 1, t[1] + 1, t[2] + 1, t[3] + 1);
    }
    out.put("$EndElements\n");
    return out.finish();
  }

  // 4.1: entities (one surface per marker, one volume per region) with bounding boxes.
  std::map<int, Box> surface_box, volume_box;
  for (std::size_t i = 0; i < markers.size(); ++i)
    for (auto v : mesh.boundary_faces[i]) surface_box[marker_tag.at(markers[i])].add(mesh.points[v]);
  for (std::size_t i = 0; i < regions.size(); ++i)
    for (auto v : mesh.tets[i]) volume_box[region_tag.at(regions[i])].add(mesh.points[v]);
  out.put("$Entities\n").line(0, 0, static_cast<std::uint64_t>(surface_box.size()),
                              static_cast<std::uint64_t>(volume_box.size()));
  for (const auto& [tag, box] : surface_box)
    out.line(tag, box.lo.x(), box.lo.y(), box.lo.z(), box.hi.x(), box.hi.y(), box.hi.z(), 1, tag, 0);
  for (const auto& [tag, box] : volume_box)
    out.line(tag, box.lo.x(), box.lo.y(), box.lo.z(), box.hi.x(), box.hi.y(), box.hi.z(), 1, tag, 0);
  out.put("$EndEntities\n");

  // All nodes in one block classified on the first volume (or surface) entity.
  const std::uint64_t n = mesh.points.size();
  out.put("$Nodes\n");
  if (n == 0) {
    out.put("0 0 0 0\n");
  } else {
    const bool on_volume = !volume_box.empty();
    const int entity = on_volume ? volume_box.begin()->first : (surface_box.empty() ? 1 : surface_box.begin()->first);
    out.line(1, n, 1, n).line(on_volume ? 3 : 2, entity, 0, n);
    for (std::uint64_t i = 1; i <= n; ++i) out.line(i);
    for (const auto& p : mesh.points) out.line(p.x(), p.y(), p.z());
  }
  out.put("$EndNodes\n$Elements\n");
  const std::uint64_t total = markers.size() + regions.size();
  out.line(static_cast<std::uint64_t>(surface_box.size() + volume_box.size()), total, total ? 1 : 0, total);
  std::uint64_t id = 1;
  std::map<int, std::vector<std::size_t>> faces_of, tets_of;
  for (std::size_t i = 0; i < markers.size(); ++i) faces_of[marker_tag.at(markers[i])].push_back(i);
  for (std::size_t i = 0; i < regions.size(); ++i) tets_of[region_tag.at(regions[i])].push_back(i);
  for (const auto& [tag, list] : faces_of) {
    out.line(2, tag, 2, static_cast<std::uint64_t>(list.size()));
    for (auto i : list) {
      const auto& f = mesh.boundary_faces[i];
      out.line(id++, f[0] + 1, f[1] + 1, f[2] + 1);
    }
  }
  for (const auto& [tag, list] : tets_of) {
    out.line(3, tag, 4, static_cast<std::uint64_t>(list.size()));
    for (auto i : list) {
      const auto& t = mesh.tets[i];
      out.line(id++, t[0] + 1, t[1] + 1, t[2] + 1, t[3] + 1);
    }
  }
  out.put("$EndElements\n");
  return out.finish();
}

}  // namespace delmesh
