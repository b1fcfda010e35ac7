// mesher/pipeline.cpp: mesh_skin(), the stages of Cheng & Shi 2004 §4.1
// "Algorithm" in order (skin, Morse–Smale complex, sweep, local refinement,
// angle improvement, check) or the baseline's (skin, growth, refinement,
// check), timed one by one.
// Notes: papers/mesher/pipeline.md
#include "mesher/pipeline.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <future>
#include <map>
#include <memory>
#include <numeric>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "core/errors.h"
#include "core/parallel.h"
#include "core/stage_clock.h"
#include "geometry/kernel/predicates.h"
#include "morse/critical_points.h"
#include "skin/molecule_io.h"
#include "skin/singular_skin.h"
#include "skin/skin_measures.h"
#include "skin/skin_surface.h"
#include "skin/vertex_data.h"

namespace skinmesh::mesher {

namespace {

/// The output arrays of a MeshResult that write_output() fills, in its order.
enum class OutputPart {
  kFaces,  ///< triangles (the half-edges, edges and faces go back after)
  kCells,  ///< per vertex the position, the mixed cell, its dimension and the atom
};
/// The parts write_output() makes. The normals and rho are made from the
/// cells after the check, which reads neither (fill_normals_and_rho()): the
/// check's peak does not hold them.
constexpr std::array<OutputPart, 2> kOutputParts{OutputPart::kFaces, OutputPart::kCells};

/// Calls size(array, n) on the output arrays of `part` in `res`, with
/// n = `vertices` for per-vertex arrays and `triangles` for the triangles.
template <class Size>
void size_part(OutputPart part, std::size_t vertices, std::size_t triangles, MeshResult& res, Size&& size) {
  switch (part) {
    case OutputPart::kFaces:
      size(res.mesh.triangles, triangles);
      break;
    case OutputPart::kCells:
      size(res.mesh.positions, vertices);
      size(res.vertex_cells, vertices);
      size(res.vertex_data.patch, vertices);
      size(res.vertex_data.atom, vertices);
      break;
  }
}

/// A block of a half-edge mesh's vertex slots [begin, end) and the output
/// index of its first vertex not deleted: the per-vertex parts of the output
/// are written block by block on the threads, so one large part (a glued
/// decomposed mesh) does not write on one thread.
struct VertexBlock {
  std::size_t mesh, begin, end, out;
};

/// The vertex blocks of `meshes[first, last)`, in order, the first output
/// index of meshes[g] being vbase[g]. Deleted vertices are left out, the
/// others keep their order (vertices() skips deleted elements in index order,
/// the order of a compaction: no garbage_collection(), which would move every
/// property array once more).
std::vector<VertexBlock> vertex_blocks(const std::vector<geometry::SurfaceMesh*>& meshes, std::size_t first,
                                       std::size_t last, const std::vector<std::size_t>& vbase, int threads) {
  constexpr std::size_t kVertexGrain = 1 << 16;  // [chosen] many evaluations per block, few blocks
  std::vector<VertexBlock> blocks;
  for (std::size_t g = first; g < last; ++g)
    for (std::size_t b = 0; b < meshes[g]->vertices_size(); b += kVertexGrain)
      blocks.push_back({g, b, std::min(meshes[g]->vertices_size(), b + kVertexGrain), 0});
  std::vector<std::size_t> live(blocks.size(), 0);
  parallel_for(blocks.size(), threads, 1, [&](std::size_t k) {
    const geometry::SurfaceMesh& m = *meshes[blocks[k].mesh];
    for (std::size_t v = blocks[k].begin; v < blocks[k].end; ++v)
      live[k] += m.is_deleted(geometry::Vertex(static_cast<Index>(v))) ? 0 : 1;
  });
  for (std::size_t k = 0; k < blocks.size(); ++k)
    blocks[k].out =
        k > 0 && blocks[k - 1].mesh == blocks[k].mesh ? blocks[k - 1].out + live[k - 1] : vbase[blocks[k].mesh];
  return blocks;
}

/// Writes the per-vertex `part` (kCells) of the vertices of
/// `block` of `mesh`, a closed SurfaceMesh of the skin, into `res` (its arrays
/// already sized).
void write_vertex_part(const skin::SkinSurface& skin, const geometry::SurfaceMesh& mesh, OutputPart part,
                       const VertexBlock& block, MeshResult& res) {
  std::size_t i = block.out;
  const auto each = [&](auto&& write) {
    for (std::size_t k = block.begin; k < block.end; ++k)
      if (const geometry::Vertex v(static_cast<Index>(k)); !mesh.is_deleted(v)) write(v, i++);
  };
  switch (part) {
    case OutputPart::kCells: {
      const auto cell = mesh.get_vertex_property(skin::kVertexCell);
      each([&](geometry::Vertex v, std::size_t j) {
        res.mesh.positions[j] = mesh.position(v);
        res.vertex_cells[j] = cell[v];
        res.vertex_data.patch[j] = skin.mixed_complex().simplex(cell[v]).dim;
        res.vertex_data.atom[j] = static_cast<std::int32_t>(skin.atom_of(cell[v], mesh.position(v)));
      });
      break;
    }
    case OutputPart::kFaces:
      break;  // per mesh (write_output)
  }
}

/// Gives back the cells and planes that the previous stage's walks made,
/// between the stages after the sweep. Each stage makes again what it reads
/// (bit for bit the same; the output reads the cells' simplices only), so
/// what the sweep and the refinement only crossed does not stay beside every
/// later stage's arrays (papers/decompose/history.md, "The made cells
/// between the stages").
void release_made_cells(const skin::SkinSurface& skin) { skin.mixed_complex().release_made(); }

/// Writes the output of the closed SurfaceMeshes of the skin `meshes`, one
/// after the other, into res.mesh (positions, triangles), res.vertex_data
/// (atom, mixed-cell dimension) and res.vertex_cells, and frees the meshes
/// (the normals and rho follow the check: fill_normals_and_rho()). The
/// meshes go in windows of `threads`, part by part (OutputPart): an array of
/// the output is sized (and so touched) only once the arrays of the
/// half-edge meshes that the previous part read have gone back, so the
/// output grows as the half-edge meshes shrink instead of both being whole at
/// once. The triangles are written one mesh per thread, the per-vertex parts
/// in blocks of vertices on the threads (vertex_blocks()); every value is the
/// one a single loop writes.
void write_output(const skin::SkinSurface& skin, const std::vector<geometry::SurfaceMesh*>& meshes, int threads,
                  MeshResult& res) {
  const std::size_t n = meshes.size();
  std::vector<std::size_t> vbase(n + 1, 0), fbase(n + 1, 0);
  for (std::size_t g = 0; g < n; ++g) {
    vbase[g + 1] = vbase[g] + meshes[g]->n_vertices();
    fbase[g + 1] = fbase[g] + meshes[g]->n_faces();
  }
  for (OutputPart part : kOutputParts)
    size_part(part, vbase[n], fbase[n], res, [](auto& a, std::size_t k) { a.reserve(k); });
  const auto window = static_cast<std::size_t>(std::max(threads, 1));
  for (std::size_t w = 0; w < n; w += window) {
    const std::size_t end = std::min(n, w + window);
    const std::vector<VertexBlock> blocks = vertex_blocks(meshes, w, end, vbase, threads);
    for (OutputPart part : kOutputParts) {
      size_part(part, vbase[end], fbase[end], res, [](auto& a, std::size_t k) { a.resize(k); });
      if (part == OutputPart::kFaces) {
        parallel_for(end - w, threads, 1, [&](std::size_t i) {
          meshes[w + i]->write_indexed_triangles(res.mesh.triangles, vbase[w + i], fbase[w + i]);
          meshes[w + i]->release_faces();
        });
      } else {
        parallel_for(blocks.size(), threads, 1,
                     [&](std::size_t k) { write_vertex_part(skin, *meshes[blocks[k].mesh], part, blocks[k], res); });
      }
    }
    for (std::size_t g = w; g < end; ++g) *meshes[g] = geometry::SurfaceMesh();
  }
}

/// The normals and rho of res.mesh's vertices, from res.vertex_cells and the
/// positions (MixedComplex::unit_normal and rho: bit for bit what
/// skin::VertexNormals and VertexRhos read on the half-edge mesh), in blocks
/// of vertices on the threads, if the output has its cells and not yet its
/// normals (a sweep's output); else nothing.
void fill_normals_and_rho(const skin::SkinSurface& skin, const skin::RunContext& run, MeshResult& res) {
  const std::size_t nv = res.mesh.positions.size();
  if (nv == 0 || res.vertex_cells.size() != nv || !res.mesh.normals.empty()) return;
  res.mesh.normals.resize(nv);
  res.vertex_data.rho.resize(nv);
  constexpr std::size_t kGrain = 1 << 16;  // [chosen] as vertex_blocks()
  const skin::MixedComplex& mc = skin.mixed_complex();
  parallel_for((nv + kGrain - 1) / kGrain, run.threads, 1, [&](std::size_t b) {
    for (std::size_t j = b * kGrain, end = std::min(nv, j + kGrain); j < end; ++j) {
      res.mesh.normals[j] = mc.unit_normal(res.vertex_cells[j], res.mesh.positions[j]);
      res.vertex_data.rho[j] = mc.rho(res.vertex_cells[j], res.mesh.positions[j]);
    }
  });
}

/// mesh_skin() on points already in their local frame.
MeshResult mesh_skin_local(const std::vector<geometry::WeightedPoint>& points, const MeshOptions& options,
                           const Vec3& centre);

/// An error message that names positions, with the frame they are given in.
std::string in_frame(const std::string& what, const Vec3& centre) {
  if (centre == Vec3::Zero() || what.find('(') == std::string::npos) return what;
  char buf[160];
  std::snprintf(buf, sizeof buf, " [positions relative to the frame centre (%.10g %.10g %.10g) Å]", centre.x(),
                centre.y(), centre.z());
  return what + buf;
}

/// What every stage of the run agrees on, from `options`: C and Q, the
/// threads, the progress reports; the pipeline owns its skin, so the stages
/// may give back the complex's made cells.
skin::RunContext run_context(const MeshOptions& options) {
  skin::RunContext run;
  run.size = options.size;
  run.threads = thread_count(options.threads);
  run.progress = options.progress;
  run.release_made_cells = true;
  return run;
}

}  // namespace

verify::SkinCheckReport check_stored_positions(const skin::SkinSurface& skin, const geometry::IndexedMesh& mesh,
                                               const Vec3& to_input, const Vec3& centre,
                                               const geometry::PositionStorage& storage,
                                               verify::SkinCheckOptions options, const skin::RunContext& run,
                                               double& displacement) {
  geometry::IndexedMesh stored;
  stored.triangles = mesh.triangles;
  stored.positions.resize(mesh.positions.size());
  double moved = 0;
  for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
    const Vec3 world = mesh.positions[v] + to_input;  // for the pipeline's mesh, as mesh_skin() brings it back
    const Vec3 p = storage.stored(world);
    moved = std::max(moved, (p - world).norm());
    stored.positions[v] = p - centre;
  }
  // The exact positions passed within max_vertex_distance; the stored ones
  // are at most `moved` farther (plus the frame's translation, a few units
  // in the last place).
  options.max_vertex_distance += moved * (1 + 1e-6);
  options.check_size_conditions = false;
  options.check_restricted_delaunay = false;
  displacement = moved;
  return verify::check_skin_mesh(skin, stored, options, run);
}

std::vector<std::string> MeshResult::problems() const {
  std::vector<std::string> out = check.problems;
  if (stored_check)
    for (const std::string& p : stored_check->problems) out.push_back("as stored (" + stored_as + "): " + p);
  return out;
}

MeshResult mesh_skin(const std::vector<geometry::WeightedPoint>& input_points, const MeshOptions& options) {
  if (options.algorithm == Algorithm::Dynamic) dynamic::validate(options.dynamic);
  // Every stage works in the local frame of the points (their bounding-box
  // centre at the origin); the output mesh is translated back at the end.
  const Vec3 centre = skin::local_frame_centre(input_points);
  try {
    MeshResult res = mesh_skin_local(skin::translated(input_points, centre), options, centre);
    res.frame_centre = centre;
    res.static_fallback = in_frame(res.static_fallback, centre);
    for (Vec3& p : res.mesh.positions) p += centre;
    for (double& c : res.cut_heights) c += options.height_direction.normalized().dot(centre);
    for (decompose::DroppedCut& d : res.dropped_cuts) {
      d.height += options.height_direction.normalized().dot(centre);
      d.why = in_frame(d.why, centre);
    }
    return res;
  } catch (const TopologyError& e) {
    throw TopologyError(in_frame(e.what(), centre));
  } catch (const GeometryError& e) {
    throw GeometryError(in_frame(e.what(), centre));
  }
}

namespace {

/// The calling thread's predicate counts since `before`.
geometry::PredicateStats predicates_since(const geometry::PredicateStats& before) {
  const geometry::PredicateStats now = geometry::predicate_stats();
  auto diff = [](geometry::PredicateCounters a, const geometry::PredicateCounters& b) {
    a.calls -= b.calls;
    a.exact -= b.exact;
    a.sos -= b.sos;
    return a;
  };
  geometry::PredicateStats d;
  d.orient2d = diff(now.orient2d, before.orient2d);
  d.orient3d = diff(now.orient3d, before.orient3d);
  d.power_test = diff(now.power_test, before.power_test);
  return d;
}

/// The sum of two angle improvements' counts (passes and kappa: the larger;
/// skipped: either; the smallest angles before and after: the smaller).
void add_angle_stats(refine::AngleImprovementStats& a, const refine::AngleImprovementStats& b) {
  a.low_triangles += b.low_triangles;
  a.passes = std::max(a.passes, b.passes);
  a.attempts += b.attempts, a.moves += b.moves, a.refused += b.refused;
  a.refused_orientation += b.refused_orientation, a.refused_rdt += b.refused_rdt;
  a.refused_intersection += b.refused_intersection;
  a.refused_L += b.refused_L, a.refused_U += b.refused_U;
  a.skipped = a.skipped || b.skipped;
  a.min_angle_before_deg = std::min(a.min_angle_before_deg, b.min_angle_before_deg);
  a.min_angle_after_deg = std::min(a.min_angle_after_deg, b.min_angle_after_deg);
  a.kappa = std::max(a.kappa, b.kappa);
}

/// run(g) for every group g in [0, n) (n >= 1) on up to `threads` threads,
/// in windows of `threads` groups taken in `order` (largest first), with
/// between() after each window, and the results joined in group order with
/// add(sum, next).
template <class Stats, class Run, class Add, class Between>
Stats per_group(const std::vector<std::size_t>& order, int threads, Run&& run, Add&& add, Between&& between) {
  const std::size_t n = order.size(), window = static_cast<std::size_t>(std::max(threads, 1));
  std::vector<Stats> each(n);
  for (std::size_t w = 0; w < n; w += window) {
    const std::size_t end = std::min(n, w + window);
    parallel_for(end - w, threads, 1, [&](std::size_t i) { each[order[w + i]] = run(order[w + i]); });
    between();
  }
  Stats sum = each[0];
  for (std::size_t g = 1; g < n; ++g) add(sum, each[g]);
  return sum;
}

/// Stages 4, 4b and the output for the parts the sweep handed back: one
/// closed mesh (one sweep, or the slabs glued), or the groups of whole skin
/// components swept on their own (decompose::DecomposedSweep::groups). Each
/// part is refined and angle-improved on its own, and the output meshes are
/// joined in part order, each written straight into its place in res.mesh
/// and its half-edge mesh freed at once. No step reads another part's mesh;
/// the check, which reads the whole mesh, still tests [L], [U], the
/// restricted Delaunay property, the angles and the embedding across parts.
/// On every input tried the groups give the glued path's mesh in another
/// order (papers/decompose/history.md, "Groups to the end"). The parts run
/// on the threads, one each, unless one holds more than half of the
/// triangles (always so for one part): then one after the other, each with
/// every thread for the refinement's scans. Neither choice changes the mesh,
/// which depends on the parts only. The observers of whole stages see the
/// mesh when there is one part (they make the sweep glue its groups).
/// `seams`: per part, the faces where its refinement starts
/// (refine::refine_seams(): a part glued from regions refined already), or
/// empty for the whole part (refine::refine_mesh()); empty: every part whole.
void finish_parts(const skin::SkinSurface& skin, const MeshOptions& options, const skin::RunContext& run,
                  StageClock& clock, std::vector<geometry::SurfaceMesh*> parts,
                  const std::vector<std::vector<geometry::Face>>& seams, MeshResult& res) {
  const int threads = run.threads;
  const std::size_t n = parts.size();
  std::size_t faces = 0, largest = 0;
  for (const geometry::SurfaceMesh* m : parts) {
    faces += m->n_faces();
    largest = std::max(largest, m->n_faces());
  }
  const bool one_large = 2 * largest > faces;
  const int outer = one_large ? 1 : threads, inner = one_large ? threads : 1;
  // The parts in windows, largest first (ties in part order), the cells
  // made by a window given back before the next: the made cells of every
  // part do not stay beside every part's mesh. The order and the windows
  // change no mesh.
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return parts[a]->n_faces() > parts[b]->n_faces(); });
  const auto release = [&skin, &run] {
    if (run.release_made_cells) release_made_cells(skin);
  };
  const auto stage_end = [&](const char* stage) {
    if (options.observers.stage_end && n == 1) options.observers.stage_end(stage, skin, *parts[0]);
  };
  if (options.refine) {
    clock.begin("refine");
    const skin::RunContext part_run = run.with_threads(inner);
    res.refinement = per_group<refine::RefineStats>(
        order, outer,
        [&](std::size_t g) {
          return g < seams.size() && !seams[g].empty()
                     ? refine::refine_seams(skin, *parts[g], seams[g], options.refinement, part_run)
                     : refine::refine_mesh(skin, *parts[g], options.refinement, part_run);
        },
        refine::add_refine_stats, release);
    stage_end("refine");
    clock.end("refine");
    // 4b. Angle improvement (not in the paper; papers/refine/angle_improvement.md).
    if (options.improve_angles) {
      clock.begin("angles");
      res.angle_improvement = per_group<refine::AngleImprovementStats>(
          order, threads,
          [&](std::size_t g) { return refine::improve_angles(skin, *parts[g], options.angle_improvement, run); },
          add_angle_stats, release);
      stage_end("angles");
      clock.end("angles");
    }
  }
  // The check reads res.mesh: the half-edge meshes go back part by part as
  // the output is written.
  release();  // the only release here when the refinement is off
  write_output(skin, parts, threads, res);
  if (options.observers.memory_released) options.observers.memory_released();
  clock.end("output");
}

/// Stage 2: the critical points and the Morse–Smale complex (§3), checked
/// against the Euler characteristic of the skin from its dual complex
/// (res.expected_topology, res.critical and res.live filled), the observer
/// of the stage called.
std::unique_ptr<morse::MorseSmaleComplex> morse_stage(const skin::SkinSurface& skin, const MeshOptions& options,
                                                      const skin::RunContext& run, MeshResult& res) {
  // The dual complex (for the Euler characteristic and the check) needs only
  // the skin: with two threads it is computed beside the Morse–Smale complex,
  // on every thread as well (alone on one it outlasted the Morse–Smale
  // complex by half: papers/decompose/history.md, "Groups to the end").
  const int threads = run.threads;
  std::future<skin::SkinTopology> topology;
  if (threads >= 2)
    topology = std::async(std::launch::async,
                          [&skin, threads] { return skin::dual_complex_topology(skin.mixed_complex(), threads); });
  auto ms = std::make_unique<morse::MorseSmaleComplex>(
      morse::build_morse_smale_complex(skin, options.height_direction, options.morse, run));
  res.expected_topology = topology.valid() ? topology.get() : skin::dual_complex_topology(skin.mixed_complex());
  res.critical = morse::count_critical_points(ms->critical);
  res.live = ms->live_count();
  if (res.critical.euler() != res.expected_topology.euler_skin())
    throw TopologyError("Morse count " + std::to_string(res.critical.euler()) +
                        " differs from the expected Euler characteristic " +
                        std::to_string(res.expected_topology.euler_skin()));
  if (options.observers.morse) options.observers.morse(skin, *ms);
  return ms;
}

/// The slab files of options.region_files whose fingerprint is `fingerprint`
/// and whose slabs are slabs of `cuts` cuts, by slab; InputError otherwise.
std::map<decompose::SlabKey, decompose::SlabOutcome> given_regions(const MeshOptions& options,
                                                                   std::uint64_t fingerprint, std::size_t cuts) {
  std::map<decompose::SlabKey, decompose::SlabOutcome> swept;
  const std::vector<decompose::SlabKey> slabs = decompose::slabs_between(cuts);
  for (const std::string& path : options.region_files) {
    decompose::RegionFile file = decompose::read_region(path);
    if (file.fingerprint != fingerprint)
      throw InputError(path, 0, "the region belongs to other points or options than the cuts file");
    if (std::find(slabs.begin(), slabs.end(), file.slab) == slabs.end())
      throw InputError(path, 0, "the region is no slab of the cuts file's cuts");
    if (!swept.emplace(file.slab, std::move(file.outcome)).second)
      throw InputError(path, 0, "a second file of the same slab");
  }
  return swept;
}

/// Stages 2–4b of Cheng & Shi: the Morse–Smale complex, the sweep, the local
/// refinement and the angle improvement; fills res.mesh.
void run_sweep(const skin::SkinSurface& skin, const MeshOptions& options, const skin::RunContext& run,
               StageClock& clock, MeshResult& res) {
  // 2. Critical points and the Morse–Smale complex (§3).
  clock.begin("morse");
  std::unique_ptr<morse::MorseSmaleComplex> ms = morse_stage(skin, options, run, res);
  // The cut curves are traced from seeds on the integral lines: before
  // their polylines go. A decomposition over processes reads them instead.
  std::vector<decompose::Cut> cuts;
  std::map<decompose::SlabKey, decompose::SlabOutcome> given;
  if (options.cuts_file.empty()) {
    cuts = decompose::choose_cuts(skin, *ms, options.decomposition, options.sweep, run);
  } else {
    decompose::CutsFile file = decompose::read_cuts(options.cuts_file);
    const std::uint64_t fingerprint = decomposition_fingerprint(skin.points(), options);
    if (file.fingerprint != fingerprint)
      throw InputError(options.cuts_file, 0,
                       "the cuts belong to other points or options than this run's (give `skinmesh cuts`, `region` and "
                       "`mesh` the same input and options)");
    cuts = std::move(file.cuts);
    given = given_regions(options, fingerprint, cuts.size());
  }
  // The sweep reads the critical points, their protecting spheres and which
  // are live, not the integral lines' polylines (their ends stay for
  // arc_end()): their memory goes back before the sweep, the stage of the
  // peak.
  for (morse::IntegralLine& line : ms->lines)
    std::vector<Vec3>().swap(line.points), std::vector<Index>().swap(line.cells);
  // What the Morse stage made of the cells and planes (the integral lines'
  // walks, the cut curves) goes back: the mesher's walks need a few percent
  // of the cells (papers/decompose/history.md, "Cells and planes made on
  // first use") and make theirs again, bit for bit the same.
  skin.mixed_complex().release_made();
  // What the skin and Morse stages freed (their work arrays, 4 MB on
  // maltoporin) would stay resident under the sweep's peak: the program may
  // give it back (the library makes no process-wide call).
  if (options.observers.memory_released) options.observers.memory_released();
  clock.end("morse");

  // 3. The sweep (§4.1, §4.2).
  clock.begin("sweep");
  decompose::DecompositionOptions decomposition = options.decomposition;
  // The groups of components are refined on their own unless someone
  // watches the whole mesh between the stages.
  decomposition.glue_groups = options.observers.stage_end || options.refinement.observer;
  // The regions are refined on the threads before the glue unless someone
  // watches the refinement or the mesh between the stages.
  decomposition.refine_regions = options.refine && !options.observers.stage_end && !options.refinement.observer;
  decomposition.refinement = options.refinement;
  decompose::DecomposedSweep decomposed =
      decompose::sweep_decomposed(skin, *ms, cuts, decomposition, options.sweep, run, std::move(given));
  front::SweepResult& swept = decomposed.sweep;
  res.sweep = swept.stats;
  res.slabs = decomposed.cut_heights.size() + 1;
  res.cut_heights = std::move(decomposed.cut_heights);
  res.cut_balls = std::move(decomposed.cut_balls);
  res.dropped_cuts = std::move(decomposed.dropped);
  res.decomposition_costs = std::move(decomposed.costs);
  res.components_fallback = std::move(decomposed.components_fallback);
  if (options.observers.stage_end) options.observers.stage_end("sweep", skin, swept.mesh);
  ms.reset();  // not needed any more: its memory goes back before the refinement and the check
  clock.end("sweep");
  // 4, 4b and the output (§4.3), over the parts: the glued mesh, or each
  // group of components.
  std::vector<geometry::SurfaceMesh*> parts;
  std::vector<std::vector<geometry::Face>> seams;
  if (decomposed.groups.empty()) {
    parts.push_back(&swept.mesh);
    seams.push_back(std::move(decomposed.seams));
  }
  for (front::SweepResult& g : decomposed.groups) parts.push_back(&g.mesh);
  finish_parts(skin, options, run, clock, std::move(parts), seams, res);
  // The regions' operations count with the glued mesh's (their refusals
  // and violations left are the pass over the glued mesh's to take up).
  res.refinement.flips += decomposed.region_refinement.flips;
  res.refinement.contractions += decomposed.region_refinement.contractions;
  res.refinement.insertions += decomposed.region_refinement.insertions;
}

/// Stage 5: the skin-aware check of res.mesh, timed on `clock`.
/// The verifier's options of stage 5 for res.mesh: options.checks with the
/// run's expected topology, and the mesher's cell of every vertex, where the
/// check's walks start.
verify::SkinCheckOptions check_options_of(const MeshOptions& options, const MeshResult& res) {
  verify::SkinCheckOptions check_options = options.checks;
  if (!check_options.expected_topology) check_options.expected_topology = res.expected_topology;
  if (res.shells) {  // the kept shells of a mesh whose every shell the check passed
    check_options.expected_topology = skin::kept_topology(*check_options.expected_topology, *res.shells);
    check_options.expected_component_euler = res.shells->kept_euler;
  }
  if (res.vertex_cells.size() == res.mesh.positions.size()) check_options.vertex_cells = res.vertex_cells;
  return check_options;
}

void run_check(const skin::SkinSurface& skin, const MeshOptions& options, const skin::RunContext& run,
               StageClock& clock, MeshResult& res) {
  clock.begin("check");
  res.check = verify::check_skin_mesh(skin, res.mesh, check_options_of(options, res), run);
  res.checked = true;
  clock.end("check");
}

/// Stage 5b: the check of res.mesh's positions as options.stored_positions
/// stores them, on `clock` (MeshOptions::stored_positions). `centre` is the
/// local frame's centre: files hold positions in the input's frame.
void run_stored_check(const skin::SkinSurface& skin, const MeshOptions& options, const skin::RunContext& run,
                      const Vec3& centre, StageClock& clock, MeshResult& res) {
  clock.begin("stored check");
  res.stored_check = check_stored_positions(skin, res.mesh, centre, centre, options.stored_positions,
                                            check_options_of(options, res), run, res.stored_displacement);
  res.stored_as = options.stored_positions.describe();
  clock.end("stored check");
}

/// The whole-skin fallback: res's sweep results are replaced by the static
/// baseline's mesh of `skin` (its stages timed on `clock`), and `why` is
/// recorded. The baseline samples the final skin and refines the restricted
/// Delaunay triangulation of the sample until [L], [U] and the restricted
/// Delaunay property hold, which needs neither the Morse–Smale complex nor a
/// front (papers/mesher/pipeline.md, "The whole-skin fallback").
void remesh_static(const skin::SkinSurface& skin, const MeshOptions& options, const skin::RunContext& run,
                   StageClock& clock, MeshResult& res, std::string why) {
  MeshResult fresh;
  fresh.algorithm = Algorithm::Dynamic;
  fresh.static_fallback = std::move(why);
  fresh.expected_topology = skin::dual_complex_topology(skin.mixed_complex(), run.threads);
  dynamic::DynamicOptions static_options = options.dynamic;
  static_options.growth = false;
  static_options.observer = nullptr;
  const geometry::PredicateStats predicates_before = geometry::predicate_stats();
  fresh.mesh = dynamic::mesh_dynamic(skin, run.size, static_options, clock, fresh.dynamic, fresh.vertex_data);
  fresh.dynamic.predicates = predicates_since(predicates_before);
  res = std::move(fresh);
  if (options.observers.memory_released) options.observers.memory_released();
}

MeshResult mesh_skin_local(const std::vector<geometry::WeightedPoint>& points, const MeshOptions& options,
                           const Vec3& centre) {
  MeshResult res;
  res.algorithm = options.algorithm;
  StageClock clock(options.progress);
  const bool dynamic = options.algorithm == Algorithm::Dynamic;
  const geometry::PredicateStats predicates_before = geometry::predicate_stats();
  const skin::RunContext run = run_context(options);

  // 1. The skin: regular triangulation and mixed complex (§2.1).
  clock.begin("skin");
  const skin::SkinSurface skin(points, run.threads);
  skin::require_non_singular(skin, run.threads);
  // The whole-skin fallback's stages are timed on their own clock and listed
  // after the others as "fallback <stage>".
  StageClock::Progress fallback_progress;
  if (options.progress)
    fallback_progress = [&options](const std::string& stage, double f) { options.progress("fallback " + stage, f); };
  StageClock fallback_clock(fallback_progress);
  // The sweep's debugging stops (max_steps, the paranoid fold check, the
  // partial dump) are errors the user asked to see.
  const bool may_fall_back = !dynamic && options.static_fallback && options.sweep.max_steps < 0 &&
                             !options.sweep.paranoid && options.sweep.dump_path.empty();
  if (dynamic) {
    res.expected_topology = skin::dual_complex_topology(skin.mixed_complex(), run.threads);
    clock.end("skin");
    res.mesh = dynamic::mesh_dynamic(skin, run.size, options.dynamic, clock, res.dynamic, res.vertex_data);
    res.dynamic.predicates = predicates_since(predicates_before);
    if (options.observers.memory_released) options.observers.memory_released();
  } else {
    clock.end("skin");
    std::string failure;
    try {
      run_sweep(skin, options, run, clock, res);
    } catch (const TopologyError& e) {
      if (!may_fall_back) throw;
      failure = std::string("topology: ") + e.what();
    } catch (const GeometryError& e) {
      if (!may_fall_back) throw;
      failure = std::string("geometry: ") + e.what();
    }
    if (!failure.empty()) {
      clock.end("abandoned");  // the time the failed stages took
      remesh_static(skin, options, run, fallback_clock, res, "the sweep failed: " + failure);
    }
  }

  // 5. The check. A refined sweep mesh that fails it is replaced (without
  // the refinement [L], [U] and the restricted Delaunay property may fail by
  // design, and the user asked for that mesh).
  if (options.check) {
    run_check(skin, options, run, res.static_fallback.empty() ? clock : fallback_clock, res);
    if (!res.check.ok() && may_fall_back && options.refine && res.static_fallback.empty()) {
      const std::string first = res.check.problems.empty() ? "" : ": " + res.check.problems.front();
      remesh_static(skin, options, run, fallback_clock, res, "the sweep's mesh failed its check" + first);
      run_check(skin, options, run, fallback_clock, res);
    }
  }
  // The shells the user keeps, once the mesh of them all is checked.
  if (options.shells.selects())
    res.shells = skin::select_shells(res.mesh, &res.vertex_data, &res.vertex_cells, options.shells);
  if (options.check && res.check.ok() && options.stored_positions.lossy())
    run_stored_check(skin, options, run, centre, res.static_fallback.empty() ? clock : fallback_clock, res);
  if (res.vertex_cells.size() == res.mesh.positions.size() && res.mesh.normals.empty()) {
    fill_normals_and_rho(skin, run, res);
    clock.end("normals");
  }
  if (options.check) std::vector<Index>().swap(res.vertex_cells);
  // The exact per-atom areas read every cell of this skin: the same skin that
  // skin::atom_areas() builds from the points (the same local frame), so the
  // same values, without a second skin beside the mesh.
  if (options.skin_atom_areas) {
    clock.begin("atom_areas");
    res.skin_atom_areas = skin::atom_areas(skin, run.threads);
    skin.mixed_complex().release_made();
    clock.end("atom_areas");
  }
  res.seconds = clock.seconds();
  for (const auto& [stage, t] : fallback_clock.seconds()) res.seconds.emplace_back("fallback " + stage, t);
  return res;
}

}  // namespace

const char* algorithm_name(Algorithm algorithm) { return algorithm == Algorithm::Dynamic ? "dynamic" : "sweep"; }

Algorithm algorithm_named(const std::string& name) {
  if (name == "sweep") return Algorithm::Sweep;
  if (name == "dynamic") return Algorithm::Dynamic;
  throw std::invalid_argument("unknown algorithm '" + name + "' (sweep or dynamic)");
}

MeshResult mesh_skin(const skin::Molecule& molecule, const MeshOptions& options) {
  if (!(options.probe_radius >= 0 && options.probe_radius <= skin::kMaxRadius))
    throw std::invalid_argument("the probe radius must lie in [0, " + std::to_string(skin::kMaxRadius) + "] Å");
  return mesh_skin(skin::weighted_points(molecule, options.probe_radius), options);
}

namespace {

/// FNV-1a, 64 bits, over the bytes of values fed one by one.
class Fingerprint {
 public:
  template <class T>
  void add(const T& value) {
    static_assert(std::is_arithmetic_v<T>, "Fingerprint: numbers only (a struct's padding has no value)");
    const auto* bytes = reinterpret_cast<const unsigned char*>(&value);
    for (std::size_t i = 0; i < sizeof(T); ++i) hash_ = (hash_ ^ bytes[i]) * 0x100000001b3ULL;
  }
  void add(const Vec3& v) { add(v.x()), add(v.y()), add(v.z()); }
  std::uint64_t value() const { return hash_; }

 private:
  std::uint64_t hash_ = 0xcbf29ce484222325ULL;
};

/// `fn(skin, ms, run)` after stages 1 and 2 on the points in their local
/// frame, as mesh_skin() runs them.
template <class Fn>
auto with_complex(const std::vector<geometry::WeightedPoint>& input_points, const MeshOptions& options, Fn&& fn) {
  const Vec3 centre = skin::local_frame_centre(input_points);
  const skin::RunContext run = run_context(options);
  try {
    const skin::SkinSurface skin(skin::translated(input_points, centre), run.threads);
    skin::require_non_singular(skin, run.threads);
    MeshResult res;
    const std::unique_ptr<morse::MorseSmaleComplex> ms = morse_stage(skin, options, run, res);
    return fn(skin, *ms, run);
  } catch (const TopologyError& e) {
    throw TopologyError(in_frame(e.what(), centre));
  } catch (const GeometryError& e) {
    throw GeometryError(in_frame(e.what(), centre));
  }
}

}  // namespace

std::uint64_t decomposition_fingerprint(const std::vector<geometry::WeightedPoint>& points,
                                        const MeshOptions& options) {
  Fingerprint f;
  f.add(points.size());
  for (const geometry::WeightedPoint& p : points) f.add(p.z), f.add(p.w);
  f.add(options.height_direction);
  f.add(options.size.C), f.add(options.size.Q);
  const morse::MorseSmaleOptions& m = options.morse;
  f.add(m.step_factor), f.add(m.protect_factor), f.add(m.cancel_factor), f.add(m.coincident_factor);
  f.add(m.max_steps), f.add(m.start_offset), f.add(m.arrival_steps), f.add(m.max_step_halvings);
  // The sweep's options that change a region's mesh: a region swept with
  // another (--no-fallback, --no-patch, --max-steps) would not join the others.
  f.add(options.sweep.disc_factor), f.add(options.sweep.patch_fallback), f.add(options.sweep.force_patch_every);
  f.add(options.sweep.max_steps);
  const decompose::DecompositionOptions& d = options.decomposition;
  f.add(d.slabs), f.add(d.atoms_per_slab), f.add(d.atoms_per_root_slab), f.add(d.max_slabs), f.add(d.park_factor),
      f.add(d.window_below);
  f.add(d.window_above), f.add(d.sphere_margin), f.add(d.min_thickness), f.add(d.balance_work);
  f.add(d.search_reach), f.add(d.search_step), f.add(d.detours), f.add(d.detour_fallback), f.add(d.components);
  f.add(d.curves.spacing), f.add(d.curves.trace_step), f.add(d.curves.seed_tolerance), f.add(d.curves.min_sine);
  return f.value();
}

decompose::CutsFile mesh_cuts(const std::vector<geometry::WeightedPoint>& points, const MeshOptions& options) {
  return with_complex(
      points, options,
      [&](const skin::SkinSurface& skin, const morse::MorseSmaleComplex& ms, const skin::RunContext& run) {
        decompose::CutsFile file;
        file.fingerprint = decomposition_fingerprint(skin.points(), options);
        file.cuts = decompose::choose_cuts(skin, ms, options.decomposition, options.sweep, run);
        return file;
      });
}

decompose::RegionFile mesh_region(const std::vector<geometry::WeightedPoint>& points, const MeshOptions& options,
                                  const decompose::CutsFile& cuts, std::size_t slab) {
  const std::vector<decompose::SlabKey> slabs = decompose::slabs_between(cuts.cuts.size());
  if (slab >= slabs.size())
    throw std::invalid_argument("mesh_region: slab " + std::to_string(slab) + " of " + std::to_string(slabs.size()) +
                                " (the cuts make slabs 0 to " + std::to_string(slabs.size() - 1) + ")");
  // The fingerprint is of the points in their local frame, as the skin holds them.
  if (decomposition_fingerprint(skin::translated(points, skin::local_frame_centre(points)), options) !=
      cuts.fingerprint)
    throw InputError("", 0,
                     "the cuts belong to other points or options than this run's (give `skinmesh cuts`, `region` and "
                     "`mesh` the same input and options)");
  return with_complex(
      points, options,
      [&](const skin::SkinSurface& skin, const morse::MorseSmaleComplex& ms, const skin::RunContext& run) {
        decompose::RegionFile file;
        file.fingerprint = cuts.fingerprint;
        file.slab = slabs[slab];
        file.outcome = decompose::sweep_slab(skin, ms, cuts.cuts, file.slab, options.decomposition, options.sweep, run);
        return file;
      });
}

}  // namespace skinmesh::mesher
