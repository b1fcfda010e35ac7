// apps/cli.h: what the commands of the program share — the molecule,
// direction and size options, reading a molecule with its notes, the
// one-line messages, the allocator policy — and the commands themselves, one
// per file (info.cpp, mesh.cpp with batch.cpp, check.cpp, trace.cpp), put
// together by main.cpp. Options are parsed with CLI11, per command (an
// option a command does not have is an error), and the library takes typed
// structs (papers/conventions.md §3).
#pragma once

#include <CLI/CLI.hpp>

#include <functional>
#include <string>
#include <vector>

#include "core/types.h"
#include "skin/molecule.h"
#include "skin/shells.h"
#include "skin/size_conditions.h"

namespace skinmesh::app {

/// The input and output formats and the exit codes, the footer of every help text.
extern const char* const kFormats;

/// A subcommand of the program: its parser (options bound to the command's
/// own arguments) and what runs once it is parsed (returns the exit code;
/// throws the library's errors, which main() turns into messages and codes).
struct Command {
  CLI::App* parser = nullptr;
  std::function<int()> run;
};

Command add_info_command(CLI::App& app);
Command add_mesh_command(CLI::App& app);
Command add_check_command(CLI::App& app);
Command add_trace_command(CLI::App& app);
Command add_cuts_command(CLI::App& app);
Command add_region_command(CLI::App& app);

/// A validator for numbers >= 0 (strictly: > 0) with a short message.
CLI::Validator number_at_least_zero(bool strictly);

/// The molecule options of every command.
struct MoleculeArgs {
  std::string input;
  /// `mesh` only: every IN given (one: input; several: a batch run).
  std::vector<std::string> inputs;
  double probe = 1.4;
  bool keep_water = false;
  bool no_hydrogens = false;
  std::string format;
  bool quiet = false;
  /// --model: "" (the first model), a model number, or (mesh only) "all".
  std::string model;
  /// --assembly: the biological assembly to read ("": the file's coordinates).
  std::string assembly;
  /// --chains: "" (every chain), a comma-separated list, or (mesh only) "each".
  std::string chains;
};

/// IN (several if `many`), --probe, --keep-water, --no-hydrogens, --format,
/// --model (N; with `many` also "all"), --assembly, --quiet.
void add_molecule_options(CLI::App& cmd, MoleculeArgs& m, bool many = false);

/// Reads the molecule (m.input; the model m.model, which must not be "all",
/// and the assembly m.assembly) and prints (at most ten of) its notes unless quiet.
/// Throws InputError (skin::read_molecule).
skin::Molecule load_molecule(const MoleculeArgs& m);

/// --direction X,Y,Z of info, mesh and trace.
void add_direction_option(CLI::App& cmd, std::vector<double>& direction);

/// The unit height direction from --direction, or the default
/// (morse::default_height_direction). Throws CLI::ValidationError for a zero
/// or non-finite vector.
Vec3 height_direction(const std::vector<double>& d);

/// --threads of mesh, check and trace: "threads (ZERO); the WHAT is the same
/// for every count", an integer in [0, 4096].
void add_threads_option(CLI::App& cmd, int& threads, const char* zero, const char* what);

/// Adds --cavities keep|remove|only and --min-cavity-volume V (Å³, >= 0) to
/// `cmd`, filling `shells` (skin/shells.h); `what` ends the help of
/// --cavities ("write", "expect").
void add_shell_options(CLI::App& cmd, skin::ShellSelection& shells, const char* what);

/// --C and --Q of mesh, check and trace.
void add_size_options(CLI::App& cmd, skin::SizeConstants& size);

/// Options that apply to one algorithm only, given with the other: prints
/// "skinmesh CMD: OPTION applies to --algorithm A only" and returns false.
/// `dynamic_only` lists the options of the baseline; every other name in
/// `names` belongs to the sweep.
bool options_fit_algorithm(const CLI::App& cmd, bool dynamic, const std::vector<std::string>& names,
                           const std::vector<std::string>& dynamic_only);

/// One line, at most ~300 characters: details belong in --trace.
std::string one_line(std::string s);

/// Returns the allocator's free pages to the system (glibc: malloc_trim).
/// The program calls it between the meshing and the check (the stage of the
/// peak); the library makes no process-wide allocator calls.
void release_free_memory();

}  // namespace skinmesh::app
