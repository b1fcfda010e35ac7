// A user's program against the installed skinmesh: meshes the weighted points
// of one or two atoms given on the command line (or a molecule file) and
// prints what the pipeline returns. Exit 0 only if the mesh passed its check.
#include <cstdio>
#include <string>
#include <vector>

#include "mesher/pipeline.h"
#include "skin/molecule_io.h"

int main(int argc, char** argv) {
  skinmesh::mesher::MeshResult r;
  if (argc > 1) {
    r = skinmesh::mesher::mesh_skin(skinmesh::skin::read_molecule(argv[1]));
  } else {
    const std::vector<skinmesh::geometry::WeightedPoint> points = {{skinmesh::Vec3(0, 0, 0), 8.0},
                                                                   {skinmesh::Vec3(3, 0, 0), 8.0}};
    r = skinmesh::mesher::mesh_skin(points);
  }
  std::printf("vertices %zu triangles %zu normals %zu atoms %zu min_angle %.3f ok %d\n", r.mesh.positions.size(),
              r.mesh.triangles.size(), r.mesh.normals.size(), r.vertex_data.atom.size(), r.check.mesh.min_angle_deg,
              int(r.ok()));
  return r.ok() && !r.mesh.triangles.empty() ? 0 : 1;
}
