// apps/mesh_command.h: the arguments of `skinmesh mesh`, shared by its single
// run (mesh.cpp) and its batch run (batch.cpp).
#pragma once

#include <string>
#include <vector>

#include "apps/cli.h"
#include "mesher/pipeline.h"
#include "skin/skin_mesh_io.h"

namespace skinmesh::app {

/// `skinmesh mesh` as parsed.
struct MeshArgs {
  MoleculeArgs mol;
  std::string out, stats;
  std::vector<double> direction;
  /// The pipeline's options that the command line sets directly (C, Q, the
  /// disc factor, threads, the sweep's debugging aids, the baseline's growth
  /// step); the rest are set by mesh_options().
  mesher::MeshOptions opt;
  bool no_check = false, force = false, trace = false, no_angle_improvement = false;
  /// --no-fallback: neither the patch nor the whole-skin fallback; --no-patch:
  /// the whole-skin fallback without the patch (a testing aid).
  bool no_fallback = false, no_patch = false;
  /// "sweep" (Cheng & Shi 2004, default) or "dynamic" (the dynamic-skin baseline).
  std::string algorithm = "sweep";
  bool no_growth = false;
  /// --no-component-sweeps: every skin component in one front.
  bool no_component_sweeps = false;
  // Batch runs (several IN or --list): outputs DIR/<name>.<format>.
  std::string out_dir, list, batch_format = "ply";
  int jobs = 1;
  bool threads_given = false;
  /// --timeout: seconds that reading and meshing one input may take (0: no limit).
  double timeout = 0;
  /// --msms-decimals: digits after the point of MSMS positions.
  int msms_decimals = 3;
  /// --float: float32 positions and normals in PLY, OFF, OBJ and VTK.
  bool float32 = false;
  /// --off-normals: NOFF (positions and normals) instead of plain OFF.
  bool off_normals = false;
  /// --ascii: PLY and STL as text.
  bool ascii = false;
  /// --msms-atom-names: the atom's name as the 10th field of MSMS vertices.
  bool msms_atom_names = false;
  /// --msms-no-header, --msms-components: MSMS files without header lines, one pair per component.
  bool msms_no_header = false, msms_components = false;
  /// --area-file: the per-atom areas' file (skin/atom_areas.h); empty: none.
  std::string area_file;
  /// --area-files: in a batch run, DIR/NAME.area beside each mesh.
  bool area_files = false;
};

/// The pipeline's options of a run: `a.opt` with the probe, the height
/// direction, the algorithm, the check and the angle improvement of the
/// command line, and the program's memory release between the meshing and
/// the check. Throws CLI::ValidationError for a bad --direction.
mesher::MeshOptions mesh_options(const MeshArgs& a);

/// The per-atom areas of a run (Å², one entry per atom of the molecule).
struct AtomAreas {
  std::vector<double> skin;  ///< of the exact skin (skin::atom_areas())
  std::vector<double> mesh;  ///< of the mesh (skin::mesh_atom_areas())
};

/// The exact skin's and the mesh's area per atom of `mol` meshed into `res`
/// with MeshOptions::skin_atom_areas (the pipeline integrated the exact ones
/// on its skin; stage "atom_areas" of res.seconds).
AtomAreas atom_areas(const skin::Molecule& mol, const mesher::MeshResult& res);

/// How the mesh files of a run of `mol` are written: precision, OFF normals,
/// MSMS decimals, atom names (from `mol`) and the probe radius for its header.
skin::SkinMeshWriteOptions write_options(const MeshArgs& a, const skin::Molecule* mol = nullptr);

/// The one-line error of a mesh that passed its checks but not as `path`
/// stores it (MeshResult::stored_check failed): what broke and what to do.
std::string stored_check_error(const std::string& path, const mesher::MeshResult& res);

/// "; kept B bodies and C cavities, left out ..." when --cavities or
/// --min-cavity-volume selected shells (MeshResult::shells); empty otherwise.
std::string shells_note(const mesher::MeshResult& res);

/// `skinmesh mesh IN IN ... -O DIR` (or --list): every input meshed by --jobs
/// workers, one failing input does not stop the others; a summary table on
/// stdout and in DIR/summary.csv and DIR/summary.json. Returns 0 if every
/// input succeeded, else the largest of their exit codes.
int run_batch(const MeshArgs& a);

}  // namespace skinmesh::app
