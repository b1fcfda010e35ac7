// trace/trace_recorder.cpp: record_trace() — a counting run, then a recording
// run whose observers turn every operation (or every k-th) into a step of
// the history (trace/FORMAT.md). The history keeps a mirror of the mesh as
// last recorded and, at each recorded step, compares the mesh with it: new
// faces open a face record, deleted or changed faces close theirs, moved
// vertices add a move. The sweep's and the refinement's half-edge mesh is
// compared by face index (indices are never reused before the compaction);
// the dynamic algorithm's restricted Delaunay triangulation, extracted anew
// at every step, by the faces' vertex triples.
// Notes: papers/trace/README.md
#include "trace/trace_recorder.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <optional>
#include <stdexcept>
#include <unordered_map>

#include "geometry/check/mesh_checks.h"
#include "skin/size_conditions.h"
#include "skin/vertex_data.h"

namespace skinmesh::trace {

namespace {

using json = nlohmann::json;
using geometry::Face;
using geometry::SurfaceMesh;
using geometry::Vertex;

/// x rounded to 1/scale (scale a power of ten): the nearest double to the
/// decimal, so that JSON prints it short.
double round_to(double x, double scale) { return std::round(x * scale) / scale; }

/// Positions are written to 1e-4 Å (trace/FORMAT.md). [chosen] far below any
/// edge of a mesh that meets [L], and short in JSON.
constexpr double kPositionScale = 1e4;
/// The check's smallest angle is written to 1e-6 degrees, the angle bound of
/// [L]/[U] to 1e-4 degrees. [chosen]
constexpr double kAngleScale = 1e6, kBoundScale = 1e4;
/// A vertex that moved less than this (squared, Å²) is not recorded as moved.
/// [chosen] 1e-5 Å, below the positions' written precision.
constexpr double kMinMoveSquared = 1e-10;
/// Integral lines are thinned to points at least this far apart (Å). [chosen]
/// well below the lines' curvature radii (rho), so the drawn curve looks the same.
constexpr double kLineSpacing = 0.1;
/// Shares of the recorded steps (TraceOptions::max_steps) given to the sweep's
/// and the refinement's operations, and to the baseline's growth steps; the
/// rest is left for the stages recorded whole. [chosen]
constexpr double kSweepShare = 0.6, kRefineShare = 0.35, kGrowthShare = 0.9;
/// Bytes of the trace per sample per recorded growth step. [derived] its id
/// and three coordinates of about ten characters each in the JSON.
constexpr double kBytesPerGrowthSample = 45.0;

json point_json(const Vec3& p) {
  return json::array(
      {round_to(p.x(), kPositionScale), round_to(p.y(), kPositionScale), round_to(p.z(), kPositionScale)});
}

/// Per-triangle quality of trace/FORMAT.md: smallest angle (degrees), the
/// [L] ratio min over edges of (|ab|/2) / ((C/Q) max(rho_a, rho_b)) and the
/// [U] ratio C Q min(rho) / circumradius (Cheng & Shi §2.2; a condition
/// holds iff its ratio exceeds 1).
std::array<double, 3> face_quality(const std::array<Vec3, 3>& p, const std::array<double, 3>& rho,
                                   const skin::SizeConstants& size) {
  const double angle = geometry::min_angle(p[0], p[1], p[2]) * 180 / kPi;
  double L = std::numeric_limits<double>::infinity();
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3;
    const double bound = size.C / size.Q * std::max(rho[i], rho[j]);
    if (bound > 0) L = std::min(L, (p[i] - p[j]).norm() / 2 / bound);
  }
  const double R = skin::circumradius(p[0], p[1], p[2]);
  const double U = R > 0 && std::isfinite(R) ? size.C * size.Q * std::min({rho[0], rho[1], rho[2]}) / R : 0;
  return {angle, std::isfinite(L) ? L : 0, U};
}

/// The history of the mesh: vertex and face records with the steps at which
/// they appear and disappear (trace/FORMAT.md).
class History {
 public:
  /// Compares the half-edge mesh with the mirror and records the changes as
  /// happening at `step`. Returns the number of vertices moved.
  std::size_t snapshot(const SurfaceMesh& mesh, int step) {
    std::size_t moved = 0;
    for (Vertex v : mesh.vertices()) moved += see_vertex(v.idx(), mesh.position(v), step);
    if (face_record_.size() < mesh.faces_size()) face_record_.resize(mesh.faces_size(), -1);
    for (std::size_t i = 0; i < mesh.faces_size(); ++i) {
      const Face f(static_cast<Index>(i));
      int& rec = face_record_[i];
      if (mesh.is_deleted(f)) {
        if (rec >= 0) close(rec, step), rec = -1;
        continue;
      }
      std::array<int, 3> t;
      int k = 0;
      for (Vertex v : mesh.vertices(f)) t[k++] = vertex_record_[v.idx()];
      t = canonical(t);
      if (rec >= 0 && same(rec, t)) continue;
      if (rec >= 0) close(rec, step);
      rec = open(t, step);
    }
    return moved;
  }

  /// Compares an extracted mesh (vertex i is the sample ids[i]) with the
  /// mirror, faces by their vertex triples. Returns the number of vertices moved.
  std::size_t snapshot(const geometry::IndexedMesh& mesh, const std::vector<Index>& ids, int step) {
    std::size_t moved = 0;
    for (std::size_t i = 0; i < ids.size(); ++i) moved += see_vertex(ids[i], mesh.positions[i], step);
    ++generation_;
    for (const auto& tri : mesh.triangles) {
      std::array<int, 3> t;
      for (int k = 0; k < 3; ++k) t[k] = vertex_record_[ids[tri[k]]];
      t = canonical(t);
      const std::uint64_t key = pack(t);
      auto [it, inserted] = face_by_key_.try_emplace(key, -1);
      if (inserted) it->second = open(t, step);
      seen_[it->second] = generation_;
    }
    for (auto it = face_by_key_.begin(); it != face_by_key_.end();) {
      if (seen_[it->second] != generation_) {
        close(it->second, step);
        it = face_by_key_.erase(it);
      } else {
        ++it;
      }
    }
    return moved;
  }

  /// Sets the quality of every open face record from the vertices' current
  /// positions and `rho_of(vertex id)`.
  template <class RhoOf>
  void set_quality(const RhoOf& rho_of, const skin::SizeConstants& size) {
    std::fill(quality_.begin(), quality_.end(), 0.0);
    double worst = 180;
    for (std::size_t r = 0; r < face_died_.size(); ++r) {
      if (face_died_[r] != -1) continue;
      std::array<Vec3, 3> p;
      std::array<double, 3> rho;
      for (int k = 0; k < 3; ++k) {
        const int v = faces_[3 * r + k];
        p[k] = position_[vertex_id_[v]];
        rho[k] = rho_of(vertex_id_[v]);
      }
      const auto q = face_quality(p, rho, size);
      for (int k = 0; k < 3; ++k) quality_[3 * r + k] = q[k];
      worst = std::min(worst, q[0]);
    }
    min_angle_ = worst;
  }

  std::size_t alive_faces() const { return alive_; }
  std::size_t face_records() const { return face_died_.size(); }
  std::size_t vertex_records() const { return vertex_step_.size(); }
  double min_angle() const { return min_angle_; }

  /// Writes the mesh history into `doc` (the keys of trace/FORMAT.md).
  void write(json& doc) const {
    std::vector<double> xyz;
    xyz.reserve(vertex_xyz_.size());
    for (double x : vertex_xyz_) xyz.push_back(round_to(x, kPositionScale));
    doc["vertices"] = std::move(xyz);
    doc["vertex_step"] = vertex_step_;
    json moves = json::array();
    for (const Move& m : moves_) {
      moves.push_back(m.vertex);
      moves.push_back(m.step);
      for (int k = 0; k < 3; ++k) moves.push_back(round_to(m.p[k], kPositionScale));
    }
    doc["moves"] = std::move(moves);
    doc["faces"] = faces_;
    std::vector<int> steps;
    steps.reserve(2 * face_born_.size());
    for (std::size_t r = 0; r < face_born_.size(); ++r) steps.push_back(face_born_[r]), steps.push_back(face_died_[r]);
    doc["face_steps"] = std::move(steps);
    std::vector<double> qa, ql, qu;
    for (std::size_t r = 0; r < face_died_.size(); ++r) {
      qa.push_back(round_to(quality_[3 * r], 1e3));
      ql.push_back(round_to(quality_[3 * r + 1], 1e3));
      qu.push_back(round_to(quality_[3 * r + 2], 1e3));
    }
    doc["quality"] = {{"min_angle", std::move(qa)}, {"L", std::move(ql)}, {"U", std::move(qu)}};
    Vec3 lo = Vec3::Zero(), hi = Vec3::Zero();
    if (!vertex_step_.empty()) lo = lo_, hi = hi_;
    doc["bounds"] = {{"min", point_json(lo)}, {"max", point_json(hi)}};
  }

 private:
  struct Move {
    int vertex, step;
    Vec3 p;
  };

  /// Records vertex `id` at p: a new vertex record, or a move if it moved by
  /// more than 1e-5 Å since it was last recorded. Returns 1 for a move.
  std::size_t see_vertex(Index id, const Vec3& p, int step) {
    if (id >= vertex_record_.size()) vertex_record_.resize(id + 1, -1), position_.resize(id + 1, Vec3::Zero());
    int& rec = vertex_record_[id];
    if (rec < 0) {
      rec = static_cast<int>(vertex_step_.size());
      vertex_step_.push_back(step);
      vertex_id_.push_back(id);
      for (int k = 0; k < 3; ++k) vertex_xyz_.push_back(p[k]);
      position_[id] = p;
      grow_bounds(p);
      return 0;
    }
    if ((p - position_[id]).squaredNorm() <= kMinMoveSquared) return 0;
    position_[id] = p;
    moves_.push_back({rec, step, p});
    grow_bounds(p);
    return 1;
  }
  void grow_bounds(const Vec3& p) {
    if (vertex_step_.size() == 1 && moves_.empty()) lo_ = hi_ = p;
    lo_ = lo_.cwiseMin(p), hi_ = hi_.cwiseMax(p);
  }
  static std::array<int, 3> canonical(const std::array<int, 3>& t) {
    const int k = t[0] <= t[1] && t[0] <= t[2] ? 0 : (t[1] <= t[2] ? 1 : 2);
    return {t[k], t[(k + 1) % 3], t[(k + 2) % 3]};
  }
  static std::uint64_t pack(const std::array<int, 3>& t) {
    // 21 bits per vertex record: up to 2,097,151 vertices (checked in open()).
    return (std::uint64_t(t[0]) << 42) | (std::uint64_t(t[1]) << 21) | std::uint64_t(t[2]);
  }
  bool same(int rec, const std::array<int, 3>& t) const {
    return faces_[3 * rec] == t[0] && faces_[3 * rec + 1] == t[1] && faces_[3 * rec + 2] == t[2];
  }
  int open(const std::array<int, 3>& t, int step) {
    if (t[0] < 0 || t[1] < 0 || t[2] < 0) throw std::logic_error("trace: a face refers to an unrecorded vertex");
    if (std::max({t[0], t[1], t[2]}) >= (1 << 21)) throw std::runtime_error("trace: more than 2,097,151 vertices");
    faces_.insert(faces_.end(), t.begin(), t.end());
    face_born_.push_back(step);
    face_died_.push_back(-1);
    seen_.push_back(0);
    quality_.insert(quality_.end(), 3, 0.0);
    ++alive_;
    return static_cast<int>(face_born_.size()) - 1;
  }
  /// A record born and closed within one step (born == died) is never drawn.
  void close(int rec, int step) {
    face_died_[rec] = step;
    --alive_;
  }

  std::vector<double> vertex_xyz_;
  std::vector<int> vertex_step_;
  std::vector<Index> vertex_id_;    ///< record -> vertex id
  std::vector<int> vertex_record_;  ///< vertex id -> record (-1: none)
  std::vector<Vec3> position_;      ///< vertex id -> position last recorded
  std::vector<Move> moves_;
  std::vector<int> faces_, face_born_, face_died_;
  std::vector<unsigned> seen_;
  std::vector<double> quality_;
  std::vector<int> face_record_;  ///< face index -> open record (-1: none)
  std::unordered_map<std::uint64_t, int> face_by_key_;
  unsigned generation_ = 0;
  std::size_t alive_ = 0;
  Vec3 lo_ = Vec3::Zero(), hi_ = Vec3::Zero();
  double min_angle_ = 0;
};

/// Operations observed but not yet recorded as a step.
struct Pending {
  std::map<std::string, long> ops;
  long n = 0;
  std::string op, text;
  std::optional<Vec3> focus;
  Index critical = kInvalidIndex;

  void add(const std::string& name, std::string what, std::optional<Vec3> where, Index cp) {
    ++ops[name];
    ++n;
    op = name;
    text = std::move(what);
    focus = where;
    critical = cp;
  }
  /// The step's JSON (trace/FORMAT.md "steps"); clears the pending operations.
  json take(const char* stage, json counters) {
    std::string line = text;
    if (n > 1) {
      line = std::to_string(n) + " operations:";
      bool first = true;
      for (const auto& [name, count] : ops) {
        line += (first ? " " : ", ") + name + " ×" + std::to_string(count);
        first = false;
      }
      line += "; the last: " + text;
    }
    json step = {{"stage", stage},
                 {"op", op},
                 {"text", line},
                 {"ops", ops},
                 {"focus", focus ? point_json(*focus) : json(nullptr)},
                 {"critical", critical == kInvalidIndex ? -1 : static_cast<long>(critical)},
                 {"counters", std::move(counters)}};
    *this = Pending{};
    return step;
  }
};

/// Index of a critical point of the height function on the surface: 0
/// minimum, 1 saddle, 2 maximum.
int morse_index(morse::CriticalKind kind) { return static_cast<int>(kind); }

/// The Morse–Smale complex's part of the document: critical points, their
/// protecting spheres, the integral lines (thinned to points 0.1 Å apart),
/// and step 0's description.
void record_morse(json& doc, const morse::MorseSmaleComplex& ms) {
  json critical = json::array();
  for (std::size_t i = 0; i < ms.critical.size(); ++i) {
    const morse::CriticalPoint& cp = ms.critical[i];
    critical.push_back(
        {{"p", point_json(cp.position)},
         {"index", morse_index(cp.kind)},
         {"live", i < ms.live.size() ? bool(ms.live[i]) : true},
         {"sphere", i < ms.protect_radius.size() ? round_to(ms.protect_radius[i], kPositionScale) : 0.0}});
  }
  json lines = json::array();
  for (const morse::IntegralLine& line : ms.lines) {
    if (line.points.size() < 2) continue;
    std::vector<double> pts;
    Vec3 last = line.points.front();
    for (int k = 0; k < 3; ++k) pts.push_back(round_to(last[k], kPositionScale));
    for (std::size_t i = 1; i < line.points.size(); ++i) {
      const Vec3& p = line.points[i];
      if ((p - last).norm() < kLineSpacing && i + 1 < line.points.size()) continue;
      for (int k = 0; k < 3; ++k) pts.push_back(round_to(p[k], kPositionScale));
      last = p;
    }
    const bool live = line.saddle < ms.live.size() ? bool(ms.live[line.saddle]) : true;
    lines.push_back({{"points", std::move(pts)}, {"critical", static_cast<long>(line.saddle)}, {"live", live}});
  }
  doc["critical"] = std::move(critical);
  doc["lines"] = std::move(lines);
  doc["height_direction"] = point_json(ms.height_direction);
}

/// Counts of the first run: how many operations each stage observes.
struct OperationCounts {
  std::size_t sweep = 0, refine = 0, growth = 0, max_samples = 0;
};

long stride(std::size_t operations, double steps) {
  return std::max<long>(1, static_cast<long>(std::ceil(double(operations) / std::max(1.0, steps))));
}

/// The last step (the output mesh, with its check's verdict; the quality
/// was set at the end of the last stage) and the document's remaining keys;
/// fills `summary`.
void finish(const mesher::MeshResult& res, json counters, json every, std::size_t operations, History& history,
            std::vector<json>& steps, json& doc, TraceSummary& summary) {
  Pending last;
  last.add("final mesh",
           "final mesh: " + std::to_string(res.mesh.triangles.size()) + " triangles, " +
               std::to_string(res.mesh.positions.size()) + " vertices" +
               (res.checked ? (res.ok() ? ", every check passed" : ", FAILED its checks") : ", not checked"),
           std::nullopt, kInvalidIndex);
  counters["triangles"] = history.alive_faces();
  steps.push_back(last.take("final", std::move(counters)));
  doc["frame_centre"] = point_json(res.frame_centre);
  doc["every"] = std::move(every);
  doc["operations"] = operations;
  json check = {{"ran", res.checked}, {"ok", res.ok()}, {"problems", res.check.problems}};
  if (res.checked) check["min_angle"] = round_to(res.check.mesh.min_angle_deg, kAngleScale);
  doc["check"] = std::move(check);
  history.write(doc);
  doc["steps"] = std::move(steps);
  summary.checked = res.checked;
  summary.ok = res.ok();
  summary.problems = res.check.problems;
  summary.triangles = res.mesh.triangles.size();
  summary.operations = operations;
  summary.min_angle_deg = res.checked ? res.check.mesh.min_angle_deg : history.min_angle();
  summary.face_records = history.face_records();
  summary.vertices = history.vertex_records();
}

/// The sweep pipeline, recorded.
json record_sweep(const std::vector<geometry::WeightedPoint>& points, const TraceOptions& options,
                  TraceSummary& summary) {
  mesher::MeshOptions run = options.mesh;
  // The trace is the sweep's: where it fails, the error is the answer (the
  // static baseline, the whole-skin fallback, is traced with --algorithm
  // dynamic --no-growth).
  run.static_fallback = false;
  OperationCounts counts;
  long every_sweep = options.every, every_refine = options.every;
  if (options.every <= 0) {
    // First run: count the operations (no check, no recording).
    mesher::MeshOptions counting = run;
    counting.check = false;
    counting.sweep.observer = [&counts](const front::SweepEvent&) { ++counts.sweep; };
    counting.refinement.observer = [&counts](refine::RefineOperation, const SurfaceMesh&) { ++counts.refine; };
    if (options.mesh.progress)
      counting.progress = [&options](const std::string& stage, double f) {
        options.mesh.progress("count " + stage, f);
      };
    mesher::mesh_skin(points, counting);
    every_sweep = stride(counts.sweep, kSweepShare * double(options.max_steps));
    every_refine = stride(counts.refine, kRefineShare * double(options.max_steps));
  }

  json doc;
  History history;
  std::vector<json> steps;
  Pending pending;
  std::size_t operations = 0, prev_contacts = 0;
  std::size_t flips = 0, contractions = 0, insertions = 0;
  const skin::SizeConstants size = run.size;
  std::vector<Vec3> critical_position;

  auto record = [&](const char* stage, const SurfaceMesh& mesh, json counters) {
    const int step = static_cast<int>(steps.size());
    history.snapshot(mesh, step);
    counters["triangles"] = history.alive_faces();
    steps.push_back(pending.take(stage, std::move(counters)));
  };
  auto sweep_counters = [](const front::SweepStats& s) {
    json j{{"creations", s.creations}, {"creeps", s.creeps},     {"contacts", s.contacts},
           {"wings", s.wings},         {"held", s.held},         {"bridges", s.bridges},
           {"seals", s.seals},         {"deferred", s.deferred}, {"collisions", s.collisions},
           {"stuck", s.stuck}};
    // The fallback's counters appear once it has been used (a sweep that needs
    // none records the same trace as one without a fallback).
    if (s.left_holes + s.patched_holes + s.folds > 0) {
      j["left_holes"] = s.left_holes;
      j["patched_holes"] = s.patched_holes;
      j["folds"] = s.folds;
    }
    return j;
  };
  json last_sweep_counters = json::object();
  auto refine_counters = [&] {
    return json{{"flips", flips}, {"contractions", contractions}, {"insertions", insertions}};
  };

  run.observers.morse = [&](const skin::SkinSurface&, const morse::MorseSmaleComplex& ms) {
    record_morse(doc, ms);
    for (const morse::CriticalPoint& cp : ms.critical) critical_position.push_back(cp.position);
    const morse::MorseCount all = morse::count_critical_points(ms.critical), live = ms.live_count();
    pending.add("morse-smale complex",
                std::to_string(ms.critical.size()) + " critical points (" + std::to_string(all.minima) + " minima, " +
                    std::to_string(all.saddles) + " saddles, " + std::to_string(all.maxima) + " maxima), " +
                    std::to_string(ms.lines.size()) + " integral lines; after simplification " +
                    std::to_string(live.minima) + " minima, " + std::to_string(live.saddles) + " saddles, " +
                    std::to_string(live.maxima) + " maxima",
                std::nullopt, kInvalidIndex);
    steps.push_back(pending.take(
        "morse", json{{"minima", live.minima}, {"saddles", live.saddles}, {"maxima", live.maxima}, {"triangles", 0}}));
  };
  run.sweep.observer = [&](const front::SweepEvent& ev) {
    ++operations;
    std::string name = front::operation_name(ev.op);
    if (ev.op == front::SweepOperation::Creep && ev.stats.contacts > prev_contacts) name = "contact";
    prev_contacts = ev.stats.contacts;
    const std::size_t added = ev.mesh.faces_size() - ev.first_face;
    const std::string cp = ev.critical == kInvalidIndex ? std::string() : " " + std::to_string(ev.critical);
    std::string text;
    std::optional<Vec3> focus;
    if (ev.vertex.is_valid()) focus = ev.mesh.position(ev.vertex);
    if (ev.critical != kInvalidIndex && ev.critical < critical_position.size() && !focus)
      focus = critical_position[ev.critical];
    const std::string tris = std::to_string(added) + (added == 1 ? " triangle" : " triangles");
    switch (ev.op) {
      case front::SweepOperation::Creation:
        text = "creation: a bowl of " + tris + " at minimum" + cp;
        break;
      case front::SweepOperation::Creep:
        text = name == "contact" ? "creep that joins two parts of the front (contact), " + tris
                                 : "creep: a fan of " + tris + " at the lowest front vertex";
        if (added == 0) text = "creep deferred: the fan would fold; the vertex waits higher up";
        break;
      case front::SweepOperation::Wings:
        text = "wings: " + tris + " close sharp front angles";
        break;
      case front::SweepOperation::Hold:
        text = "hold: a front vertex stops in the protecting sphere of saddle" + cp;
        break;
      case front::SweepOperation::Bridge:
        text = "bridge at saddle" + cp + ": " + tris + " join two front parts";
        break;
      case front::SweepOperation::SmallHole:
        text = "small hole closed during the sweep: " + tris;
        break;
      case front::SweepOperation::Seal:
        text = "seal: a hole closed with " + tris;
        break;
      case front::SweepOperation::Patch:
        text = "patch (fallback): a tangled region re-meshed by restricted Delaunay, " + tris;
        break;
    }
    pending.add(name, text, focus, ev.critical);
    const bool key = ev.op == front::SweepOperation::Creation || ev.op == front::SweepOperation::Bridge ||
                     ev.op == front::SweepOperation::Seal || ev.op == front::SweepOperation::Patch;
    last_sweep_counters = sweep_counters(ev.stats);
    if (key || pending.n >= every_sweep) record("sweep", ev.mesh, last_sweep_counters);
  };
  run.refinement.observer = [&](refine::RefineOperation op, const SurfaceMesh& mesh) {
    ++operations;
    std::string text;
    switch (op) {
      case refine::RefineOperation::Flip:
        ++flips;
        text = "flip: an edge that is not restricted Delaunay is flipped";
        break;
      case refine::RefineOperation::Contraction:
        ++contractions;
        text = "contraction: an edge too short for [L] is contracted";
        break;
      case refine::RefineOperation::Insertion:
        ++insertions;
        text = "insertion: the surface Delaunay centre of a triangle too large for [U] is inserted";
        break;
    }
    pending.add(refine::operation_name(op), text, std::nullopt, kInvalidIndex);
    if (pending.n >= every_refine) record("refine", mesh, refine_counters());
  };
  auto rho_quality = [&](const skin::SkinSurface& skin, const SurfaceMesh& mesh) {
    if (!mesh.has_vertex_property(skin::kVertexCell)) return;
    const skin::VertexRhos rho(skin.mixed_complex(), mesh);
    history.set_quality([&](Index id) { return rho[Vertex(id)]; }, size);
  };
  run.observers.stage_end = [&](const char* stage, const skin::SkinSurface& skin, const SurfaceMesh& mesh) {
    const std::string s = stage;
    if (s == "angles") {
      pending.add("vertex moves", "angle improvement: vertices moved on the skin to raise the smallest angles",
                  std::nullopt, kInvalidIndex);
      const int step = static_cast<int>(steps.size());
      const std::size_t moved = history.snapshot(mesh, step);
      pending.text += " (" + std::to_string(moved) + " vertices moved)";
      steps.push_back(pending.take("angles", json{{"moved", moved}, {"triangles", history.alive_faces()}}));
    } else if (pending.n > 0) {
      record(stage, mesh, s == "sweep" ? last_sweep_counters : refine_counters());
    }
    rho_quality(skin, mesh);
  };
  const mesher::MeshResult res = mesher::mesh_skin(points, run);

  finish(res,
         json{{"vertices", res.mesh.positions.size()},
              {"flips", flips},
              {"contractions", contractions},
              {"insertions", insertions}},
         json{{"sweep", every_sweep}, {"refine", every_refine}}, operations, history, steps, doc, summary);
  return doc;
}

/// The dynamic-skin baseline, recorded: one step per recorded growth step,
/// one for the final refinement.
json record_dynamic(const std::vector<geometry::WeightedPoint>& points, const TraceOptions& options,
                    TraceSummary& summary) {
  mesher::MeshOptions run = options.mesh;
  long every = options.every;
  if (options.every <= 0) {
    OperationCounts counts;
    mesher::MeshOptions counting = run;
    counting.check = false;
    counting.dynamic.observer = [&counts](const char* stage, const dynamic::SampleTriangulation& st) {
      if (std::string(stage) != "growth") return;
      ++counts.growth;
      counts.max_samples = std::max(counts.max_samples, st.samples().size());
    };
    if (options.mesh.progress)
      counting.progress = [&options](const std::string& stage, double f) {
        options.mesh.progress("count " + stage, f);
      };
    mesher::mesh_skin(points, counting);
    // Every recorded growth step moves every sample.
    const double affordable = double(options.growth_budget_bytes) /
                              (kBytesPerGrowthSample * double(std::max<std::size_t>(counts.max_samples, 1)));
    every = stride(counts.growth, std::min(kGrowthShare * double(options.max_steps), affordable));
  }
  json doc;
  History history;
  std::vector<json> steps;
  Pending pending;
  std::size_t growth = 0;
  pending.add("atoms",
              std::to_string(points.size()) + " weighted points; the skin grows from small spheres around them",
              std::nullopt, kInvalidIndex);
  steps.push_back(pending.take("start", json{{"triangles", 0}}));
  doc["critical"] = json::array();
  doc["lines"] = json::array();
  const skin::SizeConstants size = run.size;
  run.dynamic.observer = [&](const char* stage, const dynamic::SampleTriangulation& st) {
    const bool final_stage = std::string(stage) == "refine";
    if (!final_stage && growth++ % every != 0) return;
    std::vector<Index> ids;
    const geometry::IndexedMesh m = st.extract(&ids);
    const int step = static_cast<int>(steps.size());
    const std::size_t moved = history.snapshot(m, ids, step);
    const std::string what =
        final_stage ? "final refinement: [L], [U] and the restricted Delaunay triangulation on the final skin"
                    : "growth step " + std::to_string(growth) + ": the skin grows, the samples move with it";
    pending.add(final_stage ? "refinement" : "growth step",
                what + " (" + std::to_string(ids.size()) + " samples, " + std::to_string(m.triangles.size()) +
                    " restricted triangles, " + std::to_string(moved) + " samples moved)",
                std::nullopt, kInvalidIndex);
    steps.push_back(
        pending.take(final_stage ? "refine" : "growth",
                     json{{"samples", ids.size()}, {"growth_steps", growth}, {"triangles", history.alive_faces()}}));
    if (final_stage) history.set_quality([&st](Index id) { return st.rho(id); }, size);
  };
  const mesher::MeshResult res = mesher::mesh_skin(points, run);
  finish(res, json{{"growth_steps", growth}}, json{{"growth", every}}, growth + 1, history, steps, doc, summary);
  return doc;
}

}  // namespace

json record_trace(const std::vector<geometry::WeightedPoint>& points, const TraceOptions& options,
                  TraceSummary* summary) {
  if (options.max_steps < 10) throw std::invalid_argument("the trace needs at least 10 steps");
  TraceSummary local;
  TraceSummary& s = summary ? *summary : local;
  s = TraceSummary{};
  json doc = options.mesh.algorithm == mesher::Algorithm::Sweep ? record_sweep(points, options, s)
                                                                : record_dynamic(points, options, s);
  doc["format"] = "skinmesh-trace";
  doc["version"] = 1;
  doc["title"] = options.title;
  doc["input"] = options.input;
  doc["algorithm"] = mesher::algorithm_name(options.mesh.algorithm);
  doc["probe"] = options.probe >= 0 ? json(options.probe) : json(nullptr);
  doc["atoms"] = points.size();
  doc["min_angle_bound"] = round_to(options.mesh.size.min_angle_bound_deg(), kBoundScale);
  if (!doc.contains("height_direction")) doc["height_direction"] = nullptr;
  s.steps = doc["steps"].size();
  return doc;
}

std::string fill_viewer_template(const std::string& viewer_template, const json& document) {
  const std::string placeholder = kTracePlaceholder;
  const std::size_t at = viewer_template.find(placeholder);
  if (at == std::string::npos || viewer_template.find(placeholder, at + 1) != std::string::npos)
    throw std::runtime_error("the viewer template must hold " + placeholder + " exactly once");
  std::string data = document.dump(-1, ' ', false, json::error_handler_t::replace);
  std::string escaped;
  escaped.reserve(data.size() + data.size() / 64);
  for (char c : data) {
    if (c == '<')
      escaped += "\\u003c";  // a '<' only occurs inside JSON strings
    else
      escaped += c;
  }
  std::string page;
  page.reserve(viewer_template.size() + escaped.size());
  page.append(viewer_template, 0, at)
      .append(escaped)
      .append(viewer_template, at + placeholder.size(), std::string::npos);
  return page;
}

}  // namespace skinmesh::trace
