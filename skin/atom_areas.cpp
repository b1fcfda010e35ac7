// skin/atom_areas.cpp: per-atom areas of a mesh, and the .area file.
#include "skin/atom_areas.h"

#include <cstdio>
#include <stdexcept>

#include "geometry/io/mesh_io.h"

namespace skinmesh::skin {

std::vector<double> mesh_atom_areas(const geometry::IndexedMesh& mesh, const std::vector<std::int32_t>& atom,
                                    std::size_t num_atoms) {
  const std::size_t nv = mesh.positions.size();
  std::vector<double> areas(num_atoms, 0.0);
  if (atom.empty()) return areas;  // no vertex names an atom
  if (atom.size() != nv)
    throw std::invalid_argument("mesh_atom_areas: " + std::to_string(atom.size()) + " atoms for " + std::to_string(nv) +
                                " vertices");
  for (const auto& t : mesh.triangles) {
    if (t[0] >= nv || t[1] >= nv || t[2] >= nv)
      throw std::invalid_argument("mesh_atom_areas: a triangle's vertex index is out of range");
    const Vec3 &a = mesh.positions[t[0]], &b = mesh.positions[t[1]], &c = mesh.positions[t[2]];
    const double third = (b - a).cross(c - a).norm() / 6.0;
    for (int i = 0; i < 3; ++i) {
      const std::int32_t k = atom[t[i]];
      if (k >= 0 && static_cast<std::size_t>(k) < num_atoms) areas[static_cast<std::size_t>(k)] += third;
    }
  }
  return areas;
}

void write_area_file(const std::string& path, const std::vector<double>& skin_area,
                     const std::vector<double>& mesh_area, const std::vector<std::string>& names) {
  const std::size_t n = skin_area.size();
  if (mesh_area.size() != n || (!names.empty() && names.size() != n))
    throw std::invalid_argument("write_area_file: arrays of different lengths");
  std::string text = names.empty() ? "#    atom       skin_area       mesh_area\n"
                                   : "#    atom       skin_area       mesh_area  name\n";
  char line[96];
  for (std::size_t i = 0; i < n; ++i) {
    std::snprintf(line, sizeof line, "%9zu %15.6f %15.6f", i + 1, skin_area[i], mesh_area[i]);
    text += line;
    if (!names.empty()) text += "  " + names[i];
    text += '\n';
  }
  geometry::write_file_atomically(path, text, "area file");
}

}  // namespace skinmesh::skin
