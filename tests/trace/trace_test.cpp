// tests/trace/trace_test.cpp: the recorder of `skinmesh trace` against the
// pipeline it records. The trace is replayed independently of the recorder
// (trace/FORMAT.md: a face is drawn at step s iff born <= s < died; vertices
// at their latest move): every step's triangle count agrees with the replay,
// the last step is the closed output mesh (same triangle count, area and
// enclosed volume, same smallest angle), the sweep's key operations are
// steps of their own, and the page template is filled safely.
#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "dynamic/dynamic_skin.h"
#include "mesher/pipeline.h"
#include "tests/skin/skin_test_util.h"
#include "trace/trace_recorder.h"

using namespace skinmesh;
using json = nlohmann::json;

namespace {

/// The trace replayed at a step: faces drawn, vertex positions.
struct Replay {
  std::vector<std::array<int, 3>> faces;
  std::vector<Vec3> positions;  // every vertex record, at the step
};

Replay replay(const json& doc, long s) {
  Replay r;
  const std::vector<double> xyz = doc["vertices"].get<std::vector<double>>();
  for (std::size_t i = 0; i + 2 < xyz.size(); i += 3) r.positions.emplace_back(xyz[i], xyz[i + 1], xyz[i + 2]);
  const std::vector<double> moves = doc["moves"].get<std::vector<double>>();
  for (std::size_t i = 0; i + 4 < moves.size(); i += 5)  // moves are in step order
    if (moves[i + 1] <= s) r.positions[std::size_t(moves[i])] = Vec3(moves[i + 2], moves[i + 3], moves[i + 4]);
  const std::vector<int> faces = doc["faces"].get<std::vector<int>>();
  const std::vector<int> steps = doc["face_steps"].get<std::vector<int>>();
  for (std::size_t f = 0; 3 * f + 2 < faces.size(); ++f) {
    const int born = steps[2 * f], died = steps[2 * f + 1];
    if (born <= s && (died == -1 || s < died)) r.faces.push_back({faces[3 * f], faces[3 * f + 1], faces[3 * f + 2]});
  }
  return r;
}

/// Number of edges used by exactly one face (the front), and whether any
/// edge is used by more than two.
std::pair<std::size_t, bool> boundary_edges(const std::vector<std::array<int, 3>>& faces) {
  std::map<std::pair<int, int>, int> count;
  for (const auto& f : faces)
    for (int k = 0; k < 3; ++k) ++count[std::minmax(f[k], f[(k + 1) % 3])];
  std::size_t boundary = 0;
  bool non_manifold = false;
  for (const auto& [e, n] : count) boundary += n == 1, non_manifold |= n > 2;
  return {boundary, non_manifold};
}

/// Area (Å²) and enclosed volume (Å³, divergence theorem) of triangles.
std::pair<double, double> area_volume(const std::vector<Vec3>& p, const std::vector<std::array<int, 3>>& faces) {
  double area = 0, volume = 0;
  for (const auto& f : faces) {
    const Vec3 &a = p[f[0]], &b = p[f[1]], &c = p[f[2]];
    area += (b - a).cross(c - a).norm() / 2;
    volume += a.dot(b.cross(c)) / 6;
  }
  return {area, volume};
}

std::pair<double, double> area_volume(const geometry::IndexedMesh& m, const Vec3& shift) {
  std::vector<Vec3> p;
  for (const Vec3& x : m.positions) p.push_back(x - shift);
  std::vector<std::array<int, 3>> faces;
  for (const auto& t : m.triangles) faces.push_back({int(t[0]), int(t[1]), int(t[2])});
  return area_volume(p, faces);
}

/// The checks every trace must pass against its final mesh.
void check_against(const json& doc, const geometry::IndexedMesh& mesh, const Vec3& frame_centre) {
  const json& steps = doc["steps"];
  REQUIRE(steps.size() >= 2);
  CHECK(replay(doc, 0).faces.empty());
  // Every step's counter of triangles is the replay's (a sample of steps
  // plus the last: a full replay per step is quadratic).
  const long last = long(steps.size()) - 1;
  for (long s = 0; s <= last; s += std::max<long>(1, last / 40)) {
    CAPTURE(s);
    CHECK(steps[s]["counters"]["triangles"].get<std::size_t>() == replay(doc, s).faces.size());
  }
  const Replay end = replay(doc, last);
  CHECK(end.faces.size() == mesh.triangles.size());
  CHECK(steps[last]["counters"]["triangles"].get<std::size_t>() == end.faces.size());
  const auto [boundary, non_manifold] = boundary_edges(end.faces);
  CHECK(boundary == 0);
  CHECK_FALSE(non_manifold);
  const auto [area, volume] = area_volume(end.positions, end.faces);
  const auto [area_out, volume_out] = area_volume(mesh, frame_centre);
  CHECK(area == doctest::Approx(area_out).epsilon(1e-4));
  CHECK(volume == doctest::Approx(volume_out).epsilon(1e-4));
  CHECK(volume > 0);
  // Quality: the smallest angle over the final faces is the check's.
  const std::vector<int> fsteps = doc["face_steps"].get<std::vector<int>>();
  const std::vector<double> angle = doc["quality"]["min_angle"].get<std::vector<double>>();
  double worst = 180;
  for (std::size_t f = 0; f < angle.size(); ++f)
    if (fsteps[2 * f + 1] == -1) worst = std::min(worst, angle[f]);
  CHECK(worst == doctest::Approx(doc["check"]["min_angle"].get<double>()).epsilon(2e-3));
  // Face records: born <= died, and born and died at existing steps.
  for (std::size_t f = 0; 2 * f + 1 < fsteps.size(); ++f) {
    const int born = fsteps[2 * f], died = fsteps[2 * f + 1];
    REQUIRE(born >= 0);
    REQUIRE(born <= last);
    if (died != -1) REQUIRE((died >= born && died <= last));
  }
}

}  // namespace

TEST_SUITE("trace") {

TEST_CASE("a trace of the sweep replays to the output mesh, with every key operation a step") {
  const auto points = test::cube_corners(1.4);  // Figure 4's configuration
  trace::TraceOptions opt;
  opt.max_steps = 300;
  trace::TraceSummary summary;
  const json doc = trace::record_trace(points, opt, &summary);
  const mesher::MeshResult res = mesher::mesh_skin(points);
  REQUIRE(res.ok());
  CHECK(summary.ok);
  CHECK(summary.triangles == res.mesh.triangles.size());
  CHECK(doc["format"] == "skinmesh-trace");
  check_against(doc, res.mesh, res.frame_centre);
  // The Morse–Smale complex: every critical point, with its index.
  CHECK(doc["critical"].size() == std::size_t(res.critical.minima + res.critical.saddles + res.critical.maxima));
  std::map<int, int> by_index;
  for (const json& c : doc["critical"]) ++by_index[c["index"].get<int>()];
  CHECK(by_index[0] == res.critical.minima);
  CHECK(by_index[1] == res.critical.saddles);
  CHECK(by_index[2] == res.critical.maxima);
  CHECK(doc["lines"].size() > 0);
  // Creations, bridges and seals each end a step of their own.
  std::map<std::string, std::size_t> ops;
  for (const json& s : doc["steps"]) ++ops[s["op"].get<std::string>()];
  CHECK(ops["creation"] == res.sweep.creations);
  CHECK(ops["bridge"] == res.sweep.bridges);
  // Seals at the end of the sweep: one step each (small holes are counted in
  // SweepStats::seals too, but may be merged with creeps).
  CHECK(ops["seal"] >= 1);
  CHECK(ops["seal"] <= res.sweep.seals);
  // The step budget is kept (key operations may add a few).
  CHECK(doc["steps"].size() <= opt.max_steps + res.sweep.creations + res.sweep.bridges + res.sweep.seals + 4);
  // The sweep's steps show a front; the refinement's steps keep it closed.
  bool front_seen = false;
  for (std::size_t s = 0; s < doc["steps"].size(); ++s) {
    if (doc["steps"][s]["stage"] != "sweep") continue;
    if (boundary_edges(replay(doc, long(s)).faces).first > 0) {
      front_seen = true;
      break;
    }
  }
  CHECK(front_seen);
}

TEST_CASE("every operation is a step with --every 1; the trace is the same for every thread count") {
  const auto points = test::two_balls();
  trace::TraceOptions opt;
  opt.every = 1;
  opt.mesh.threads = 1;
  const json one = trace::record_trace(points, opt);
  opt.mesh.threads = 2;
  const json two = trace::record_trace(points, opt);
  CHECK(one == two);
  mesher::MeshOptions counting;
  std::size_t sweep_ops = 0, refine_ops = 0;
  counting.sweep.observer = [&](const front::SweepEvent&) { ++sweep_ops; };
  counting.refinement.observer = [&](refine::RefineOperation, const geometry::SurfaceMesh&) { ++refine_ops; };
  const mesher::MeshResult res = mesher::mesh_skin(points, counting);
  std::size_t sweep_steps = 0, refine_steps = 0;
  for (const json& s : one["steps"]) sweep_steps += s["stage"] == "sweep", refine_steps += s["stage"] == "refine";
  CHECK(sweep_steps == sweep_ops);
  CHECK(refine_steps == refine_ops);
  CHECK(one["operations"].get<std::size_t>() == sweep_ops + refine_ops);
  check_against(one, res.mesh, res.frame_centre);
}

TEST_CASE("a trace of the dynamic-skin baseline replays to its output mesh") {
  const auto points = test::two_balls();
  trace::TraceOptions opt;
  opt.mesh.algorithm = mesher::Algorithm::Dynamic;
  trace::TraceSummary summary;
  const json doc = trace::record_trace(points, opt, &summary);
  mesher::MeshOptions dynamic;
  dynamic.algorithm = mesher::Algorithm::Dynamic;
  const mesher::MeshResult res = mesher::mesh_skin(points, dynamic);
  REQUIRE(res.ok());
  CHECK(summary.ok);
  check_against(doc, res.mesh, res.frame_centre);
  CHECK(doc["critical"].empty());
  std::size_t growth = 0;
  for (const json& s : doc["steps"]) growth += s["stage"] == "growth";
  CHECK(growth >= 2);
  CHECK_FALSE(doc["moves"].empty());  // the samples move as the skin grows
}

TEST_CASE("the page template is filled once, and no string in the data can end its script element") {
  json doc = {{"title", "</script><script>alert(1)</script>"}, {"n", 1}};
  const std::string tmpl = std::string("<html><script id=\"skinmesh-trace\" type=\"application/json\">") +
                           trace::kTracePlaceholder + "</script></html>";
  const std::string page = trace::fill_viewer_template(tmpl, doc);
  CHECK(page.find("</script><script>") == std::string::npos);
  const std::size_t open = page.find("application/json\">") + 18, close = page.find("</script>", open);
  std::string data = page.substr(open, close - open);
  CHECK(data.find('<') == std::string::npos);
  CHECK(json::parse(data) == doc);  // "\u003c" is the JSON escape of "<"
  CHECK_THROWS_AS(trace::fill_viewer_template("<html></html>", doc), std::runtime_error);
  CHECK_THROWS_AS(trace::fill_viewer_template(tmpl + tmpl, doc), std::runtime_error);
}

TEST_CASE("bad options are errors") {
  CHECK_THROWS_AS(mesher::algorithm_named("marching cubes"), std::invalid_argument);
  trace::TraceOptions opt;
  opt.max_steps = 3;
  CHECK_THROWS_AS(trace::record_trace(test::two_balls(), opt), std::invalid_argument);
}

}  // TEST_SUITE
