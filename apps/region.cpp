// apps/region.cpp: one structure meshed over several processes (jobs of a
// workflow, nodes of a cluster) — `skinmesh cuts` chooses the cuts and writes
// them, `skinmesh region` sweeps one slab between them and writes it, and
// `skinmesh mesh --cuts F --regions R...` glues the slabs, refines, checks and
// writes the mesh, the same mesh as one `skinmesh mesh` with the same options
// (decompose/region_files.h; papers/decompose/README.md, "One structure over
// several processes"). Each process builds the skin and the Morse–Smale
// complex of the whole input; the files carry the run's fingerprint, so
// processes given other inputs or options refuse each other's files.
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "apps/cli.h"
#include "apps/output.h"
#include "decompose/region_files.h"
#include "mesher/pipeline.h"
#include "skin/molecule_io.h"
#include "skin/skin_surface.h"

namespace skinmesh::app {

namespace {

/// The arguments `cuts` and `region` share with `mesh`: what the cuts and
/// slabs depend on.
struct RegionArgs {
  MoleculeArgs mol;
  std::vector<double> direction;
  mesher::MeshOptions opt;
  bool no_component_sweeps = false;
  std::string cuts, out;
  std::size_t index = 0;
};

/// The options `mesh` accepts that decide the cuts and the slabs (the same
/// names, so that a workflow passes one option string to all three commands).
void add_decomposition_options(CLI::App& cmd, RegionArgs& a) {
  add_molecule_options(cmd, a.mol);
  add_direction_option(cmd, a.direction);
  add_size_options(cmd, a.opt.size);
  cmd.add_option("--disc-factor", a.opt.sweep.disc_factor, "tangent-disc radius / rho, as `skinmesh mesh`'s")
      ->check(number_at_least_zero(true))
      ->capture_default_str();
  add_threads_option(cmd, a.opt.threads, "0: every core", "output is, byte for byte,");
  cmd.add_option("--slabs", a.opt.decomposition.slabs, "slabs wanted, as `skinmesh mesh --slabs`")
      ->check(CLI::Range(0, 1000000))
      ->capture_default_str();
  cmd.add_flag("--cut-detours", a.opt.decomposition.detours, "cuts that pass around critical points, as `mesh`'s");
  cmd.add_flag("--detour-fallback,!--no-detour-fallback", a.opt.decomposition.detour_fallback,
               "as `skinmesh mesh --detour-fallback` (the default)");
  cmd.add_flag("--no-component-sweeps", a.no_component_sweeps, "as `skinmesh mesh --no-component-sweeps`");
}

/// The pipeline's options of `a`, as mesh_options() makes them for `mesh`.
mesher::MeshOptions options_of(const RegionArgs& a) {
  mesher::MeshOptions options = a.opt;
  options.probe_radius = a.mol.probe;
  options.height_direction = height_direction(a.direction);
  options.decomposition.components = !a.no_component_sweeps;
  return options;
}

int run_cuts(const RegionArgs& a) {
  require_writable(a.out);
  const skin::Molecule mol = load_molecule(a.mol);
  mesher::MeshOptions options = options_of(a);
  ProgressReporter progress(!a.mol.quiet);
  options.progress = [&progress](const std::string& stage, double f) { progress.report(stage, f); };
  const decompose::CutsFile cuts = mesher::mesh_cuts(skin::weighted_points(mol, options.probe_radius), options);
  progress.finish();
  decompose::write_cuts(a.out, cuts);
  // The one line a workflow reads: how many regions to sweep.
  std::cout << cuts.cuts.size() + 1 << "\n";
  if (!a.mol.quiet)
    std::cerr << "skinmesh cuts: " << cuts.cuts.size() << " cuts, " << cuts.cuts.size() + 1
              << " regions (skinmesh region --index 0 .. " << cuts.cuts.size() << ") -> " << a.out << "\n";
  return 0;
}

int run_region(const RegionArgs& a) {
  require_writable(a.out);
  const decompose::CutsFile cuts = decompose::read_cuts(a.cuts);
  if (a.index > cuts.cuts.size())
    throw InputError(a.cuts, 0,
                     "has " + std::to_string(cuts.cuts.size() + 1) + " regions: --index " + std::to_string(a.index) +
                         " is not one of 0 .. " + std::to_string(cuts.cuts.size()));
  const skin::Molecule mol = load_molecule(a.mol);
  mesher::MeshOptions options = options_of(a);
  ProgressReporter progress(!a.mol.quiet);
  options.progress = [&progress](const std::string& stage, double f) { progress.report(stage, f); };
  decompose::RegionFile region;
  try {
    region = mesher::mesh_region(skin::weighted_points(mol, options.probe_radius), options, cuts, a.index);
  } catch (const InputError& e) {
    if (!e.file().empty()) throw;
    throw InputError(a.cuts, 0, e.problem());
  }
  progress.finish();
  decompose::write_region(a.out, region);
  if (!a.mol.quiet) {
    const decompose::SlabOutcome& o = region.outcome;
    std::cerr << "skinmesh region " << a.index << ": ";
    if (o.result)
      std::cerr << o.result->mesh.n_faces() << " triangles";
    else
      std::cerr << "the sweep failed (the gluing process merges it with a neighbour): " << one_line(o.error);
    std::cerr << ", " << o.seconds << " s -> " << a.out << "\n";
  }
  return 0;
}

}  // namespace

Command add_cuts_command(CLI::App& app) {
  auto args = std::make_shared<RegionArgs>();
  CLI::App* cmd = app.add_subcommand(
      "cuts",
      "choose the cuts that split one structure into regions and write them (-o FILE), for `skinmesh region` "
      "and `skinmesh mesh --cuts`; prints the number of regions");
  add_decomposition_options(*cmd, *args);
  cmd->add_option("-o,--output", args->out, "the cuts file to write")->required();
  return {cmd, [args] { return run_cuts(*args); }};
}

Command add_region_command(CLI::App& app) {
  auto args = std::make_shared<RegionArgs>();
  CLI::App* cmd = app.add_subcommand(
      "region",
      "sweep one region between the cuts of `skinmesh cuts` and write it (-o FILE), for `skinmesh mesh --cuts "
      "F --regions R...`; give the same input and options as to `cuts`");
  add_decomposition_options(*cmd, *args);
  cmd->add_option("--cuts", args->cuts, "the cuts file `skinmesh cuts` wrote")->required();
  cmd->add_option("--index", args->index, "the region, 0 (lowest) .. the number `skinmesh cuts` printed - 1")
      ->required();
  cmd->add_option("-o,--output", args->out, "the region file to write")->required();
  return {cmd, [args] { return run_region(*args); }};
}

}  // namespace skinmesh::app
