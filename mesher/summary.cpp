// mesher/summary.cpp: run_summary(), the result schema of `--stats` and of
// Python's Mesh.stats.
// Notes: papers/mesher/pipeline.md ("The result schema")
#include "mesher/summary.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <utility>

#include "core/errors.h"
#include "core/parallel.h"
#include "geometry/mesh/mesh_measures.h"
#include "skin/skin_measures.h"

namespace skinmesh::mesher {

namespace {

using json = nlohmann::ordered_json;

/// The counts of the baseline's run (Algorithm::Dynamic); `growth`: whether
/// it grew the skin (never in the whole-skin fallback, the static variant).
void add_dynamic_counts(bool growth, const dynamic::DynamicStats& d, json& j) {
  const dynamic::SampleStats& st = d.samples;
  j["growth"] = growth;
  j["operations"] = {{"growth_steps", d.steps},
                     {"start_level", d.start_level},
                     {"sphere_patches_seeded", d.births},
                     {"seeds", st.seeds},
                     {"u_insertions", st.u_insertions},
                     {"bounding_insertions", st.bounding_insertions},
                     {"manifold_insertions", st.manifold_insertions},
                     {"l_deletions", st.l_deletions},
                     {"ring_samples", st.ring_samples},
                     {"isolated_deletions", st.isolated_deletions},
                     {"lost_samples", d.lost_samples},
                     {"failed_insertions", st.failed_insertions},
                     {"moves", d.moves},
                     {"kinetic_moves", d.kinetic_moves},
                     {"voronoi_vertices_evaluated", st.tets_classified},
                     {"peak_samples", d.peak_samples},
                     {"peak_tetrahedra", d.peak_tets},
                     {"refine_rounds", st.rounds},
                     {"converged", d.converged},
                     {"L_left", st.L_left},
                     {"U_left", st.U_left},
                     {"nonmanifold_left", st.nonmanifold_left}};
  const auto& dt = d.delaunay;
  j["delaunay"] = {{"insertions", dt.insertions},       {"removals", dt.removals},
                   {"kinetic_moves", dt.kinetic_moves}, {"conflict_tets", dt.conflict_tets},
                   {"star_tets", dt.star_tets},         {"link_vertices", dt.link_vertices},
                   {"local_tets", dt.local_tets},       {"walk_steps", dt.walk_steps}};
  const auto& pr = d.predicates;
  j["predicates"] = {
      {"orient3d", {{"calls", pr.orient3d.calls}, {"exact", pr.orient3d.exact}, {"sos", pr.orient3d.sos}}},
      {"power_test", {{"calls", pr.power_test.calls}, {"exact", pr.power_test.exact}, {"sos", pr.power_test.sos}}}};
}

/// The counts of the sweep, the refinement and the angle improvement (Algorithm::Sweep).
void add_sweep_counts(const MeshOptions& options, const MeshResult& res, json& j) {
  const front::SweepStats& s = res.sweep;
  const refine::RefineStats& r = res.refinement;
  j["operations"] = {{"creations", s.creations},
                     {"creeps", s.creeps},
                     {"wings", s.wings},
                     {"bridges", s.bridges},
                     {"seals", s.seals},
                     {"held", s.held},
                     {"deferred", s.deferred},
                     {"bridge_rows", s.bridge_rows},
                     {"contacts", s.contacts},
                     {"collisions", s.collisions},
                     {"covered_triangles", s.covered_triangles},
                     {"stuck", s.stuck},
                     {"enlarged_holes", s.enlarged_holes},
                     {"left_holes", s.left_holes},
                     {"folds", s.folds},
                     {"patched_holes", s.patched_holes},
                     {"patch_faces", s.patch_faces},
                     {"reopened_holes", s.reopened_holes},
                     {"reopened_faces", s.reopened_faces},
                     {"departures", s.departures},
                     {"departure_bound", front::departure_bound(s, options.sweep.max_departures)},
                     {"spent_vertices", s.spent_vertices},
                     {"most_departures", s.most_departures},
                     {"merged_minima", s.merged_minima},
                     {"released_saddles", s.released},
                     {"flips", r.flips},
                     {"contractions", r.contractions},
                     {"insertions", r.insertions},
                     {"refine_rounds", r.rounds},
                     {"refused_contractions", r.refused_contractions},
                     {"protected_contractions", r.protected_contractions},
                     {"refused_insertions", r.refused_insertions},
                     {"crowded_insertions", r.crowded_insertions},
                     {"flip_caps", r.flip_caps},
                     {"L_left", r.L_left},
                     {"U_left", r.U_left}};
  // Only a decomposed sweep reports its slabs, so that one sweep's summary
  // keeps its keys.
  if (res.slabs > 1 || !res.dropped_cuts.empty()) {
    json dropped = json::array();
    for (const decompose::DroppedCut& d : res.dropped_cuts) dropped.push_back({{"height", d.height}, {"why", d.why}});
    std::vector<std::size_t> slab_triangles;
    for (const decompose::SlabCost& c : res.decomposition_costs.slabs) slab_triangles.push_back(c.triangles);
    j["decomposition"] = {{"slabs", res.slabs},
                          {"cut_heights", res.cut_heights},
                          {"parked", s.parked},
                          {"dropped_cuts", dropped},
                          {"slab_triangles", slab_triangles}};
    if (std::any_of(res.cut_balls.begin(), res.cut_balls.end(), [](std::size_t n) { return n > 0; }))
      j["decomposition"]["cut_balls"] = res.cut_balls;
  }
  // Without cuts, the groups of skin components swept on their own.
  if (!res.decomposition_costs.components.empty() || !res.components_fallback.empty()) {
    std::vector<std::size_t> triangles;
    for (const decompose::SlabCost& c : res.decomposition_costs.components) triangles.push_back(c.triangles);
    j["component_sweeps"] = {{"groups", triangles.size()}, {"triangles", triangles}};
    if (!res.components_fallback.empty()) j["component_sweeps"]["fallback"] = res.components_fallback;
  }
  const refine::AngleImprovementStats& ai = res.angle_improvement;
  j["angle_improvement"] = {{"enabled", options.improve_angles},
                            {"low_triangles", ai.low_triangles},
                            {"passes", ai.passes},
                            {"attempts", ai.attempts},
                            {"moves", ai.moves},
                            {"refused", ai.refused},
                            {"refused_orientation", ai.refused_orientation},
                            {"refused_rdt", ai.refused_rdt},
                            {"refused_intersection", ai.refused_intersection},
                            {"refused_L", ai.refused_L},
                            {"refused_U", ai.refused_U},
                            {"skipped", ai.skipped},
                            {"min_angle_before_deg", ai.min_angle_before_deg},
                            {"min_angle_after_deg", ai.min_angle_after_deg},
                            {"kappa", ai.kappa}};
}

}  // namespace

json run_summary(const MeshResult& res, const MeshOptions& options, const SummaryContext& context) {
  json j;
  j["input"] = context.input;
  j["output"] = context.output;
  j["atoms"] = context.atoms;
  j["probe_radius"] = options.probe_radius;
  j["vertices"] = res.mesh.positions.size();
  j["triangles"] = res.mesh.triangles.size();
  double analytic_seconds = -1;
  {
    // Area and enclosed volume from the mesh, per component and in all.
    json parts = json::array();
    double area = 0, volume = 0;
    for (const geometry::ComponentMeasure& c : geometry::component_measures(res.mesh)) {
      parts.push_back({{"vertices", c.vertices},
                       {"triangles", c.triangles},
                       {"area_A2", c.area},
                       {"volume_A3", c.volume},
                       {"kind", c.volume >= 0 ? "body" : "cavity"}});
      area += c.area;
      volume += c.volume;
    }
    j["surface"] = {{"area_A2", area}, {"volume_A3", volume}, {"components", std::move(parts)}};
    if (res.shells)
      j["surface"]["shells"] = {{"cavities", skin::cavity_choice_name(options.shells.cavities)},
                                {"min_cavity_volume_A3", options.shells.min_cavity_volume},
                                {"kept_bodies", res.shells->bodies},
                                {"kept_cavities", res.shells->cavities},
                                {"removed_bodies", res.shells->removed_bodies},
                                {"removed_cavities", res.shells->removed_cavities},
                                {"removed_cavity_volume_A3", res.shells->removed_cavity_volume}};
    // The same two numbers of the exact skin, integrated over its sphere and
    // hyperboloid patches, and how far the mesh is off.
    if (context.exact_measures_of) {
      const auto start = std::chrono::steady_clock::now();
      try {
        const skin::SkinMeasures exact = skin::skin_measures(*context.exact_measures_of, options.threads);
        analytic_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        j["surface"]["analytic"] = {
            {"area_A2", exact.area}, {"volume_A3", exact.volume}, {"patch_cells", exact.patch_cells}};
        j["surface"]["mesh_relative_difference"] = {{"area", area / exact.area - 1},
                                                    {"volume", volume / exact.volume - 1}};
      } catch (const GeometryError& e) {
        j["surface"]["analytic"] = {{"error", e.what()}};
        std::fprintf(stderr, "skinmesh: warning: no exact area and volume: %s\n", e.what());
      }
    }
  }
  if (context.skin_atom_areas && context.mesh_atom_areas) {
    // Sums in atom order; the atoms with area are those of a non-empty patch piece.
    double skin_sum = 0, mesh_sum = 0;
    std::size_t skin_atoms = 0, mesh_atoms = 0;
    for (double x : *context.skin_atom_areas) skin_sum += x, skin_atoms += x > 0;
    for (double x : *context.mesh_atom_areas) mesh_sum += x, mesh_atoms += x > 0;
    j["surface"]["atom_areas"] = {{"file", context.area_file},
                                  {"skin_sum_A2", skin_sum},
                                  {"mesh_sum_A2", mesh_sum},
                                  {"skin_atoms_with_area", skin_atoms},
                                  {"mesh_atoms_with_area", mesh_atoms}};
  }
  j["checked"] = res.checked;
  if (res.checked) {
    j["min_angle_deg"] = res.check.mesh.min_angle_deg;
    j["max_angle_deg"] = res.check.mesh.max_angle_deg;
    j["checks_passed"] = res.ok();
    j["problems"] = res.check.problems;
    if (res.stored_check) {
      j["stored_positions"] = {{"storage", options.stored_positions.describe()},
                               {"max_displacement_A", res.stored_displacement},
                               {"min_angle_deg", res.stored_check->mesh.min_angle_deg},
                               {"checks_passed", res.stored_check->ok()},
                               {"problems", res.stored_check->problems}};
    }
  }
  j["critical_points"] = {
      {"minima", res.critical.minima}, {"saddles", res.critical.saddles}, {"maxima", res.critical.maxima}};
  j["live_critical_points"] = {{"minima", res.live.minima}, {"saddles", res.live.saddles}, {"maxima", res.live.maxima}};
  j["algorithm"] = algorithm_name(res.algorithm);
  // The whole-skin fallback: the sweep was asked for, the static baseline made the mesh.
  if (!res.static_fallback.empty()) j["static_fallback"] = res.static_fallback;
  j["threads"] = thread_count(options.threads);
  if (res.algorithm == Algorithm::Dynamic)
    add_dynamic_counts(options.dynamic.growth && res.static_fallback.empty(), res.dynamic, j);
  else
    add_sweep_counts(options, res, j);
  json seconds = json::object();
  if (context.read_seconds >= 0) seconds["read"] = context.read_seconds;
  for (const auto& [stage, t] : res.seconds) seconds[stage] = t;
  if (analytic_seconds >= 0) seconds["analytic"] = analytic_seconds;
  // The decomposed sweep's parts (inside "sweep"): per slab, bottom to top,
  // then the bands, the glue, the slabs lost to dropped cuts and the slabs
  // swept ahead of their round (taken; seconds of those given up).
  if (!res.decomposition_costs.slabs.empty()) {
    const decompose::DecompositionCosts& c = res.decomposition_costs;
    std::vector<double> per_slab;
    for (const decompose::SlabCost& slab : c.slabs) per_slab.push_back(slab.seconds);
    seconds["sweep_parts"] = {{"slabs", per_slab},    {"bands", c.bands},           {"glue", c.glue},
                              {"retried", c.retried}, {"ahead_used", c.ahead_used}, {"ahead_unused", c.ahead_unused}};
  } else if (!res.decomposition_costs.components.empty()) {
    const decompose::DecompositionCosts& c = res.decomposition_costs;
    std::vector<double> per_group;
    for (const decompose::SlabCost& group : c.components) per_group.push_back(group.seconds);
    seconds["sweep_parts"] = {{"components", per_group}, {"glue", c.glue}};
  }
  if (context.write_seconds >= 0) seconds["write"] = context.write_seconds;
  if (context.total_seconds >= 0) seconds["total"] = context.total_seconds;
  j["seconds"] = seconds;
  if (context.peak_memory_bytes > 0) j["peak_memory_bytes"] = context.peak_memory_bytes;
  if (!context.stage_peak_memory_bytes.empty()) {
    json per_stage = json::object();
    for (const auto& [stage, bytes] : context.stage_peak_memory_bytes) per_stage[stage] = bytes;
    j["peak_memory_bytes_per_stage"] = per_stage;
  }
  return j;
}

}  // namespace skinmesh::mesher
