// apps/main.cpp: the command-line program — its commands, its exit codes and
// its allocator policy. Errors are one line "file:line: problem" with a
// non-zero exit code; no partial output file is ever left behind (every file
// is written to a temporary and renamed).
//
//   skinmesh info  IN                describe the skin of a molecule       (info.cpp)
//   skinmesh mesh  IN -o OUT         mesh the skin (Cheng & Shi 2004)      (mesh.cpp, batch.cpp)
//   skinmesh check IN MESH           verify a mesh against the analytic skin (check.cpp)
//   skinmesh trace IN -o trace.html  record the algorithm, step by step, as a page (trace.cpp)
//   skinmesh cuts  IN -o F.cuts      one structure over several processes: its cuts (region.cpp)
//   skinmesh region IN --cuts F.cuts --index K -o F.K.region   one region's sweep (region.cpp)
//
// Exit codes: 0 success; 1 bad input or a mesh that fails `check`; 2 bad
// command line; 3 the algorithm failed (or the mesh failed its checks);
// 4 internal error; 5 `mesh --timeout` reached (nothing written).
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

#if defined(__GLIBC__)
#include <malloc.h>  // mallopt, malloc_trim
#endif

#include "apps/cli.h"
#include "core/errors.h"

namespace skinmesh::app {

// The program's allocator policy, in this one place: the library makes no
// process-wide allocator calls (papers/bench/profile.md, "Memory").
void release_free_memory() {
#if defined(__GLIBC__)
  // The sweep frees many small blocks (the collision grids' cells) that the
  // heap would otherwise keep resident through the check, the stage of the peak.
  malloc_trim(0);
#endif
}

namespace {

void configure_allocator() {
#if defined(__GLIBC__)
  // Large arrays (the mixed complex, the mesh's property arrays, the check's
  // tables) come from their own mappings and go back to the system when freed.
  // By default glibc raises this threshold each time such an array is freed,
  // after which the next ones come from the heap and their memory stays
  // resident after the stage that used them.
  mallopt(M_MMAP_THRESHOLD, 1 << 20);
#endif
}

constexpr const char* kDescription =
    "skinmesh: guaranteed-quality meshes of molecular skin surfaces\n"
    "(Cheng & Shi, \"Guaranteed Quality Triangulation of Molecular Skin Surfaces\", IEEE Vis 2004).";

}  // namespace

}  // namespace skinmesh::app

int main(int argc, char** argv) {
  using namespace skinmesh;
  using namespace skinmesh::app;
  configure_allocator();
  CLI::App app{kDescription, "skinmesh"};
  app.footer(kFormats);
  app.set_version_flag("--version", std::string("skinmesh ") + SKINMESH_VERSION);
  app.require_subcommand(1);
  const std::vector<Command> commands = {add_info_command(app),  add_mesh_command(app), add_check_command(app),
                                         add_trace_command(app), add_cuts_command(app), add_region_command(app)};

  if (argc < 2) {
    std::cerr << app.help();
    return 2;
  }
  if (const std::string first = argv[1]; first[0] != '-' && first != "info" && first != "mesh" && first != "check" &&
                                         first != "trace" && first != "cuts" && first != "region") {
    std::cerr << "skinmesh: unknown command '" << first
              << "' (commands: info, mesh, check, trace, cuts, region; see 'skinmesh --help')\n";
    return 2;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::string cmd;
    for (CLI::App* sub : app.get_subcommands()) cmd = " " + sub->get_name();
    std::cerr << "skinmesh" << cmd << ": " << one_line(e.what()) << " (see 'skinmesh" << cmd << " --help')\n";
    return 2;
  }
  const Command* parsed = nullptr;
  for (const Command& c : commands)
    if (c.parser->parsed()) parsed = &c;
  const bool meshing = parsed->parser->get_name() == "mesh" || parsed->parser->get_name() == "region";
  try {
    return parsed->run();
  } catch (const CLI::ValidationError& e) {
    std::cerr << "skinmesh: " << one_line(e.what()) << "\n";
    return 2;
  } catch (const InputError& e) {
    std::cerr << "error: " << one_line(e.what()) << "\n";
    return 1;
  } catch (const TopologyError& e) {
    std::cerr << "error: topology: " << one_line(e.what())
              << (meshing ? " (rerun with --trace for the sweep's decisions)" : "") << "\n";
    return 3;
  } catch (const GeometryError& e) {
    std::cerr << "error: geometry: " << one_line(e.what()) << "\n";
    return 3;
  } catch (const std::invalid_argument& e) {
    std::cerr << "skinmesh: " << one_line(e.what()) << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "internal error: " << one_line(e.what()) << "\n";
    return 4;
  }
}
