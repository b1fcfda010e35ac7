// mesher/pipeline.h: the program layer — one call meshes a skin with either
// algorithm, the entry point that the command line, Python, the benchmarks,
// the recorder and the tests share. Both algorithms run in the same frame of
// stages: the local frame of the points, the skin and the refusal of
// singular skins, the stopwatch and progress, the output mesh, the check.
// Cheng & Shi 2004 §4.1 "Algorithm" (Algorithm::Sweep): the input is a set of
// weighted points B, the output a triangulation K of the skin F_B; the
// stages are
//   1. skin       the regular triangulation and the mixed complex of B (§2.1)
//   2. morse      the critical points of the height function, the Morse–Smale
//                 complex and its simplification (§3), checked against the
//                 Euler characteristic of the skin (from its dual complex)
//   3. sweep      Algorithm 1: creation, creep, wing, bridge, seal (§4.1, §4.2)
//   4. refine     the local refinement: flips, contractions, insertions (§4.3)
//   4b. angles    vertex moves that raise the smallest angles and keep [L],
//                 [U] and the restricted Delaunay property (not in the paper;
//                 refine/angle_improvement.h)
//   5. check      the skin-aware verifier (verify/skin_mesh_check.h)
// The dynamic-skin baseline (Algorithm::Dynamic, dynamic/dynamic_skin.h)
// replaces stages 2–4b by "growth" (absent in the static variant) and
// "refine".
// Notes: papers/mesher/pipeline.md
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "decompose/decomposed.h"
#include "decompose/region_files.h"
#include "dynamic/dynamic_skin.h"
#include "front/sweep.h"
#include "geometry/io/mesh_io.h"
#include "geometry/kernel/weighted_point.h"
#include "geometry/mesh/indexed_mesh.h"
#include "morse/critical_points.h"
#include "morse/morse_smale_complex.h"
#include "refine/angle_improvement.h"
#include "refine/local_refinement.h"
#include "skin/dual_complex.h"
#include "skin/molecule.h"
#include "skin/shells.h"
#include "skin/size_conditions.h"
#include "skin/vertex_data.h"
#include "verify/skin_mesh_check.h"

namespace skinmesh::mesher {

/// The two meshers of Table 1.
enum class Algorithm {
  Sweep,    ///< the advancing front of Cheng & Shi 2004
  Dynamic,  ///< the dynamic-skin baseline of Cheng, Dey, Edelsbrunner & Sullivan 2001
};

/// "sweep" or "dynamic", as the command line and Python spell them.
const char* algorithm_name(Algorithm algorithm);
/// The algorithm named "sweep" or "dynamic"; std::invalid_argument otherwise.
Algorithm algorithm_named(const std::string& name);

/// Observers of the pipeline's stages, for recorders (trace/trace_recorder.h);
/// an empty one is not called. Everything they see is in the local frame
/// (MeshResult::frame_centre). They must not throw unless the pipeline is to
/// stop, and the pipeline computes the same with or without them.
struct PipelineObservers {
  /// After stage 2, with the skin and the Morse–Smale complex, before the
  /// integral lines' polylines are freed.
  std::function<void(const skin::SkinSurface&, const morse::MorseSmaleComplex&)> morse;
  /// At the end of the sweep, the refinement and the angle improvement
  /// ("sweep", "refine", "angles"), with the half-edge mesh before it is
  /// compacted (deleted elements still present, marked deleted).
  std::function<void(const char* stage, const skin::SkinSurface&, const geometry::SurfaceMesh&)> stage_end;
  /// Called where a stage's working memory has just been freed: after the
  /// Morse stage (its work arrays and the integral lines' polylines), before
  /// the sweep, and once the output mesh is made (the half-edge mesh, the
  /// Morse–Smale complex, the sample freed), before the check, the stage of
  /// the peak. A program may return the allocator's free pages to the system
  /// there; the library makes no process-wide calls.
  std::function<void()> memory_released;
};

/// Options of the whole pipeline, one struct per stage.
struct MeshOptions {
  /// Which mesher runs between the skin and the check.
  Algorithm algorithm = Algorithm::Sweep;
  /// Probe radius (Å) used by the Molecule overload of mesh_skin: atom weight
  /// w = 2 (r + probe)² (Cheng & Shi §2.1; papers/skin/molecule_io.md).
  double probe_radius = 1.4;
  /// C and Q of [L] and [U] (Cheng & Shi §2.2), held here only: every stage
  /// gets them in the run's one skin::RunContext (with `threads` and
  /// `progress`), so that all stages agree.
  skin::SizeConstants size;
  /// Unit height direction of the sweep (§3.1 uses +y; the default is tilted
  /// slightly so that no two atoms are at the same height by accident).
  Vec3 height_direction = morse::default_height_direction();
  /// Stage 2: integral lines, protecting spheres, arc contraction.
  morse::MorseSmaleOptions morse;
  /// Stage 3: the sweep's tuning numbers and debugging aids.
  front::SweepOptions sweep;
  /// Stage 3 decomposed (papers/decompose/README.md): with
  /// decomposition.slabs > 1 the skin is cut at regular heights chosen in
  /// stage 2 (decompose::choose_cuts) and swept slab by slab, the slabs glued
  /// along the shared cut samples (decompose::sweep_decomposed); the stages
  /// after the sweep see one closed mesh as before. Default 0: automatic
  /// (decompose::automatic_slabs: one sweep below 3,750 atoms).
  decompose::DecompositionOptions decomposition;
  /// Stage 3 carried out over several processes (decompose/region_files.h):
  /// a cuts file that mesh_cuts() wrote replaces the cut choice, and the
  /// region files of its slabs that mesh_region() wrote are glued instead of
  /// being swept again (slabs without a file are swept here). Every file
  /// must come from the same points and options (their fingerprint,
  /// decomposition_fingerprint(), is compared; InputError otherwise). The
  /// mesh is the one a single process makes. Empty: the cuts are chosen here.
  std::string cuts_file;
  std::vector<std::string> region_files;
  /// Stage 4: run the local refinement (default). Without it the mesh is
  /// closed, embedded and of the right topology but [L], [U] and the
  /// restricted Delaunay property may fail.
  bool refine = true;
  refine::RefineOptions refinement;
  /// Stage 4b, after the refinement (skipped when `refine` is false): move
  /// the vertices of triangles with small angles on the skin, keeping [L],
  /// [U], the restricted Delaunay property, orientation and embedding
  /// (refine/angle_improvement.h; papers/refine/angle_improvement.md).
  /// Default on; off gives the mesh of the paper's algorithm alone.
  bool improve_angles = true;
  refine::AngleImprovementOptions angle_improvement;
  /// Algorithm::Dynamic: growth or the static variant, the sample's spacing,
  /// the growth schedule, its observer.
  dynamic::DynamicOptions dynamic;
  /// Algorithm::Sweep's last resort (papers/mesher/pipeline.md, "The
  /// whole-skin fallback"): when stages 2–4b throw TopologyError or
  /// GeometryError (the local fallback, sweep.patch_fallback, could not
  /// repair the front), or when the sweep's refined mesh fails its check, the
  /// whole skin is meshed again by the restricted Delaunay refinement of a
  /// sample of the final skin (the baseline's static variant, with
  /// `dynamic`'s other options), which carries its own guarantee;
  /// MeshResult::static_fallback then says why. Default off, so that the
  /// library's callers (the tests, the stress suite, the benchmarks) see the
  /// sweep's own failures: the error is thrown, or the failing mesh
  /// returned. The command line, batch runs and Python turn it on
  /// (`--no-fallback` turns it off there).
  bool static_fallback = false;
  /// Stage 5: verify the mesh (default); the verdict is in MeshResult::check.
  bool check = true;
  /// After the check, the exact skin's area per atom
  /// (MeshResult::skin_atom_areas) from the run's own skin: the values
  /// skin::atom_areas() of the weighted points gives, without building the
  /// skin a second time (stage "atom_areas"; papers/skin/atom_areas.md).
  bool skin_atom_areas = false;
  verify::SkinCheckOptions checks;
  /// How the file the mesh goes to stores positions (skin::position_storage
  /// of its path; default exact). When lossy and the check passed, the check
  /// runs again on the positions as the file will hold them (in the input's
  /// frame, rounded, then brought into the local frame as a reader's check
  /// does): closed, manifold, oriented, exact self-intersections, topology,
  /// angles and distance to the skin (to the largest displacement the
  /// rounding made); [L], [U] and the restricted Delaunay property are
  /// properties of the exact positions (verify::SkinCheckOptions::
  /// check_size_conditions). The verdict is MeshResult::stored_check.
  geometry::PositionStorage stored_positions;
  /// The shells of the skin the mesh keeps (skin/shells.h; default all). The
  /// check (stage 5) verifies the mesh of every shell; the shells left out
  /// are then removed from MeshResult::mesh and its vertex data, and the
  /// stored-positions check expects the kept shells (their count and Euler
  /// characteristics). MeshResult::shells says what was kept.
  skin::ShellSelection shells;
  /// Threads (0: every core of the machine). The mesh and every count in
  /// MeshResult are the same, byte for byte, for every thread count: the
  /// threads run independent computations side by side — the skin's dual
  /// complex beside the Morse–Smale complex, the integral lines of different
  /// saddles, the mesh-only checks beside the skin checks
  /// (papers/bench/profile.md, "Threads").
  int threads = 0;
  /// Called with a stage name ("skin", "morse", "sweep", "refine", "angles",
  /// "growth", "check") and the fraction of it done (0..1); empty: no
  /// reports. The library itself prints nothing.
  std::function<void(const std::string& stage, double fraction)> progress;
  /// Observers of whole stages; the sweep's operations are observed through
  /// sweep.observer, the refinement's through refinement.observer.
  PipelineObservers observers;
};

/// What the pipeline produced and measured.
struct MeshResult {
  /// The algorithm that made the mesh: Algorithm::Dynamic also when the
  /// sweep was asked for and the whole-skin fallback replaced it.
  Algorithm algorithm = Algorithm::Sweep;
  /// Why the sweep's result was replaced by the whole-skin fallback
  /// (MeshOptions::static_fallback), in one line; empty if it was not.
  std::string static_fallback;
  /// The mesh: positions (Å, on the skin), triangles counter-clockwise about
  /// the outward normal, unit outward normals per vertex.
  geometry::IndexedMesh mesh;
  /// The skin's data at the vertices of `mesh`: atom, rho and mixed-cell
  /// dimension, one entry per vertex each (skin/vertex_data.h).
  skin::SkinVertexData vertex_data;
  /// The mixed cell (skin::MixedComplex) holding each vertex of `mesh`, as the
  /// mesher found it: where the check's point location starts. Filled by the
  /// sweep's output and emptied after the check; empty for the baseline.
  std::vector<Index> vertex_cells;
  /// Critical points of the height function before and after simplification
  /// (Algorithm::Sweep; zero for the baseline).
  morse::MorseCount critical, live;
  /// Topology of the skin computed from the dual complex (independent of the mesh).
  skin::SkinTopology expected_topology;
  front::SweepStats sweep;
  /// Slabs the sweep was decomposed into (MeshOptions::decomposition; 1: one
  /// sweep, 0: the baseline).
  std::size_t slabs = 0;
  /// The cut heights between the slabs (Å, e·x in the input's coordinates,
  /// e = MeshOptions::height_direction), increasing; empty for one sweep.
  std::vector<double> cut_heights;
  /// Per cut, the balls about critical points it passes around (0 for a
  /// level cut; MeshOptions' decomposition.detours).
  std::vector<std::size_t> cut_balls;
  /// The cuts chosen but given up by the decomposed sweep (a slab next to it
  /// or its band failed; decompose::sweep_decomposed), heights as cut_heights',
  /// messages with positions in the input's coordinates frame noted.
  std::vector<decompose::DroppedCut> dropped_cuts;
  /// Where the decomposed sweep's time went (per slab, bands, glue, lost to
  /// dropped cuts; wall-clock seconds) and each slab's triangles; empty for
  /// one sweep.
  decompose::DecompositionCosts decomposition_costs;
  /// Why the skin's groups of components were swept as one after all (a
  /// group's sweep failed), or empty (decompose::DecomposedSweep).
  std::string components_fallback;
  refine::RefineStats refinement;
  /// What stage 4b did (all zero if it did not run).
  refine::AngleImprovementStats angle_improvement;
  /// What the baseline did (Algorithm::Dynamic; stats.predicates counts the
  /// calling thread's predicates from the skin to the output mesh).
  dynamic::DynamicStats dynamic;
  /// True if stage 5 ran; then `check` holds its report.
  bool checked = false;
  verify::SkinCheckReport check;
  /// Wall-clock seconds per stage, in order ("skin", "morse", "sweep",
  /// "refine", "angles" — or "growth", "refine" for the baseline — then
  /// "output" (compaction, normals, atoms) and "check"; stages that did not
  /// run are absent).
  std::vector<std::pair<std::string, double>> seconds;

  /// Centre of the local frame (Å, skin::local_frame_centre): every stage ran
  /// on the points translated by -frame_centre, and `mesh` was translated
  /// back. The check's report refers to the local frame.
  Vec3 frame_centre = Vec3::Zero();

  /// What MeshOptions::shells kept and left out, if it selects.
  std::optional<skin::ShellCounts> shells;

  /// With MeshOptions::skin_atom_areas: the exact skin's area per input point
  /// (Å², input order, 0 for redundant points; every shell, whatever
  /// MeshOptions::shells keeps). Empty otherwise.
  std::vector<double> skin_atom_areas;

  /// The check of the positions as MeshOptions::stored_positions stores
  /// them, if it ran (a lossy storage, and the check passed).
  std::optional<verify::SkinCheckReport> stored_check;
  /// The largest distance (Å) that storage moved a vertex, if stored_check ran.
  double stored_displacement = 0;
  /// How the storage rounds ("3 decimals", "float32"), if stored_check ran.
  std::string stored_as;
  /// The problems of `check`, then those of `stored_check`, each of these
  /// prefixed "as stored (<stored_as>): ", one line each.
  std::vector<std::string> problems() const;

  /// True unless the check ran and failed, on the exact or the stored positions.
  bool ok() const { return !checked || (check.ok() && (!stored_check || stored_check->ok())); }
};

/// Meshes the skin of the weighted points `points` (centres in Å, weights in
/// Å²) with options.algorithm (stages listed in this header). Throws
/// InputError if `points` is empty or the skin is singular
/// (skin::require_non_singular), TopologyError if the Morse count
/// of the critical points differs from the skin's Euler characteristic or
/// the sweep cannot close the front, GeometryError if a projection fails,
/// std::invalid_argument for options out of range (a tangent-disc factor
/// outside the window of C and Q, a baseline option outside
/// dynamic::validate's ranges). A mesh that fails its check is returned
/// with the report (ok() false), never silently. With
/// options.static_fallback the sweep's TopologyError and
/// GeometryError, and a refined sweep mesh that fails its check, are not
/// returned: the skin is meshed again by the static baseline
/// (MeshResult::static_fallback says why). Every stage works in the
/// local frame of the points (skin::local_frame_centre at the origin); when
/// that centre is not the origin, an error that names positions says so.
MeshResult mesh_skin(const std::vector<geometry::WeightedPoint>& points, const MeshOptions& options = {});

/// mesh_skin() of a molecule's atoms, weighted with options.probe_radius
/// (std::invalid_argument unless 0 <= probe_radius <= skin::kMaxRadius).
MeshResult mesh_skin(const skin::Molecule& molecule, const MeshOptions& options = {});

/// What the cuts and slabs of a run depend on, hashed (FNV-1a, 64 bits): the
/// weighted points (in order, as their bytes), the height direction, C and
/// Q, the Morse–Smale complex's tuning, the sweep's disc factor and park
/// factor and the decomposition's numbers. The processes of one
/// decomposition compare it (MeshOptions::cuts_file).
std::uint64_t decomposition_fingerprint(const std::vector<geometry::WeightedPoint>& points, const MeshOptions& options);

/// Stages 1 and 2 and the cut choice of a sweep over several processes: the
/// cuts of the points' skin (decompose::choose_cuts() with
/// options.decomposition, in the local frame of the points), with the run's
/// fingerprint, for decompose::write_cuts(). Throws as mesh_skin() does for
/// those stages.
decompose::CutsFile mesh_cuts(const std::vector<geometry::WeightedPoint>& points, const MeshOptions& options);

/// Stages 1 and 2 and the sweep of slab `slab` (bottom to top,
/// decompose::slabs_between()) of `cuts`, as the process that glues them
/// would sweep it (decompose::sweep_slab()), for decompose::write_region().
/// Throws InputError if `cuts` belongs to other points or options (its
/// fingerprint), std::invalid_argument if there is no such slab; otherwise
/// as mesh_cuts(). A slab whose sweep fails is returned with its failure.
decompose::RegionFile mesh_region(const std::vector<geometry::WeightedPoint>& points, const MeshOptions& options,
                                  const decompose::CutsFile& cuts, std::size_t slab);

/// The check of `mesh`'s positions as `storage` stores them
/// (MeshOptions::stored_positions). `skin` is in the local frame whose centre
/// is `centre`; files hold positions in the input's frame, which `mesh`'s
/// positions reach by adding `to_input` (`centre` for a mesh in the local
/// frame, zero for one in the input's frame): each position p is checked at
/// storage.stored(p + to_input) - centre. Checked with
/// `options` and `run` but for [L], [U] and the restricted Delaunay property (left
/// out) and a vertex-distance tolerance raised by the largest displacement,
/// which goes to `displacement` (Å). The pipeline runs it after its own
/// check; callers holding a mesh and its skin (the Python module's
/// Mesh.write) run it before writing to a lossy format.
verify::SkinCheckReport check_stored_positions(const skin::SkinSurface& skin, const geometry::IndexedMesh& mesh,
                                               const Vec3& to_input, const Vec3& centre,
                                               const geometry::PositionStorage& storage,
                                               verify::SkinCheckOptions options, const skin::RunContext& run,
                                               double& displacement);

}  // namespace skinmesh::mesher
