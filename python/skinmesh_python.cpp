// python/skinmesh_python.cpp: the Python module `skinmesh` (pybind11) — the
// pipeline's entry points with numpy arrays in and out:
//   skinmesh.mesh(path_or_atoms, probe=1.4, algorithm="sweep", check=True,
//                 threads=0, ..., model=None, assembly=None, chains=None) -> Mesh
//   skinmesh.check(path_or_atoms, mesh_or_path, probe=1.4) -> dict
//   skinmesh.read_mesh(path) -> Mesh,  Mesh.write(path)
// Errors are Python exceptions carrying the command line's one-line messages:
// skinmesh.InputError (a ValueError: bad file, bad array, bad option),
// skinmesh.TopologyError and skinmesh.GeometryError (RuntimeErrors: the
// algorithm failed). The GIL is released while C++ runs.
// Notes: papers/python.md
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/errors.h"
#include "geometry/io/mesh_io.h"
#include "mesher/pipeline.h"
#include "mesher/summary.h"
#include "skin/atom_areas.h"
#include "skin/dual_complex.h"
#include "skin/element_radii.h"
#include "skin/molecule_io.h"
#include "skin/shells.h"
#include "skin/skin_measures.h"
#include "skin/skin_mesh_io.h"
#include "skin/skin_surface.h"
#include "verify/skin_mesh_check.h"

namespace py = pybind11;
using namespace skinmesh;

namespace {

/// A mesh as numpy arrays, and what the run measured.
struct PyMesh {
  geometry::IndexedMesh mesh;
  skin::SkinVertexData vertex_data;
  py::dict stats;
  /// The check's verdict; empty for a mesh never checked (mesh(check=False), read_mesh()).
  std::optional<bool> ok;
  /// The weighted points of the skin a checked mesh passed against (empty
  /// otherwise): write() checks the positions a lossy format stores against it.
  std::vector<geometry::WeightedPoint> points;
  /// The probe radius (Å) of mesh(), for the MSMS header.
  double probe = 0;
  /// What mesh()'s cavities / min_cavity_volume left out, if they selected,
  /// and the skin's topology (from the run): write() then expects the kept
  /// shells without building the dual complex again.
  std::optional<skin::ShellCounts> shells;
  skin::SkinTopology topology;
  /// The number of atoms of mesh()'s molecule (0 for a mesh read from a file).
  std::size_t atoms = 0;
};

/// The shell selection of mesh() and check(): cavities "keep", "remove" or
/// "only", and the smallest cavity volume kept (Å³). Throws InputError.
skin::ShellSelection shell_selection(const std::string& cavities, double min_cavity_volume) {
  skin::ShellSelection s;
  try {
    s.cavities = skin::cavity_choice_named(cavities);
  } catch (const std::invalid_argument& e) {
    throw InputError("", 0, e.what());
  }
  if (!(min_cavity_volume >= 0 && std::isfinite(min_cavity_volume)))
    throw InputError("", 0, "min_cavity_volume must be a finite volume >= 0 (Å³)");
  s.min_cavity_volume = min_cavity_volume;
  return s;
}

/// True if `p` is a path: str, bytes or os.PathLike.
bool is_path(const py::object& p) {
  return py::isinstance<py::str>(p) || py::isinstance<py::bytes>(p) || py::hasattr(p, "__fspath__");
}

/// The file name of a path (str, bytes or os.PathLike), as the file system
/// encodes it (os.fsdecode), so that bytes paths work as str paths do.
std::string path_of(const py::object& p) {
  const py::module_ os = py::module_::import("os");
  return py::str(os.attr("fsdecode")(os.attr("fspath")(p)));
}

/// What of a structure file to read (skin::ReadOptions): model (None: the
/// first; N: the model numbered N), assembly (None or an id) and chains (None,
/// "A,B" or a list of chain names), as `--model`, `--assembly` and `--chains`.
struct Selection {
  py::object model = py::none(), assembly = py::none(), chains = py::none();
  bool any() const { return !model.is_none() || !assembly.is_none() || !chains.is_none(); }
};

/// skin::ReadOptions of `sel`; InputError for a bad model, assembly or chain list.
skin::ReadOptions read_options_of(const Selection& sel) {
  skin::ReadOptions opt;
  if (!sel.model.is_none()) {
    const bool integer = py::isinstance<py::int_>(sel.model) && !py::isinstance<py::bool_>(sel.model);
    // Python ints have no bound: compared in Python, so that 2**70 is refused, not wrapped.
    if (!integer || sel.model < py::int_(1) || sel.model > py::int_(std::numeric_limits<int>::max()))
      throw InputError("", 0,
                       "model must be None (the first) or a model number >= 1 (model_numbers() lists a file's; for "
                       "every model, mesh each in turn)");
    opt.model = sel.model.cast<int>();
  }
  if (!sel.assembly.is_none()) {
    opt.assembly = py::str(sel.assembly);
    if (opt.assembly.empty()) throw InputError("", 0, "assembly must be None or an assembly id such as '1'");
  }
  if (!sel.chains.is_none()) {
    std::vector<std::string> names;
    if (py::isinstance<py::str>(sel.chains)) {
      const std::string list = sel.chains.cast<std::string>();
      std::size_t start = 0;
      while (start <= list.size()) {
        const std::size_t comma = std::min(list.find(',', start), list.size());
        names.push_back(list.substr(start, comma - start));
        start = comma + 1;
      }
    } else if (py::isinstance<py::iterable>(sel.chains)) {
      for (const py::handle& c : sel.chains) names.push_back(py::str(c));
    } else {
      names.emplace_back();  // refused below, with the other bad lists
    }
    for (const std::string& n : names)
      if (n.empty()) throw InputError("", 0, "chains must be chain names such as 'A,B' or ['A', 'B'], none empty");
    opt.chains = names;
  }
  return opt;
}

/// The atoms of `source`: a path (str, bytes or os.PathLike) read with
/// read_molecule and the selection `sel`, or an array (n, 4) of x, y, z (Å)
/// and radius (Å), for which a selection is an InputError.
skin::Molecule molecule_of(const py::object& source, const Selection& sel = {}) {
  if (is_path(source)) {
    const std::string path = path_of(source);
    const skin::ReadOptions opt = read_options_of(sel);
    py::gil_scoped_release release;
    return skin::read_molecule(path, opt);
  }
  if (sel.any()) throw InputError("", 0, "model, assembly and chains select from a structure file, not from an array");
  const auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(source);
  if (!a || a.ndim() != 2 || a.shape(1) != 4)
    throw InputError("", 0, "atoms must be a path or an array of shape (n, 4): x, y, z, radius (Å)");
  if (a.shape(0) == 0) throw InputError("", 0, "no atoms");
  skin::Molecule mol;
  const auto v = a.unchecked<2>();
  for (py::ssize_t i = 0; i < a.shape(0); ++i) {
    skin::Atom atom;
    atom.centre = Vec3(v(i, 0), v(i, 1), v(i, 2));
    atom.radius = v(i, 3);
    if (!atom.centre.allFinite() || std::abs(atom.centre.x()) > geometry::kMaxCoordinate ||
        std::abs(atom.centre.y()) > geometry::kMaxCoordinate || std::abs(atom.centre.z()) > geometry::kMaxCoordinate)
      throw InputError("", 0,
                       "atom " + std::to_string(i) + ": coordinates must be finite and within ±" +
                           std::to_string(geometry::kMaxCoordinate) + " Å");
    if (!(atom.radius > 0 && atom.radius <= skin::kMaxRadius))
      throw InputError(
          "", 0,
          "atom " + std::to_string(i) + ": the radius must lie in (0, " + std::to_string(skin::kMaxRadius) + "] Å");
    mol.atoms.push_back(atom);
  }
  return mol;
}

/// A copy of `rows` × `cols` values as a numpy array of T.
template <class T, class Get>
py::array_t<T> array_of(std::size_t rows, std::size_t cols, const Get& get) {
  py::array_t<T> out(cols == 1 ? std::vector<py::ssize_t>{py::ssize_t(rows)}
                               : std::vector<py::ssize_t>{py::ssize_t(rows), py::ssize_t(cols)});
  T* p = out.mutable_data();
  for (std::size_t i = 0; i < rows; ++i)
    for (std::size_t k = 0; k < cols; ++k) p[i * cols + k] = get(i, k);
  return out;
}

/// A numpy view of `rows` × `cols` values of T at `data` (rows `row_bytes`
/// apart; 1-d if cols == 1), kept alive by `owner`: writable, so that
/// in-place edits change the mesh they view.
template <class T>
py::array view_of(const py::object& owner, T* data, std::size_t rows, std::size_t cols, std::size_t row_bytes) {
  static T empty{};  // numpy needs a pointer even for no element
  std::vector<py::ssize_t> shape{py::ssize_t(rows)}, strides{py::ssize_t(row_bytes)};
  if (cols != 1) shape.push_back(py::ssize_t(cols)), strides.push_back(py::ssize_t(sizeof(T)));
  return py::array(py::dtype::of<T>(), shape, strides, data ? data : &empty, owner);
}

/// The exact skin's area and volume (skin/skin_measures.h) as a dict.
py::dict analytic_measures(const skin::Molecule& mol, double probe, int threads) {
  skin::SkinMeasures m;
  {
    py::gil_scoped_release release;
    m = skin::skin_measures(skin::weighted_points(mol, probe), threads);
  }
  py::dict d;
  d["area_A2"] = m.area;
  d["volume_A3"] = m.volume;
  d["patch_cells"] = m.patch_cells;
  return d;
}

void check_probe_and_threads(double probe, int threads) {
  if (!(probe >= 0 && probe <= skin::kMaxRadius)) throw InputError("", 0, "the probe radius must lie in [0, 100] Å");
  if (threads < 0) throw InputError("", 0, "threads must be >= 0");
}

PyMesh mesh(const py::object& source, double probe, const std::string& algorithm, bool check, int threads,
            bool analytic, const std::string& cavities, double min_cavity_volume, const py::object& model,
            const py::object& assembly, const py::object& chains) {
  if (algorithm != "sweep" && algorithm != "dynamic")
    throw InputError("", 0, "algorithm must be 'sweep' or 'dynamic', not '" + algorithm + "'");
  check_probe_and_threads(probe, threads);
  const skin::Molecule mol = molecule_of(source, {model, assembly, chains});
  mesher::MeshOptions options;
  options.algorithm = mesher::algorithm_named(algorithm);
  options.probe_radius = probe;
  options.check = check;
  options.threads = threads;
  options.shells = shell_selection(cavities, min_cavity_volume);
  // As on the command line: where the sweep fails, the static baseline meshes
  // the skin, and stats["static_fallback"] says why.
  options.static_fallback = true;
  mesher::SummaryContext context;
  if (is_path(source)) context.input = path_of(source);
  context.atoms = mol.atoms.size();
  PyMesh out;
  std::string summary;
  {
    py::gil_scoped_release release;
    mesher::MeshResult res = mesher::mesh_skin(mol, options);
    const std::vector<geometry::WeightedPoint> points = skin::weighted_points(mol, probe);
    if (analytic) context.exact_measures_of = &points;
    // The same schema as `skinmesh mesh --stats` (mesher/summary.h).
    summary = mesher::run_summary(res, options, context).dump();
    if (res.checked) out.ok = res.ok();
    out.probe = probe;
    out.shells = res.shells;
    out.topology = res.expected_topology;
    out.atoms = mol.atoms.size();
    if (res.checked && res.ok()) out.points = points;
    out.mesh = std::move(res.mesh);
    out.vertex_data = std::move(res.vertex_data);
  }
  out.stats = py::module_::import("json").attr("loads")(summary);
  return out;
}

/// The check's report as a Python dict (through its JSON).
py::dict check(const py::object& source, const py::object& mesh_or_path, double probe, bool strict,
               const std::string& cavities, double min_cavity_volume, const py::object& model,
               const py::object& assembly, const py::object& chains) {
  const skin::Molecule mol = molecule_of(source, {model, assembly, chains});
  geometry::IndexedMesh m;
  verify::SkinCheckOptions options;
  options.shells = shell_selection(cavities, min_cavity_volume);
  if (py::isinstance<PyMesh>(mesh_or_path)) {
    m = mesh_or_path.cast<const PyMesh&>().mesh;
  } else {
    const std::string path = path_of(mesh_or_path);
    py::gil_scoped_release release;
    m = skin::read_skin_mesh(path);
    // Formats that round positions, as `skinmesh check` reads them: distances
    // checked to the rounding; [L], [U] and the restricted Delaunay property,
    // which hold for the exact positions, left out unless strict.
    const double rounding = skin::position_rounding(path, m);
    options.max_vertex_distance = std::max(options.max_vertex_distance, rounding);
    if (rounding > 0 && !strict) options.check_size_conditions = options.check_restricted_delaunay = false;
  }
  std::string json;
  {
    py::gil_scoped_release release;
    const std::vector<geometry::WeightedPoint> points = skin::weighted_points(mol, probe);
    const Vec3 centre = skin::local_frame_centre(points);
    for (Vec3& p : m.positions) p -= centre;
    skin::RunContext run;
    run.threads = 0;  // every core
    const skin::SkinSurface skin(skin::translated(points, centre), run.threads);
    json = verify::check_skin_mesh(skin, m, options, run).to_json();
  }
  return py::module_::import("json").attr("loads")(json);
}

}  // namespace

PYBIND11_MODULE(skinmesh, m) {
  m.attr("__version__") = SKINMESH_VERSION;
  m.doc() =
      "skinmesh: guaranteed-quality triangle meshes of molecular skin surfaces (Cheng & Shi, IEEE Visualization "
      "2004). mesh() meshes a molecule file or an array of atoms; check() verifies a mesh against the analytic skin.";
  static py::exception<InputError> input_error(m, "InputError", PyExc_ValueError);
  static py::exception<TopologyError> topology_error(m, "TopologyError", PyExc_RuntimeError);
  static py::exception<GeometryError> geometry_error(m, "GeometryError", PyExc_RuntimeError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const InputError& e) {
      input_error(e.what());
    } catch (const TopologyError& e) {
      topology_error((std::string("topology: ") + e.what()).c_str());
    } catch (const GeometryError& e) {
      geometry_error((std::string("geometry: ") + e.what()).c_str());
    }
  });

  py::class_<PyMesh>(
      m, "Mesh",
      "A triangle mesh of the skin: vertices (n, 3) float64 in Å, triangles (m, 3) int32 "
      "counter-clockwise seen from outside, unit outward normals (n, 3), atom (n,) int32 (0-based "
      "index of the atom whose skin patch holds the vertex, -1 if unknown), rho (n,) local length "
      "scale in Å (None if a file held none); the arrays are views of the mesh (edits change it); stats: a "
      "dict of what the run measured; ok: True or False after a check, None if never checked.")
      .def_property_readonly(
          "vertices",
          [](py::object self) {
            PyMesh& s = self.cast<PyMesh&>();
            return view_of<double>(self, s.mesh.positions.empty() ? nullptr : s.mesh.positions[0].data(),
                                   s.mesh.positions.size(), 3, sizeof(Vec3));
          },
          "(n, 3) float64, Å: a view of the mesh's positions (edits change the mesh)")
      .def_property_readonly(
          "triangles",
          [](py::object self) {
            // Index is uint32; indices below 2^31 read the same as int32, and
            // write() refuses a triangle whose index is out of range.
            static_assert(sizeof(Index) == sizeof(std::int32_t) && sizeof(std::array<Index, 3>) == 3 * sizeof(Index));
            PyMesh& s = self.cast<PyMesh&>();
            return view_of<std::int32_t>(
                self, s.mesh.triangles.empty() ? nullptr : reinterpret_cast<std::int32_t*>(s.mesh.triangles[0].data()),
                s.mesh.triangles.size(), 3, sizeof(std::array<Index, 3>));
          },
          "(m, 3) int32: a view of the triangles, counter-clockwise seen from outside")
      .def_property_readonly(
          "normals",
          [](py::object self) -> py::object {
            PyMesh& s = self.cast<PyMesh&>();
            if (s.mesh.normals.size() != s.mesh.positions.size()) return py::none();
            return view_of<double>(self, s.mesh.normals.empty() ? nullptr : s.mesh.normals[0].data(),
                                   s.mesh.normals.size(), 3, sizeof(Vec3));
          },
          "(n, 3) float64 unit outward normals (a view), or None for a file that holds none")
      .def_property_readonly(
          "atom",
          [](py::object self) {
            PyMesh& s = self.cast<PyMesh&>();
            return view_of<std::int32_t>(self, s.vertex_data.atom.data(), s.vertex_data.atom.size(), 1,
                                         sizeof(std::int32_t));
          },
          "(n,) int32: a view of each vertex's atom (0-based), -1 where unknown")
      .def_property_readonly(
          "rho",
          [](py::object self) -> py::object {
            PyMesh& s = self.cast<PyMesh&>();
            if (s.vertex_data.rho.size() != s.mesh.positions.size()) return py::none();
            return view_of<double>(self, s.vertex_data.rho.data(), s.vertex_data.rho.size(), 1, sizeof(double));
          },
          "(n,) float64: a view of the local length scale rho (Å), or None for a file that holds none")
      .def(
          "atom_areas",
          [](const PyMesh& s, std::optional<std::size_t> atoms) {
            // The atom count of mesh()'s molecule, else the caller's, else
            // one past the largest atom index the vertices name.
            std::size_t n = atoms ? *atoms : s.atoms;
            if (!atoms && n == 0)
              for (std::int32_t a : s.vertex_data.atom) n = std::max(n, static_cast<std::size_t>(std::max(a, -1) + 1));
            std::vector<double> areas;
            try {
              areas = skin::mesh_atom_areas(s.mesh, s.vertex_data.atom, n);
            } catch (const std::invalid_argument& e) {
              throw InputError("", 0, e.what());
            }
            return array_of<double>(areas.size(), 1, [&](std::size_t i, std::size_t) { return areas[i]; });
          },
          py::arg("atoms") = py::none(),
          "The mesh's area per atom (Å², float64 array): each triangle's area, a third to the atom of each corner "
          "(Mesh.atom). Its length is the molecule's atom count for a mesh made by mesh(), else `atoms`, else one "
          "past the largest atom index. Compare skinmesh.atom_areas(), the exact skin's.")
      .def_readonly("stats", &PyMesh::stats)
      .def_property_readonly(
          "ok", [](const PyMesh& s) -> py::object { return s.ok ? py::cast(*s.ok) : py::none(); },
          "True if the mesh passed its check, False if it failed, None if it was never checked (mesh(check=False), "
          "read_mesh(): skinmesh.check() verifies it)")
      .def(
          "write",
          [](const PyMesh& s, const py::object& path, int msms_decimals, bool force, bool ascii) {
            const std::string p = path_of(path);
            py::gil_scoped_release release;
            skin::SkinMeshWriteOptions w;
            w.msms_decimals = msms_decimals;
            w.geometry.ascii = ascii;
            w.probe_radius = s.probe;
            const geometry::PositionStorage storage = skin::position_storage(p, w);
            // As the command line does: a mesh that passed its check is checked
            // again at the positions a lossy format stores.
            if (storage.lossy() && !force && !s.points.empty()) {
              const Vec3 centre = skin::local_frame_centre(s.points);
              const skin::SkinSurface skin(skin::translated(s.points, centre), 0);
              double moved = 0;
              verify::SkinCheckOptions expect;
              skin::RunContext every_core;
              every_core.threads = 0;
              if (s.shells) {  // the kept shells of a mesh whose every shell passed
                expect.expected_topology = skin::kept_topology(s.topology, *s.shells);
                expect.expected_component_euler = s.shells->kept_euler;
              }
              const verify::SkinCheckReport rep = mesher::check_stored_positions(skin, s.mesh, Vec3::Zero(), centre,
                                                                                 storage, expect, every_core, moved);
              if (!rep.ok())
                throw InputError(p, 0,
                                 "stores positions as " + storage.describe() +
                                     ", which breaks the mesh: " + rep.problems.front() + "; not written (" +
                                     (skin::is_msms_path(p) ? "msms_decimals=6 or more keeps it, "
                                                            : ".ply or ascii=True keeps positions exact, ") +
                                     "force=True writes it anyway)");
            }
            skin::write_skin_mesh(p, s.mesh, s.vertex_data, w);
          },
          py::arg("path"), py::arg("msms_decimals") = 3, py::arg("force") = false, py::arg("ascii") = false,
          "Writes the mesh; the format by the extension: .ply .off .obj .stl .vtk .vtp .vtu, or .vert (MSMS .vert and "
          ".face, "
          "positions with msms_decimals decimals, 3 to 12). ascii=True writes .ply and .stl as text (TetGen reads "
          "only text PLY and STL; ASCII STL keeps exact positions). A checked mesh written to a format that rounds "
          "positions (MSMS, binary STL) is checked again as the file stores them; if that fails, InputError names "
          "what broke and nothing is written, unless force=True.")
      .def("__repr__", [](const PyMesh& s) {
        return "<skinmesh.Mesh: " + std::to_string(s.mesh.positions.size()) + " vertices, " +
               std::to_string(s.mesh.triangles.size()) + " triangles" +
               (!s.ok   ? ", not checked"
                : *s.ok ? ""
                        : ", FAILED its check") +
               ">";
      });

  m.def("mesh", &mesh, py::arg("path_or_atoms"), py::arg("probe") = 1.4, py::arg("algorithm") = "sweep",
        py::arg("check") = true, py::arg("threads") = 0, py::arg("analytic") = false, py::arg("cavities") = "keep",
        py::arg("min_cavity_volume") = 0.0, py::arg("model") = py::none(), py::arg("assembly") = py::none(),
        py::arg("chains") = py::none(),
        "Meshes the skin (shrink factor 1/2) of a molecule: a file (.pdb .cif .pqr .xyzr .xyzrn, optionally .gz) or an "
        "array (n, 4) of x, y, z, radius in Å. Atom weights are 2 (r + probe)². algorithm: 'sweep' (Cheng & Shi "
        "2004) or 'dynamic' (the dynamic-skin baseline). With check=True the mesh is verified and Mesh.ok says "
        "whether it passed (None with check=False). threads=0: every core; the mesh is the same for every count. "
        "stats['surface'] holds the "
        "mesh's area (Å²) and enclosed volume (Å³), per component and in all; analytic=True adds "
        "stats['surface']['analytic'], the same of the exact skin (see measures()). Where the sweep fails, the "
        "whole skin is meshed by the static dynamic-skin baseline instead: stats['algorithm'] is then 'dynamic' "
        "and stats['static_fallback'] says why. Raises InputError for a bad file, array or option, TopologyError "
        "or GeometryError if the algorithm fails. cavities='remove' keeps the outer surfaces only (as MSMS writes), "
        "'only' the cavities only, and cavities enclosing less than min_cavity_volume Å³ are left out: the check "
        "verifies every shell first, and stats['surface']['shells'] says what was kept. From a PDB or mmCIF file, "
        "model=N reads the model numbered N (the first by default; model_numbers() lists them), assembly='1' the "
        "biological assembly of that id expanded (copies of chain A are named A, A2, ...), chains='A,B' (or a "
        "list) only those chains (chain_names() lists them), as --model, --assembly and --chains do.");
  m.def(
      "measures",
      [](const py::object& source, double probe, int threads, const py::object& model, const py::object& assembly,
         const py::object& chains) {
        check_probe_and_threads(probe, threads);
        return analytic_measures(molecule_of(source, {model, assembly, chains}), probe, threads);
      },
      py::arg("path_or_atoms"), py::arg("probe") = 1.4, py::arg("threads") = 0, py::arg("model") = py::none(),
      py::arg("assembly") = py::none(), py::arg("chains") = py::none(),
      "Area (area_A2, Å²) and enclosed volume (volume_A3, Å³, cavities negative) of the exact skin of a molecule, "
      "integrated over its sphere and hyperboloid patches without a mesh (relative accuracy about 1e-10). "
      "Returns a dict; patch_cells counts the mixed cells whose patch is not empty. model, assembly and chains "
      "select atoms of a structure file as in mesh().");
  m.def(
      "atom_areas",
      [](const py::object& source, double probe, int threads, const py::object& model, const py::object& assembly,
         const py::object& chains) {
        check_probe_and_threads(probe, threads);
        const skin::Molecule mol = molecule_of(source, {model, assembly, chains});
        std::vector<double> areas;
        {
          py::gil_scoped_release release;
          areas = skin::atom_areas(skin::weighted_points(mol, probe), threads);
        }
        return array_of<double>(areas.size(), 1, [&](std::size_t i, std::size_t) { return areas[i]; });
      },
      py::arg("path_or_atoms"), py::arg("probe") = 1.4, py::arg("threads") = 0, py::arg("model") = py::none(),
      py::arg("assembly") = py::none(), py::arg("chains") = py::none(),
      "The exact skin's area per atom (Å², float64 array, one entry per atom in input order), without a mesh: each "
      "sphere patch belongs to its atom, and each hyperboloid or concave sphere patch is cut among its atoms by "
      "their power bisectors (the rule of Mesh.atom). The entries sum to measures()['area_A2'] within about 1e-10 "
      "relative; redundant atoms (no skin) get 0. model, assembly and chains select atoms of a structure file as in "
      "mesh().");
  m.def(
      "vdw_radii",
      [](const std::vector<std::string>& elements) {
        std::vector<double> radii;
        for (const std::string& e : elements)
          radii.push_back(skin::van_der_waals_radius(skin::canonical_element_symbol(e)).radius);
        return array_of<double>(radii.size(), 1, [&](std::size_t i, std::size_t) { return radii[i]; });
      },
      py::arg("elements"),
      "The van der Waals radius (Å, float64 array) of each element symbol, as the file readers give atoms: "
      "Bondi's, and 2.0 Å for an element Bondi does not list. For atoms given as arrays, e.g. from an MDAnalysis "
      "AtomGroup's elements.");
  m.def("check", &check, py::arg("path_or_atoms"), py::arg("mesh"), py::arg("probe") = 1.4, py::arg("strict") = false,
        py::arg("cavities") = "keep", py::arg("min_cavity_volume") = 0.0, py::arg("model") = py::none(),
        py::arg("assembly") = py::none(), py::arg("chains") = py::none(),
        "Verifies a mesh (a Mesh, or a mesh file) against the skin of the molecule: closed, manifold, oriented, "
        "no self-intersections, topology, distance to the skin, angles, [L], [U], restricted Delaunay. Returns "
        "the report as a dict; report['problems'] is empty if every check passed. A file that rounds positions "
        "(MSMS, STL, float32 coordinates) is checked to its rounding, without [L], [U] and the restricted "
        "Delaunay test (they hold for the exact positions) unless strict=True, as `skinmesh check` does. cavities and "
        "min_cavity_volume say which shells the mesh holds, and model, assembly and chains which atoms, as mesh() "
        "took them.");
  m.def(
      "model_numbers",
      [](const py::object& path) {
        const std::string p = path_of(path);
        py::gil_scoped_release release;
        return skin::model_numbers(p);
      },
      py::arg("path"),
      "The model numbers of a PDB or mmCIF file, in file order (a file without models holds model 1): the values "
      "mesh(model=...) takes. Raises InputError for an unreadable file.");
  m.def(
      "chain_names",
      [](const py::object& path, const py::object& model, const py::object& assembly) {
        const skin::Molecule mol = molecule_of(path, {model, assembly, py::none()});
        return skin::chain_names(mol);
      },
      py::arg("path"), py::arg("model") = py::none(), py::arg("assembly") = py::none(),
      "The chain names of a structure file's atoms (of the model, expanded to the assembly if one is named), in "
      "order of first appearance: the values mesh(chains=...) takes.");
  m.def(
      "read_mesh",
      [](const py::object& path) {
        const std::string p = path_of(path);
        PyMesh out;
        {
          py::gil_scoped_release release;
          out.mesh = skin::read_skin_mesh(p, &out.vertex_data);
          // As the docstring says: atom -1 where the file names none.
          if (out.vertex_data.atom.size() != out.mesh.positions.size())
            out.vertex_data.atom.assign(out.mesh.positions.size(), -1);
        }
        out.stats["vertices"] = out.mesh.positions.size();
        out.stats["triangles"] = out.mesh.triangles.size();
        return out;
      },
      py::arg("path"), "Reads a mesh file (.ply .off .obj .stl .vtk .vtp .vtu .vert/.face).");
}
