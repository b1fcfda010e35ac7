// mesher/pipeline.cpp: mesh_skin(), the stages of Cheng & Shi 2004 §4.1
// "Algorithm" in order (skin, Morse–Smale complex, sweep, local refinement,
// angle improvement, check), timed one by one.
// Notes: papers/mesher/pipeline.md
#include "mesher/pipeline.h"

#include <chrono>
#if defined(__GLIBC__)
#include <malloc.h>  // malloc_trim
#endif
#include <cmath>
#include <cstdio>
#include <future>
#include <memory>
#include <string>
#include <stdexcept>

#include "core/errors.h"
#include "core/parallel.h"
#include "morse/critical_points.h"
#include "skin/singular_skin.h"
#include "skin/molecule_io.h"
#include "skin/skin_surface.h"

namespace skinmesh::mesher {

namespace {

/// The output mesh of a closed SurfaceMesh of the skin: positions, triangles,
/// and per vertex the normal from "v:normal", the atom and the dimension of
/// its mixed cell ("v:cell") and rho ("v:rho"). Deleted elements are left out.
geometry::IndexedMesh output_mesh(const skin::SkinSurface& skin, const geometry::SurfaceMesh& mesh) {
  // No garbage_collection(): to_indexed_mesh() and vertices() skip deleted
  // elements in index order, which is the order the compaction keeps (the same
  // output without moving every property array of the mesh once more).
  geometry::IndexedMesh out = mesh.to_indexed_mesh();
  const auto normal = mesh.get_vertex_property<Vec3>("v:normal");
  const auto cell = mesh.get_vertex_property<Index>("v:cell");
  const auto rho = mesh.get_vertex_property<double>("v:rho");
  out.normals.resize(out.positions.size());
  out.atom.resize(out.positions.size());
  out.rho.resize(out.positions.size());
  out.patch.resize(out.positions.size());
  Index i = 0;
  for (geometry::Vertex v : mesh.vertices()) {
    out.normals[i] = normal[v];
    out.atom[i] = static_cast<std::int32_t>(skin.atom_of(cell[v], mesh.position(v)));
    out.rho[i] = rho[v];
    out.patch[i] = skin.mixed_complex().cell(cell[v]).dim;
    ++i;
  }
  return out;
}

/// Returns the allocator's free pages to the system (glibc: malloc_trim). The
/// sweep frees many small blocks (the collision grids' cells) that the heap
/// would otherwise keep resident through the check, the stage of the peak.
void release_free_memory() {
#if defined(__GLIBC__)
  malloc_trim(0);
#endif
}

/// mesh_skin() on points already in their local frame.
MeshResult mesh_skin_local(const std::vector<geometry::WeightedPoint>& points, const MeshOptions& options);

/// An error message that names positions, with the frame they are given in.
std::string in_frame(const std::string& what, const Vec3& centre) {
  if (centre == Vec3::Zero() || what.find('(') == std::string::npos) return what;
  char buf[160];
  std::snprintf(buf, sizeof buf, " [positions relative to the frame centre (%.10g %.10g %.10g) Å]", centre.x(),
                centre.y(), centre.z());
  return what + buf;
}

/// A stage's options with the size constants every stage must share.
template <class StageOptions>
StageOptions with_size(StageOptions stage_options, const skin::SizeConstants& size) {
  stage_options.size = size;
  return stage_options;
}

}  // namespace

MeshResult mesh_skin(const std::vector<geometry::WeightedPoint>& input_points, const MeshOptions& options) {
  // Every stage works in the local frame of the points (their bounding-box
  // centre at the origin); the output mesh is translated back at the end.
  const Vec3 centre = skin::local_frame_centre(input_points);
  try {
    MeshResult res = mesh_skin_local(skin::translated(input_points, centre), options);
    res.frame_centre = centre;
    for (Vec3& p : res.mesh.positions) p += centre;
    return res;
  } catch (const TopologyError& e) {
    throw TopologyError(in_frame(e.what(), centre));
  } catch (const GeometryError& e) {
    throw GeometryError(in_frame(e.what(), centre));
  }
}

namespace {

MeshResult mesh_skin_local(const std::vector<geometry::WeightedPoint>& points, const MeshOptions& options) {
  using Clock = std::chrono::steady_clock;
  MeshResult res;
  auto t0 = Clock::now();
  auto stage = [&](const char* name) {
    if (options.progress) options.progress(name, 0.0);
  };
  auto lap = [&](const char* name) {
    const auto t1 = Clock::now();
    res.seconds.emplace_back(name, std::chrono::duration<double>(t1 - t0).count());
    t0 = t1;
    if (options.progress) options.progress(name, 1.0);
  };

  // 1. The skin: regular triangulation and mixed complex (§2.1).
  stage("skin");
  const skin::SkinSurface skin(points);
  skin::require_non_singular(skin);
  lap("skin");

  // 2. Critical points and the Morse–Smale complex (§3), checked against the
  //    Euler characteristic of the skin from its dual complex.
  stage("morse");
  // The dual complex (for the Euler characteristic and the check) needs only
  // the skin: with two threads it is computed beside the Morse–Smale complex.
  const int threads = thread_count(options.threads);
  std::future<skin::SkinTopology> topology;
  if (threads >= 2)
    topology = std::async(std::launch::async, [&skin] { return skin::dual_complex_topology(skin.mixed_complex()); });
  morse::MorseSmaleOptions morse_options = options.morse;
  if (morse_options.threads == morse::MorseSmaleOptions{}.threads) morse_options.threads = threads;
  auto ms = std::make_unique<morse::MorseSmaleComplex>(
      morse::build_morse_smale_complex(skin, options.height_direction, morse_options));
  res.expected_topology = topology.valid() ? topology.get() : skin::dual_complex_topology(skin.mixed_complex());
  res.critical = morse::count_critical_points(ms->critical);
  res.live = ms->live_count();
  if (res.critical.euler() != res.expected_topology.euler_skin())
    throw TopologyError("Morse count " + std::to_string(res.critical.euler()) +
                        " differs from the expected Euler characteristic " +
                        std::to_string(res.expected_topology.euler_skin()));
  if (options.observers.morse) options.observers.morse(skin, *ms);
  // The sweep reads the critical points, their protecting spheres and which
  // are live, not the integral lines' polylines (their ends stay for
  // arc_end()): their memory goes back before the sweep, the stage of the
  // peak (7 MB on maltoporin).
  for (morse::IntegralLine& line : ms->lines) std::vector<Vec3>().swap(line.points);
  lap("morse");

  // 3. The sweep (§4.1, §4.2).
  stage("sweep");
  front::SweepOptions sweep_options = with_size(options.sweep, options.size);
  if (!sweep_options.progress) sweep_options.progress = options.progress;
  front::SweepResult swept = front::sweep_mesh(skin, *ms, sweep_options);
  res.sweep = swept.stats;
  if (options.observers.stage_end) options.observers.stage_end("sweep", skin, swept.mesh);
  ms.reset();  // not needed any more: its memory goes back before the refinement and the check
  lap("sweep");

  // 4. The local refinement (§4.3).
  if (options.refine) {
    stage("refine");
    res.refinement = refine::refine_mesh(skin, swept.mesh, with_size(options.refinement, options.size));
    if (options.observers.stage_end) options.observers.stage_end("refine", skin, swept.mesh);
    lap("refine");
    // 4b. Angle improvement (not in the paper; papers/refine/angle_improvement.md).
    if (options.improve_angles) {
      stage("angles");
      res.angle_improvement =
          refine::improve_angles(skin, swept.mesh, with_size(options.angle_improvement, options.size));
      if (options.observers.stage_end) options.observers.stage_end("angles", skin, swept.mesh);
      lap("angles");
    }
  }
  res.mesh = output_mesh(skin, swept.mesh);
  swept.mesh = geometry::SurfaceMesh();  // the check reads res.mesh: free the half-edge mesh first
  release_free_memory();
  lap("output");

  // 5. The check.
  if (options.check) {
    stage("check");
    verify::SkinCheckOptions check_options = with_size(options.checks, options.size);
    if (!check_options.expected_topology) check_options.expected_topology = res.expected_topology;
    if (check_options.threads == verify::SkinCheckOptions{}.threads) check_options.threads = threads;
    res.check = verify::check_skin_mesh(skin, res.mesh, check_options);
    res.checked = true;
    lap("check");
  }
  return res;
}

}  // namespace

MeshResult mesh_skin(const skin::Molecule& molecule, const MeshOptions& options) {
  if (!(options.probe_radius >= 0 && options.probe_radius <= skin::kMaxRadius))
    throw std::invalid_argument("the probe radius must lie in [0, " + std::to_string(skin::kMaxRadius) + "] Å");
  return mesh_skin(skin::weighted_points(molecule, options.probe_radius), options);
}

}  // namespace skinmesh::mesher
