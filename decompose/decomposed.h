// decompose/decomposed.h: the decomposed sweep — the skin cut near heights
// of equal predicted work (decompose/work.h) into slabs, each swept by
// sweep_region() from its lower cut curves, the band between each slab's
// parked rims and its upper cut curves closed by strip_triangulation(), and
// the slabs glued along the shared cut samples into one closed mesh
// (papers/decompose/README.md, "The cuts", "The sweep of a region", "The
// band's strip" and "The glue"). The result goes to the local refinement
// like sweep_mesh()'s.
// Notes: papers/decompose/README.md
#pragma once

#include <limits>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "front/region.h"
#include "front/sweep.h"
#include "morse/level_curves.h"
#include "refine/local_refinement.h"

namespace skinmesh::decompose {

/// Tuning of the cut choice and of the glue. Lengths are multiples of the
/// disc radius r = disc_factor · rho of the point concerned.
struct DecompositionOptions {
  /// Slabs wanted (1: no cut; 0, the default: automatic_slabs() of the input,
  /// one sweep below 3,750 atoms). The cut heights aim at equal shares of
  /// the predicted work (balance_work), so they depend on the input and on
  /// this number only, never on the thread count. Fewer slabs come out where
  /// no admissible height is found near a target.
  int slabs = 0;
  /// With slabs = 0: one slab per this many atoms. [measured] 2500: maltoporin
  /// (10,123 atoms) in 4 slabs, whose sweeps on two threads take 0.34 s
  /// against 0.58 s for one sweep, at a lower peak than one sweep's
  /// (papers/decompose/history.md, "Slabs by default").
  double atoms_per_slab = 2500;
  /// With slabs = 0, above atoms_per_slab² / atoms_per_root_slab atoms
  /// (7,812): sqrt(atoms / atoms_per_root_slab) slabs instead, fewer than
  /// one per atoms_per_slab. [derived] a cut's cost (its search, its curve,
  /// its band, and the chance that it drops and two slabs are swept again)
  /// grows with its length, about the square root of a body's atoms, so
  /// slabs growing as that root keep the cuts' share of the work even.
  /// [measured] 800: the 218,760-atom shell (bench/assembly.py shell --t 1)
  /// on 2 threads took 70.5, 65.8, 74.9 and 88.1 s (`total`) in 8, 16, 24
  /// and the linear rule's 88 slabs, 2, 3, 6 and 25 cuts dropped; 800 gives
  /// it 17 and keeps maltoporin (10,123 atoms) at 4
  /// (papers/decompose/history.md, "Slabs as the root of the atoms").
  /// 0: the linear rule alone.
  double atoms_per_root_slab = 800;
  /// With slabs = 0: at most this many slabs.
  int max_slabs = 256;
  /// Region::park_factor of every slab.
  double park_factor = 2;
  /// A critical point p, live or cancelled, forbids the cut heights c with
  /// c - below · r_p <= h(p) <= c + above · r_p. [measured] 2 and 1: the
  /// parking scales with sin(theta), which vanishes at a critical point, so
  /// a maximum or saddle a little below the cut is sealed or bridged, not
  /// parked around, and only points within about two disc radii of the cut
  /// height disturb the band; the live spheres near the curve are kept away
  /// by sphere_margin instead. Adding the protecting radius s_p to the
  /// window, as first designed, left no cut at probe 0
  /// (papers/decompose/history.md, "Increments", 4).
  double window_below = 2;
  /// See window_below.
  double window_above = 1;
  /// Every sample of a cut curve lies at least sphere_margin · r (r at the
  /// sample) outside every live protecting sphere. [derived] the parked rim
  /// and the strip lie within about park_factor + 1 disc radii of the curve.
  double sphere_margin = 3;
  /// Two consecutive cuts are at least min_thickness · r apart at every
  /// sample of either (sweep_region refuses a slab thinner than park_factor +
  /// 1). [derived] park_factor + 2: one row of fans between the lower
  /// curve and the parking height.
  double min_thickness = 4;
  /// Cut targets at equal shares of the predicted work (work_profile(): the
  /// skin's sphere patches' integral of 1/rho², which follows the mesh's
  /// triangles by height within 5 % at every decile on the bundled
  /// molecules), the candidates around the equal part of the critical
  /// heights' range searched after them; without it, only the latter.
  /// [measured] largest slab over the mean on maltoporin in its 4 slabs
  /// 1.66 -> 1.16, src kinase in 4 1.58 -> 1.32 (papers/decompose/
  /// history.md, "Cuts at equal shares of the predicted work").
  bool balance_work = true;
  /// Candidate heights are searched within this fraction of the slab height
  /// on each side of a target, at steps of search_step of the slab height.
  /// [measured] 0.4 and 0.01: 81 candidates per target.
  double search_reach = 0.4;
  double search_step = 0.01;
  /// The cut curves' tracing and sampling.
  morse::LevelCurveOptions curves;
  /// Every cut passes around the critical points it meets (morse::cut_detours,
  /// morse::cut_curves) instead of being a level cut where one is admissible
  /// (papers/decompose/README.md, "Detoured cuts"). Off by default: a level
  /// cut is cheaper and never drops (see detour_fallback).
  bool detours = false;
  /// Without `detours`: a target near which no level cut is admissible gets
  /// a detoured cut (its candidates searched again, traced around the
  /// critical points they meet): level cuts where the skin admits them,
  /// detoured cuts where it does not, as large bodies need (no level cut on a
  /// 218,760-atom shell, none on maltoporin at probe 0). Meshes with a level
  /// cut at every target are those of level cuts alone. [measured] on by
  /// default since the slab count grows as the root of the atoms: the
  /// 218,760-atom shell (16 slabs) took 64.8–76.4 s on 2 threads against
  /// 68.4–80.8 s as one sweep; the 1,214,760-atom shell (21 slabs kept of
  /// 39) about 340 s against 331 s at a peak of 8.26 GB against 9.23 GB, and
  /// 593 s on one thread (papers/decompose/history.md, "Slabs as the root of
  /// the atoms"). More cores gain more, since the slabs share them.
  bool detour_fallback = true;
  /// Without a cut: one sweep per group of whole skin components
  /// (morse::component_groups()), on the threads, instead of one sweep of
  /// the whole skin. The groups depend on the input only. Off where the
  /// sweep has an observer or a trace (they follow one front in one mesh).
  bool components = true;
  /// With components: append the groups' meshes into one (true), or hand
  /// them back one by one in DecomposedSweep::groups (false), for a caller
  /// that refines each group on its own and joins the output meshes: no
  /// copy of the whole mesh, and each group's half-edge mesh can be freed
  /// once its output is made (papers/decompose/README.md, "After the
  /// sweep"). mesher::mesh_skin() sets it itself: false unless an observer
  /// watches the whole mesh between the stages.
  bool glue_groups = true;
  /// With cuts: refine each region's mesh on the threads once its bands
  /// are known, before the glue (refine::refine_mesh() with `refinement`,
  /// one thread per region, its boundary kept), so that the refinement's
  /// serial flips, contractions and insertions run region by region and the
  /// pass over the glued mesh meets the seams. The mesh depends on the
  /// regions only, never on the thread count
  /// (papers/decompose/README.md, "After the sweep").
  bool refine_regions = false;
  /// The refinement of refine_regions.
  refine::RefineOptions refinement;
};

/// The slab count of DecompositionOptions::slabs = 0 for `atoms` atoms:
/// round(min(atoms / opt.atoms_per_slab, sqrt(atoms / opt.atoms_per_root_slab))),
/// within [1, opt.max_slabs].
int automatic_slabs(std::size_t atoms, const DecompositionOptions& opt);

/// The slab count of DecompositionOptions::slabs = 0 for a skin of `atoms`
/// atoms with the Morse–Smale complex `ms`: automatic_slabs() of the atoms'
/// share of the largest group of whole components (morse::component_groups(),
/// its share of the critical points) when that group holds more than half of
/// them; 1 when it does not (the groups already share the threads, and cuts
/// through many groups would need heights clear of all of them), when
/// opt.components is off (one front for everything), and where the sweep has
/// an observer or a trace (they follow one front, as the paper's Algorithm 1).
/// Depends on the input only, never on the thread count.
int automatic_slabs(std::size_t atoms, const morse::MorseSmaleComplex& ms, const DecompositionOptions& opt,
                    const front::SweepOptions& sweep);

/// One cut of the decomposition: its height (Å) and its sampled level
/// curves (morse::level_curves(), oriented by n × e).
struct Cut {
  double height = 0;
  std::vector<morse::LevelCurve> curves;
  /// The clusters of balls the cut passes around (DecompositionOptions::detours).
  std::vector<morse::CutDetour> detours;
  /// A detoured cut (morse::cut_curves(), even with no ball): no height
  /// window keeps the critical points away from it, so the slab below it
  /// holds before it parks (front::Region::holds_before_parking).
  bool detoured = false;
};

/// The cut heights of opt.slabs slabs (automatic_slabs() if 0), in
/// increasing order, each admissible
/// (DecompositionOptions' windows, sphere margin and thickness) with its
/// curves traced. Needs the integral lines' polylines of `ms` (the seeds of
/// level_curves()), so it runs before they are freed. A target without an
/// admissible height nearby is skipped (fewer slabs). With opt.detours, a
/// cluster of morse::cut_detours() that goes down but whose union the level
/// set enters is sent up, and the cut traced again (papers/decompose/
/// README.md, "Detoured cuts"). The detoured cuts' candidates are traced on
/// run.threads threads (0: every core); the cuts are the same for every
/// count. Throws std::invalid_argument if opt.slabs < 0.
std::vector<Cut> choose_cuts(const skin::SkinSurface& skin, const morse::MorseSmaleComplex& ms,
                             const DecompositionOptions& opt, const front::SweepOptions& sweep,
                             const skin::RunContext& run = {});

/// A cut the decomposed sweep gave up, and why: a slab next to it failed
/// (the message of sweep_region()'s error) or a band under it had no strip.
struct DroppedCut {
  double height = 0;
  std::string why;
};

/// What one slab of the glued mesh cost: the wall-clock seconds of its
/// sweep_region() (on whichever thread ran it; with several threads these
/// include the contention of the shared caches and memory) and its
/// triangles. For the speed-up model of bench/speedup_model.py
/// (papers/decompose/README.md, "Measured costs and the predicted speed-up").
struct SlabCost {
  double seconds = 0;  ///< with DecompositionOptions::refine_regions, its refinement's as well
  std::size_t triangles = 0;
};

/// Where the decomposed sweep's time went, in wall-clock seconds: per slab
/// of the glued mesh (bottom to top), the bands' strips (all of them, on
/// the threads), the glue (serial), and the slabs swept but given up when a
/// cut was dropped (their time is lost).
struct DecompositionCosts {
  std::vector<SlabCost> slabs;
  /// Without a cut: per group of components swept on its own, in group order.
  std::vector<SlabCost> components;
  double bands = 0;
  double glue = 0;
  double retried = 0;
  /// Slabs swept ahead of their round on a thread that would have waited
  /// for the round's last slab (decompose/slab_pool.h): how many a round
  /// took, and the seconds of those given up.
  std::size_t ahead_used = 0;
  double ahead_unused = 0;
};

/// The decomposed sweep's mesh and the cuts it kept.
struct DecomposedSweep {
  /// The glued mesh, with the vertex properties and the meaning of
  /// sweep_mesh()'s; its stats the sum over the slabs of the mesh.
  front::SweepResult sweep;
  /// The heights (Å, along the complex's height direction) of the cuts the
  /// mesh was glued along, increasing.
  std::vector<double> cut_heights;
  /// Per kept cut, the balls it passes around (0 for a level cut).
  std::vector<std::size_t> cut_balls;
  /// The cuts dropped, in the order they were.
  std::vector<DroppedCut> dropped;
  /// With DecompositionOptions::refine_regions: the sum of the refinements
  /// of the glued regions (rounds: the most; refusals and violations left
  /// are the region pass's, which the pass over the glued mesh takes up).
  refine::RefineStats region_refinement;
  /// With DecompositionOptions::refine_regions and regions glued: the faces
  /// of the glued mesh at the seams (the bands' triangles and the triangles
  /// around their corners, increasing), where refine::refine_seams() starts;
  /// away from them the regions' pass refined the mesh. Empty otherwise.
  std::vector<geometry::Face> seams;
  /// The costs, empty for one sweep (no cut kept, one group of components).
  DecompositionCosts costs;
  /// Why the groups of components were swept as one after all (a group's
  /// sweep failed: its error), or empty.
  std::string components_fallback;
  /// With DecompositionOptions::glue_groups false and at least two groups
  /// swept: each group's mesh (garbage-collected, with sweep_mesh()'s vertex
  /// properties), in group order; `sweep` then holds the summed stats and
  /// an empty mesh. Empty otherwise (the mesh is in `sweep`).
  std::vector<front::SweepResult> groups;
};

/// A slab by the indices of its two cuts in the cuts given, increasing;
/// kNoCut for the lowest slab's lower cut and the highest's upper one.
using SlabKey = std::pair<std::size_t, std::size_t>;
inline constexpr std::size_t kNoCut = std::numeric_limits<std::size_t>::max();

/// The slabs between `cuts` cuts when every one is kept, bottom to top: slab
/// k lies between cut k - 1 and cut k.
std::vector<SlabKey> slabs_between(std::size_t cuts);

/// One slab's sweep (front::sweep_region() of its region): its mesh, or why
/// it failed.
struct SlabOutcome {
  std::optional<front::RegionResult> result;
  /// The failure the decomposition answers by merging the slab with a
  /// neighbour (a TopologyError, GeometryError or std::invalid_argument of
  /// sweep_region()), or empty.
  std::string error;
  bool at_lower_cut = false;  ///< the failure was the lower cut's (front::LowerCutError)
  double seconds = 0;         ///< wall clock of the sweep_region() call and of the region's refinement
  refine::RefineStats refinement;
  bool refined = false;  ///< by the region's refinement (DecompositionOptions::refine_regions)
};

/// The slab `key` of `cuts` swept as sweep_decomposed() sweeps it in its
/// first round (before any cut is dropped), with every thread of `run`
/// for it: the outcome another process hands to sweep_decomposed()
/// (decompose/region_files.h). Throws std::invalid_argument if `key` is not
/// a slab of `cuts`.
SlabOutcome sweep_slab(const skin::SkinSurface& skin, const morse::MorseSmaleComplex& ms, const std::vector<Cut>& cuts,
                       const SlabKey& key, const DecompositionOptions& opt, const front::SweepOptions& sweep = {},
                       const skin::RunContext& run = {});

/// Meshes the skin slab by slab between `cuts` (increasing heights, as
/// choose_cuts() returns them) and glues the slabs into one closed mesh: the
/// cut samples are shared by the slab above (its lower boundary) and the
/// band below (the strip between the slab's parked rims and the cut's
/// curves). The slabs, then the bands, are computed on up to run.threads
/// threads (one if `sweep` has an observer or a trace); the mesh does not
/// depend on the count. With run.release_made_cells (the caller owns the
/// skin: no other thread reads the complex during the sweep) the groups of
/// components are swept in windows of run.threads groups, largest first,
/// and what a window made goes back before the next, so the made cells of
/// every group do not stay beside every group's mesh; with cuts, what the
/// slabs made goes back before the glue (papers/decompose/history.md, "The
/// made cells between the stages"). C and Q and the progress reports come
/// from `run`. The sweep goes down a ladder whose rungs fail by value, each
/// failure sending it to the next: regions, merged where one fails (a slab
/// whose sweep_region() throws TopologyError, GeometryError or
/// std::invalid_argument drops the cut above it, below it for the top slab;
/// a band without an outward strip, a band triangle that does not glue or
/// a seam left open or pinched drops its cut: the two slabs become one,
/// swept again, the others kept); with no cut given, one sweep per group of
/// whole skin components (DecompositionOptions::components); one sweep of
/// everything (sweep_mesh()) when there is one group, a group's sweep fails
/// or every cut was dropped. Throws what sweep_mesh() throws; the
/// whole-skin fallback below the last rung is the pipeline's. `swept`: slabs
/// of `cuts` swept already (sweep_slab(), in other processes), taken instead
/// of sweeping them; the mesh is the same as without them.
DecomposedSweep sweep_decomposed(const skin::SkinSurface& skin, const morse::MorseSmaleComplex& ms,
                                 const std::vector<Cut>& cuts, const DecompositionOptions& opt,
                                 const front::SweepOptions& sweep = {}, const skin::RunContext& run = {},
                                 std::map<SlabKey, SlabOutcome> swept = {});

}  // namespace skinmesh::decompose
