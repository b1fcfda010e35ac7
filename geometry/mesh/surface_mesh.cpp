// geometry/mesh/surface_mesh.cpp: SurfaceMesh method definitions (see surface_mesh.h).
#include "geometry/mesh/surface_mesh.h"

#include <algorithm>
#include <ostream>
#include <sstream>
#include <stdexcept>

#include "core/binary_io.h"
#include "core/errors.h"

namespace skinmesh::geometry {

namespace {

// Names of the built-in properties; remove_*_property refuses them.
constexpr const char* kVConn = "v:connectivity";
constexpr const char* kVPoint = "v:point";
constexpr const char* kVDeleted = "v:deleted";
constexpr const char* kHConn = "h:connectivity";
constexpr const char* kEDeleted = "e:deleted";
constexpr const char* kFConn = "f:connectivity";
constexpr const char* kFDeleted = "f:deleted";

template <class H>
std::string str(H h) {
  std::ostringstream os;
  os << h;
  return os.str();
}

template <class H>
std::ostream& print_handle(std::ostream& os, char prefix, H h) {
  os << prefix;
  if (h.is_valid())
    os << h.idx();
  else
    os << '-';
  return os;
}

/// A half-edge's face-or-prev field (SurfaceMesh::HalfedgeConnectivity) with
/// its face index renumbered by face_of or its prev's by halfedge_of (a prev
/// not linked yet stays so): for the offsets of append() and the maps of
/// garbage_collection().
template <class FaceOf, class HalfedgeOf>
Index renumbered_face_or_prev(Index fp, FaceOf&& face_of, HalfedgeOf&& halfedge_of) {
  constexpr Index kTag = SurfaceMesh::kBoundaryTag, kNone = SurfaceMesh::kNoPrev;
  if (!(fp & kTag)) return face_of(fp);
  const Index p = fp & kNone;
  return p == kNone ? fp : kTag | halfedge_of(p);
}

}  // namespace

// Handle Printing
std::ostream& operator<<(std::ostream& os, Vertex v) { return print_handle(os, 'v', v); }
std::ostream& operator<<(std::ostream& os, Halfedge h) { return print_handle(os, 'h', h); }
std::ostream& operator<<(std::ostream& os, Edge e) { return print_handle(os, 'e', e); }
std::ostream& operator<<(std::ostream& os, Face f) { return print_handle(os, 'f', f); }

// ---------------------------------------------------------------------------
// SurfaceMesh Construction
// ---------------------------------------------------------------------------

SurfaceMesh::SurfaceMesh() {
  vprops_.add<VertexConnectivity>(kVConn, {});
  vprops_.add<Vec3>(kVPoint, Vec3::Zero());
  vprops_.add<bool>(kVDeleted, false);
  hprops_.add<HalfedgeConnectivity>(kHConn, {});
  eprops_.add<bool>(kEDeleted, false);
  fprops_.add<FaceConnectivity>(kFConn, {});
  fprops_.add<bool>(kFDeleted, false);
  bind_builtin_properties();
}

SurfaceMesh::SurfaceMesh(const SurfaceMesh& other)
    : vprops_(other.vprops_),
      hprops_(other.hprops_),
      eprops_(other.eprops_),
      fprops_(other.fprops_),
      deleted_vertices_(other.deleted_vertices_),
      deleted_edges_(other.deleted_edges_),
      deleted_faces_(other.deleted_faces_) {
  bind_builtin_properties();
}

SurfaceMesh& SurfaceMesh::operator=(const SurfaceMesh& other) {
  if (this == &other) return *this;
  vprops_ = other.vprops_;
  hprops_ = other.hprops_;
  eprops_ = other.eprops_;
  fprops_ = other.fprops_;
  deleted_vertices_ = other.deleted_vertices_;
  deleted_edges_ = other.deleted_edges_;
  deleted_faces_ = other.deleted_faces_;
  bind_builtin_properties();
  return *this;
}

// Moving transfers the property arrays (their addresses do not change, so
// property handles follow the data); the moved-from mesh becomes a fresh empty mesh.
SurfaceMesh::SurfaceMesh(SurfaceMesh&& other) noexcept : SurfaceMesh() { *this = std::move(other); }

SurfaceMesh& SurfaceMesh::operator=(SurfaceMesh&& other) noexcept {
  if (this == &other) return *this;
  std::swap(vprops_, other.vprops_);
  std::swap(hprops_, other.hprops_);
  std::swap(eprops_, other.eprops_);
  std::swap(fprops_, other.fprops_);
  std::swap(deleted_vertices_, other.deleted_vertices_);
  std::swap(deleted_edges_, other.deleted_edges_);
  std::swap(deleted_faces_, other.deleted_faces_);
  bind_builtin_properties();
  other.bind_builtin_properties();
  other.clear();
  return *this;
}

SurfaceMesh::~SurfaceMesh() = default;

void SurfaceMesh::bind_builtin_properties() {
  vconn_ = VertexProperty<VertexConnectivity>(vprops_.get<VertexConnectivity>(kVConn));
  vpoint_ = VertexProperty<Vec3>(vprops_.get<Vec3>(kVPoint));
  vdeleted_ = VertexProperty<bool>(vprops_.get<bool>(kVDeleted));
  hconn_ = HalfedgeProperty<HalfedgeConnectivity>(hprops_.get<HalfedgeConnectivity>(kHConn));
  edeleted_ = EdgeProperty<bool>(eprops_.get<bool>(kEDeleted));
  fconn_ = FaceProperty<FaceConnectivity>(fprops_.get<FaceConnectivity>(kFConn));
  fdeleted_ = FaceProperty<bool>(fprops_.get<bool>(kFDeleted));
}

void SurfaceMesh::clear() {
  vprops_.resize(0);
  hprops_.resize(0);
  eprops_.resize(0);
  fprops_.resize(0);
  deleted_vertices_ = deleted_edges_ = deleted_faces_ = 0;
}

void SurfaceMesh::release_faces() {
  hprops_.release();
  eprops_.release();
  fprops_.release();
  deleted_edges_ = deleted_faces_ = 0;
}

void SurfaceMesh::reserve(std::size_t nv, std::size_t nf) {
  // Every property array of each kind (a closed triangle mesh has about
  // nv + nf edges).
  vprops_.reserve(nv);
  hprops_.reserve(2 * (nv + nf));
  eprops_.reserve(nv + nf);
  fprops_.reserve(nf);
}

void SurfaceMesh::remove_property(detail::PropertyContainer& c, const detail::BasePropertyArray* p) {
  if (p == nullptr) throw std::invalid_argument("SurfaceMesh: removing an invalid property");
  const std::string& n = p->name();
  for (const char* b : {kVConn, kVPoint, kVDeleted, kHConn, kEDeleted, kFConn, kFDeleted})
    if (n == b) throw std::invalid_argument("SurfaceMesh: built-in property '" + n + "' cannot be removed");
  c.remove(p);
}

void SurfaceMesh::require_valid(Vertex v, const char* where) const {
  if (!is_valid(v))
    throw std::invalid_argument(std::string("SurfaceMesh::") + where + ": vertex " + str(v) +
                                " is out of range or deleted");
}
void SurfaceMesh::require_valid(Face f, const char* where) const {
  if (!is_valid(f))
    throw std::invalid_argument(std::string("SurfaceMesh::") + where + ": face " + str(f) +
                                " is out of range or deleted");
}
void SurfaceMesh::require_valid(Edge e, const char* where) const {
  if (!is_valid(e))
    throw std::invalid_argument(std::string("SurfaceMesh::") + where + ": edge " + str(e) +
                                " is out of range or deleted");
}
void SurfaceMesh::require_valid(Halfedge h, const char* where) const {
  if (!is_valid(h))
    throw std::invalid_argument(std::string("SurfaceMesh::") + where + ": half-edge " + str(h) +
                                " is out of range or deleted");
}

// ---------------------------------------------------------------------------
// SurfaceMesh Element Creation
// ---------------------------------------------------------------------------

Vertex SurfaceMesh::add_vertex(const Vec3& p) {
  vprops_.push_back();
  Vertex v(Index(vprops_.size() - 1));
  vpoint_[v] = p;
  return v;
}

void SurfaceMesh::append(const SurfaceMesh& other) {
  if (&other == this) throw std::invalid_argument("SurfaceMesh::append: a mesh cannot be appended to itself");
  if (other.has_garbage()) throw std::invalid_argument("SurfaceMesh::append: the appended mesh has deleted elements");
  require_room_for(other);
  const Index v0 = Index(vertices_size()), h0 = Index(halfedges_size()), f0 = Index(faces_size());
  // Invalid handles stay invalid; valid ones move by their kind's offset.
  auto shift_v = [v0](Vertex v) { return v.is_valid() ? Vertex(v.idx() + v0) : v; };
  auto shift_h = [h0](Halfedge h) { return h.is_valid() ? Halfedge(h.idx() + h0) : h; };
  reserve(vertices_size() + other.vertices_size(), faces_size() + other.faces_size());
  for (std::size_t i = 0; i < other.vertices_size(); ++i) {
    const Vertex w(static_cast<Index>(i));
    const Vertex v = add_vertex(other.position(w));
    set_halfedge(v, shift_h(other.halfedge(w)));
  }
  for (std::size_t i = 0; i < other.edges_size(); ++i) {
    eprops_.push_back();
    hprops_.push_back();
    hprops_.push_back();
  }
  for (std::size_t i = 0; i < other.halfedges_size(); ++i) {
    const Halfedge g(static_cast<Index>(i));
    HalfedgeConnectivity& c = hconn_[Halfedge(g.idx() + h0)];
    const HalfedgeConnectivity& o = other.hconn_[g];
    c.to = shift_v(o.to), c.next = shift_h(o.next);
    c.face_or_prev = renumbered_face_or_prev(
        o.face_or_prev, [f0](Index f) { return f + f0; }, [h0](Index p) { return p + h0; });
  }
  for (std::size_t i = 0; i < other.faces_size(); ++i) {
    const Face g(static_cast<Index>(i));
    set_halfedge(new_face(), shift_h(other.halfedge(g)));
  }
}

void SurfaceMesh::append_consuming(SurfaceMesh& other) {
  if (&other == this) throw std::invalid_argument("SurfaceMesh::append_consuming: a mesh cannot be appended to itself");
  if (other.has_garbage())
    throw std::invalid_argument("SurfaceMesh::append_consuming: the appended mesh has deleted elements");
  require_room_for(other);
  const Index v0 = Index(vertices_size()), h0 = Index(halfedges_size()), f0 = Index(faces_size());
  const std::size_t nv = other.vertices_size(), nh = other.halfedges_size(), nf = other.faces_size();
  vprops_.append_consuming(other.vprops_);
  hprops_.append_consuming(other.hprops_);
  eprops_.append_consuming(other.eprops_);
  fprops_.append_consuming(other.fprops_);
  // The copied connectivity moves by each kind's offset (invalid handles stay).
  auto shift_h = [h0](Halfedge h) { return h.is_valid() ? Halfedge(h.idx() + h0) : h; };
  for (std::size_t i = 0; i < nv; ++i) {
    VertexConnectivity& c = vconn_[Vertex(Index(v0 + i))];
    c.halfedge = shift_h(c.halfedge);
  }
  for (std::size_t i = 0; i < nh; ++i) {
    HalfedgeConnectivity& c = hconn_[Halfedge(Index(h0 + i))];
    if (c.to.is_valid()) c.to = Vertex(c.to.idx() + v0);
    c.face_or_prev = renumbered_face_or_prev(
        c.face_or_prev, [f0](Index f) { return f + f0; }, [h0](Index p) { return p + h0; });
    c.next = shift_h(c.next);
  }
  for (std::size_t i = 0; i < nf; ++i) {
    FaceConnectivity& c = fconn_[Face(Index(f0 + i))];
    c.halfedge = shift_h(c.halfedge);
  }
  other.clear();
}

void SurfaceMesh::require_room_for(const SurfaceMesh& other) const {
  if (halfedges_size() + other.halfedges_size() > kNoPrev || faces_size() + other.faces_size() > kNoPrev)
    throw std::length_error("SurfaceMesh: more than 2^31 - 1 half-edges or faces (the limit of the half-edge links)");
}

Halfedge SurfaceMesh::new_edge(Vertex a, Vertex b) {
  if (hprops_.size() + 2 > kNoPrev)
    throw std::length_error("SurfaceMesh: more than 2^31 - 1 half-edges (the limit of the half-edge links)");
  eprops_.push_back();
  hprops_.push_back();
  hprops_.push_back();
  Halfedge h(Index(hprops_.size() - 2));
  set_vertex(h, b);
  set_vertex(opposite(h), a);
  return h;
}

Face SurfaceMesh::new_face() {
  if (fprops_.size() + 1 > kNoPrev)
    throw std::length_error("SurfaceMesh: more than 2^31 - 1 faces (the limit of the half-edge links)");
  fprops_.push_back();
  return Face(Index(fprops_.size() - 1));
}

// The outgoing half-edges of a vertex, in clockwise order (o -> next(opposite(o))),
// alternate between fans of faces and boundary gaps; a gap is a boundary
// half-edge p coming in, followed by next(p) going out. A new face whose corner
// at v is (p into v, n out of v) sits between opposite(p) and n in that order.
// Starting at `from` and walking clockwise, return the first incoming boundary
// half-edge (a gap), or invalid if the incoming half-edge `stop` comes first.
Halfedge SurfaceMesh::find_gap_after(Halfedge from, Halfedge stop) const {
  Halfedge o = from;
  for (std::size_t guard = 0; guard <= halfedges_size(); ++guard) {
    Halfedge e = opposite(o);
    if (e == stop) return Halfedge();
    if (is_boundary(e)) return e;
    o = next(e);
  }
  throw std::logic_error("SurfaceMesh::find_gap_after: vertex circulation does not terminate");
}

Face SurfaceMesh::add_triangle(Vertex a, Vertex b, Vertex c) {
  const Vertex v[3] = {a, b, c};
  auto name = [&] { return "SurfaceMesh::add_triangle(" + str(a) + ", " + str(b) + ", " + str(c) + "): "; };
  for (int i = 0; i < 3; ++i) require_valid(v[i], "add_triangle");
  if (a == b || b == c || c == a) throw TopologyError(name() + "repeated vertex");

  // Check the corners and the edges before changing anything.
  for (int i = 0; i < 3; ++i)
    if (!is_boundary(v[i]))
      throw TopologyError(name() + "vertex " + str(v[i]) +
                          " is interior (its one-ring is closed); no face can be attached");
  Halfedge he[3];  // he[i] goes v[i] -> v[i+1]
  bool is_new[3];
  for (int i = 0; i < 3; ++i) {
    const Vertex s = v[i], t = v[(i + 1) % 3];
    he[i] = find_halfedge(s, t);
    is_new[i] = !he[i].is_valid();
    if (!is_new[i] && !is_boundary(he[i])) {
      if (is_boundary(opposite(he[i])))
        throw TopologyError(name() + "wrong orientation: half-edge " + str(s) + "->" + str(t) +
                            " is already used by face " + str(face(he[i])) + " (the new face must traverse it as " +
                            str(t) + "->" + str(s) + ")");
      throw TopologyError(name() + "non-manifold edge (" + str(s) + ", " + str(t) +
                          "): it already has faces on both sides");
    }
  }
  // Corner k is at v[k], entered by p = he[k-1] and left by n = he[k]. Where both
  // exist but are not consecutive on the boundary, the fans between them must
  // move to another gap of v[k], found clockwise after n.
  Halfedge gap[3];
  for (int k = 0; k < 3; ++k) {
    const Halfedge p = he[(k + 2) % 3], n = he[k];
    if (is_new[(k + 2) % 3] || is_new[k] || next(p) == n) continue;
    gap[k] = find_gap_after(n, p);
    if (!gap[k].is_valid())
      throw TopologyError(name() + "the face would close a fan around vertex " + str(v[k]) +
                          " into a disk while the vertex keeps other fans (non-manifold vertex)");
  }

  // Create the missing edges and the face.
  for (int i = 0; i < 3; ++i)
    if (is_new[i]) he[i] = new_edge(v[i], v[(i + 1) % 3]);
  const Face f = new_face();

  // Plan the next() links from the old state: every link is (incoming -> outgoing)
  // at one corner and reads only half-edges at that corner, so the corners do not
  // interfere.
  std::pair<Halfedge, Halfedge> links[9];
  int nlinks = 0;
  auto link = [&](Halfedge h, Halfedge nx) { links[nlinks++] = {h, nx}; };
  for (int k = 0; k < 3; ++k) {
    const Vertex w = v[k];
    const bool p_new = is_new[(k + 2) % 3], n_new = is_new[k];
    const Halfedge p = he[(k + 2) % 3], n = he[k];
    if (p_new && n_new) {
      const Halfedge out = halfedge(w);  // an outgoing boundary half-edge, if any
      if (!out.is_valid()) {
        link(opposite(n), opposite(p));  // isolated vertex: the face's own boundary
      } else {
        link(prev(out), opposite(p));  // put the face into the gap before out
        link(opposite(n), out);
      }
    } else if (!p_new && n_new) {
      link(opposite(n), next(p));
    } else if (p_new && !n_new) {
      link(prev(n), opposite(p));
    } else if (next(p) != n) {
      // Move the patch next(p) .. prev(n) into the gap (gap[k] -> next(gap[k])).
      const Halfedge first = next(p), last = prev(n), g = gap[k], g_next = next(gap[k]);
      link(g, first);
      link(last, g_next);
    }
    link(p, n);
  }

  // Apply.
  for (int i = 0; i < 3; ++i) set_face(he[i], f);
  set_halfedge(f, he[0]);
  for (int i = 0; i < nlinks; ++i) set_next(links[i].first, links[i].second);
  for (int k = 0; k < 3; ++k) {
    if (!halfedge(v[k]).is_valid()) set_halfedge(v[k], he[k]);
    adjust_outgoing_halfedge(v[k]);
  }
  return f;
}

void SurfaceMesh::adjust_outgoing_halfedge(Vertex v) {
  const Halfedge start = halfedge(v);
  if (!start.is_valid() || is_boundary(start)) return;
  Halfedge h = start;
  for (std::size_t guard = 0; guard <= halfedges_size(); ++guard) {
    if (is_boundary(h)) {
      set_halfedge(v, h);
      return;
    }
    h = ccw_rotated(h);
    if (h == start) return;
  }
  throw std::logic_error("SurfaceMesh: circulation around " + str(v) + " does not terminate");
}

// ---------------------------------------------------------------------------
// SurfaceMesh Connectivity Queries
// ---------------------------------------------------------------------------

bool SurfaceMesh::is_boundary(Face f) const {
  for (Halfedge h : halfedges(f))
    if (is_boundary(opposite(h))) return true;
  return false;
}

std::size_t SurfaceMesh::valence(Vertex v) const {
  std::size_t n = 0;
  for ([[maybe_unused]] Halfedge h : halfedges(v)) ++n;
  return n;
}

std::size_t SurfaceMesh::boundary_gaps(Vertex v) const {
  std::size_t n = 0;
  for (Halfedge h : halfedges(v))
    if (is_boundary(h)) ++n;
  return n;
}

bool SurfaceMesh::is_manifold(Vertex v) const { return boundary_gaps(v) <= 1; }

Halfedge SurfaceMesh::find_halfedge(Vertex a, Vertex b) const {
  for (Halfedge h : halfedges(a))
    if (to_vertex(h) == b) return h;
  return Halfedge();
}

Edge SurfaceMesh::find_edge(Vertex a, Vertex b) const {
  Halfedge h = find_halfedge(a, b);
  return h.is_valid() ? edge(h) : Edge();
}

std::vector<Halfedge> SurfaceMesh::boundary_loop(Halfedge h) const {
  require_valid(h, "boundary_loop");
  if (!is_boundary(h))
    throw std::invalid_argument("SurfaceMesh::boundary_loop: " + str(h) + " is not a boundary half-edge");
  std::vector<Halfedge> loop_halfedges;
  for (Halfedge g : loop(h)) loop_halfedges.push_back(g);
  return loop_halfedges;
}

std::vector<std::vector<Halfedge>> SurfaceMesh::boundary_loops() const {
  std::vector<std::vector<Halfedge>> loops;
  std::vector<bool> seen(halfedges_size(), false);
  for (Halfedge h : halfedges()) {
    if (!is_boundary(h) || seen[h.idx()]) continue;
    loops.push_back(boundary_loop(h));
    for (Halfedge g : loops.back()) seen[g.idx()] = true;
  }
  return loops;
}

// ---------------------------------------------------------------------------
// SurfaceMesh Refinement Operations
// ---------------------------------------------------------------------------

bool SurfaceMesh::is_flip_ok(Edge e) const {
  if (!is_valid(e) || is_boundary(e)) return false;
  const Halfedge h = halfedge(e, 0), o = halfedge(e, 1);
  const Vertex c = to_vertex(next(h)), d = to_vertex(next(o));
  if (c == d) return false;
  return !find_halfedge(c, d).is_valid();
}

void SurfaceMesh::flip(Edge e) {
  require_valid(e, "flip");
  if (!is_flip_ok(e))
    throw TopologyError("SurfaceMesh::flip(" + str(e) +
                        "): not flippable (boundary edge, or the new edge exists already)");
  // Before: f = (a, b, c) with h = a->b, h1 = b->c, h2 = c->a;
  //         g = (b, a, d) with o = b->a, o1 = a->d, o2 = d->b.
  // After:  f = (a, d, c) with o1, h = d->c, h2;  g = (b, c, d) with h1, o = c->d, o2.
  const Halfedge h = halfedge(e, 0), h1 = next(h), h2 = next(h1);
  const Halfedge o = halfedge(e, 1), o1 = next(o), o2 = next(o1);
  const Vertex a = to_vertex(o), b = to_vertex(h), c = to_vertex(h1), d = to_vertex(o1);
  const Face f = face(h), g = face(o);

  set_vertex(h, c);
  set_vertex(o, d);
  set_next(o1, h);
  set_next(h, h2);
  set_next(h2, o1);
  set_next(h1, o);
  set_next(o, o2);
  set_next(o2, h1);
  set_face(o1, f);
  set_face(h1, g);
  set_halfedge(f, h);
  set_halfedge(g, o);
  if (halfedge(a) == h) set_halfedge(a, o1);
  if (halfedge(b) == o) set_halfedge(b, h1);
}

bool SurfaceMesh::is_collapse_ok(Halfedge h) const {
  if (!is_valid(h)) return false;
  const Halfedge o = opposite(h);
  const Vertex v0 = to_vertex(o), v1 = to_vertex(h);
  const Face fh = face(h), fo = face(o);
  if (!fh.is_valid() && !fo.is_valid()) return false;
  if (!is_manifold(v0) || !is_manifold(v1)) return false;

  // At each face of the edge: its two other edges must not both be boundary
  // edges, and an interior apex must keep valence >= 3.
  Vertex vl, vr;
  auto apex_ok = [&](Halfedge side, Vertex& apex) {
    const Halfedge s1 = next(side), s2 = next(s1);
    apex = to_vertex(s1);
    if (is_boundary(opposite(s1)) && is_boundary(opposite(s2))) return false;
    if (!is_boundary(apex) && valence(apex) <= 3) return false;
    return true;
  };
  if (fh.is_valid() && !apex_ok(h, vl)) return false;
  if (fo.is_valid() && !apex_ok(o, vr)) return false;
  if (vl == vr) return false;  // both valid and equal (only in degenerate meshes)

  // An interior edge between two boundary vertices would pinch the surface.
  if (fh.is_valid() && fo.is_valid() && is_boundary(v0) && is_boundary(v1)) return false;

  // Link condition: the only common neighbours of v0 and v1 are the apexes.
  std::vector<Vertex> ring1;
  for (Vertex w : vertices(v1)) ring1.push_back(w);
  for (Vertex w : vertices(v0)) {
    if (w == v1 || w == vl || w == vr) continue;
    if (std::find(ring1.begin(), ring1.end(), w) != ring1.end()) return false;
  }
  return true;
}

void SurfaceMesh::collapse(Halfedge h) {
  require_valid(h, "collapse");
  if (!is_collapse_ok(h))
    throw TopologyError("SurfaceMesh::collapse(" + str(h) + " = " + str(from_vertex(h)) + "->" + str(to_vertex(h)) +
                        "): refused by is_collapse_ok (link condition, "
                        "boundary configuration or valence)");
  const Halfedge o = opposite(h);
  const Vertex v0 = to_vertex(o), v1 = to_vertex(h);
  const Face fh = face(h), fo = face(o);
  Halfedge h1, h2, o1, o2;  // fh = (v0, v1, vl): h, h1 = v1->vl, h2 = vl->v0
  Vertex vl, vr;            // fo = (v1, v0, vr): o, o1 = v0->vr, o2 = vr->v1
  if (fh.is_valid()) {
    h1 = next(h);
    h2 = next(h1);
    vl = to_vertex(h1);
  }
  if (fo.is_valid()) {
    o1 = next(o);
    o2 = next(o1);
    vr = to_vertex(o1);
  }

  // 1. Every half-edge that ends at v0 now ends at v1.
  std::vector<Halfedge> out0;
  for (Halfedge g : halfedges(v0)) out0.push_back(g);
  for (Halfedge g : out0) set_vertex(opposite(g), v1);

  // 2. Take h and o out of their loops; a face of the edge becomes a 2-gon.
  {
    const Halfedge hp = prev(h), hn = next(h), op = prev(o), on = next(o);
    set_next(hp, hn);
    set_next(op, on);
  }

  // 3. Dissolve each 2-gon: the edge (v1, apex) is kept and takes the place of
  // the twin of the edge (v0, apex), which is deleted.
  auto dissolve = [&](Halfedge keep, Halfedge drop, Vertex apex, Halfedge apex_out) {
    // keep and t = opposite(drop) now have the same endpoints and direction.
    const Halfedge t = opposite(drop);
    const Halfedge tp = prev(t), tn = next(t);
    const Face ft = face(t);
    if (ft.is_valid())
      set_face(keep, ft);
    else
      set_boundary(keep);  // before the link that records its prev
    set_next(tp, keep);
    set_next(keep, tn);
    if (ft.is_valid() && halfedge(ft) == t) set_halfedge(ft, keep);
    if (halfedge(apex) == drop || halfedge(apex) == t) set_halfedge(apex, apex_out);
    edeleted_[edge(drop)] = true;
    ++deleted_edges_;
  };
  if (fh.is_valid()) dissolve(h1, h2, vl, opposite(h1));  // keep v1->vl, drop vl->v0
  if (fo.is_valid()) dissolve(o2, o1, vr, o2);            // keep vr->v1, drop v0->vr

  // 4. Vertex half-edges and deletion flags.
  set_halfedge(v1, fh.is_valid() ? h1 : opposite(o2));
  adjust_outgoing_halfedge(v1);
  if (vl.is_valid()) adjust_outgoing_halfedge(vl);
  if (vr.is_valid()) adjust_outgoing_halfedge(vr);
  set_halfedge(v0, Halfedge());
  vdeleted_[v0] = true;
  ++deleted_vertices_;
  edeleted_[edge(h)] = true;
  ++deleted_edges_;
  for (Face f : {fh, fo})
    if (f.is_valid()) {
      fdeleted_[f] = true;
      ++deleted_faces_;
    }
}

Vertex SurfaceMesh::split_face(Face f, const Vec3& p) {
  require_valid(f, "split_face");
  // f = (a, b, c) with h0 = a->b, h1 = b->c, h2 = c->a becomes
  // f = (a, b, v), f1 = (b, c, v), f2 = (c, a, v).
  const Halfedge h0 = halfedge(f), h1 = next(h0), h2 = next(h1);
  const Vertex a = to_vertex(h2), b = to_vertex(h0), c = to_vertex(h1);
  const Vertex v = add_vertex(p);
  const Halfedge av = new_edge(a, v), bv = new_edge(b, v), cv = new_edge(c, v);
  const Halfedge va = opposite(av), vb = opposite(bv), vc = opposite(cv);
  const Face f1 = new_face(), f2 = new_face();
  auto make = [&](Face g, Halfedge x, Halfedge y, Halfedge z) {
    set_next(x, y);
    set_next(y, z);
    set_next(z, x);
    set_face(x, g);
    set_face(y, g);
    set_face(z, g);
    set_halfedge(g, x);
  };
  make(f, h0, bv, va);
  make(f1, h1, cv, vb);
  make(f2, h2, av, vc);
  set_halfedge(v, va);
  return v;
}

Vertex SurfaceMesh::split_edge(Edge e, const Vec3& p) {
  require_valid(e, "split_edge");
  // h = a->b becomes a->v; o = b->a becomes v->a; new edge g = v->b, go = b->v.
  const Halfedge h = halfedge(e, 0), o = halfedge(e, 1);
  const Vertex b = to_vertex(h);
  const Halfedge hn = next(h), op = prev(o);
  const Face f = face(h), k = face(o);
  const Vertex v = add_vertex(p);
  const Halfedge g = new_edge(v, b), go = opposite(g);
  set_vertex(h, v);

  auto make = [&](Face fc, Halfedge x, Halfedge y, Halfedge z) {
    set_next(x, y);
    set_next(y, z);
    set_next(z, x);
    set_face(x, fc);
    set_face(y, fc);
    set_face(z, fc);
    set_halfedge(fc, x);
  };
  if (f.is_valid()) {
    // f = (a, b, c): h, h1 = b->c, h2 = c->a  ->  (a, v, c) and (v, b, c).
    const Halfedge h1 = hn, h2 = next(h1);
    const Halfedge q = new_edge(v, to_vertex(h1));  // v->c
    make(f, h, q, h2);
    make(new_face(), g, h1, opposite(q));
  } else {
    set_next(h, g);
    set_next(g, hn);
  }
  if (k.is_valid()) {
    // k = (b, a, d): o, o1 = a->d, o2 = d->b  ->  (v, a, d) and (b, v, d).
    const Halfedge o1 = next(o), o2 = next(o1);
    const Halfedge r = new_edge(to_vertex(o1), v);  // d->v
    make(k, o, o1, r);
    make(new_face(), go, opposite(r), o2);
  } else {
    set_next(op, go);
    set_next(go, o);
  }
  if (halfedge(b) == o) set_halfedge(b, go);
  set_halfedge(v, !f.is_valid() ? g : o);
  adjust_outgoing_halfedge(b);
  return v;
}

void SurfaceMesh::delete_face(Face f) {
  require_valid(f, "delete_face");
  Halfedge hs[3];
  Vertex vs[3];
  int i = 0;
  for (Halfedge h : halfedges(f)) {
    hs[i] = h;
    vs[i] = to_vertex(h);
    ++i;
  }
  // The face's half-edges become a boundary loop of three; edges with no face
  // left are then cut out of the boundary loops.
  std::vector<Edge> dead;
  for (int k = 0; k < 3; ++k) {
    set_boundary(hs[k], hs[(k + 2) % 3]);
    if (is_boundary(opposite(hs[k]))) dead.push_back(edge(hs[k]));
  }
  fdeleted_[f] = true;
  ++deleted_faces_;

  for (Edge e : dead) {
    // h0 = v1->v0, h1 = v0->v1, both boundary: p1 -> h1 at v0 is followed by
    // h0 -> n0, and p0 -> h0 at v1 by h1 -> n1.
    const Halfedge h0 = halfedge(e, 0), h1 = halfedge(e, 1);
    const Vertex v0 = to_vertex(h0), v1 = to_vertex(h1);
    const Halfedge n0 = next(h0), p0 = prev(h0), n1 = next(h1), p1 = prev(h1);
    const bool v0_alone = n0 == h1, v1_alone = n1 == h0;
    if (!v0_alone) set_next(p1, n0);
    if (!v1_alone) set_next(p0, n1);
    if (halfedge(v0) == h1) set_halfedge(v0, v0_alone ? Halfedge() : n0);
    if (halfedge(v1) == h0) set_halfedge(v1, v1_alone ? Halfedge() : n1);
    edeleted_[e] = true;
    ++deleted_edges_;
  }
  for (Vertex v : vs) {
    if (is_isolated(v)) {
      vdeleted_[v] = true;
      ++deleted_vertices_;
    } else {
      adjust_outgoing_halfedge(v);
    }
  }
}

void SurfaceMesh::delete_vertex(Vertex v) {
  require_valid(v, "delete_vertex");
  std::vector<Face> fs;
  for (Face f : faces(v)) fs.push_back(f);
  for (Face f : fs) delete_face(f);
  if (!is_deleted(v)) {  // v was isolated
    vdeleted_[v] = true;
    ++deleted_vertices_;
  }
}

void SurfaceMesh::garbage_collection() {
  if (!has_garbage()) return;
  // Old -> new index maps (detail::CompactionMap) drive the compaction.
  auto build = [](std::size_t n, auto deleted) {
    std::pair<std::vector<Index>, std::size_t> r;  // (map, kept)
    r.first.assign(n, kInvalidIndex);
    for (std::size_t i = 0; i < n; ++i)
      if (!deleted(Index(i))) r.first[i] = Index(r.second++);
    return r;
  };
  const auto [vmap, vkept] = build(vertices_size(), [&](Index i) { return is_deleted(Vertex(i)); });
  const auto [emap, ekept] = build(edges_size(), [&](Index i) { return is_deleted(Edge(i)); });
  const auto [fmap, fkept] = build(faces_size(), [&](Index i) { return is_deleted(Face(i)); });
  auto hmap = [&](Halfedge h) { return h.is_valid() ? Halfedge(2 * emap[h.idx() >> 1] + (h.idx() & 1u)) : h; };

  for (std::size_t v = 0; v < vmap.size(); ++v)
    if (vmap[v] != kInvalidIndex) vconn_[Vertex(Index(v))].halfedge = hmap(vconn_[Vertex(Index(v))].halfedge);
  for (std::size_t f = 0; f < fmap.size(); ++f)
    if (fmap[f] != kInvalidIndex) fconn_[Face(Index(f))].halfedge = hmap(fconn_[Face(Index(f))].halfedge);
  for (std::size_t e = 0; e < emap.size(); ++e) {
    if (emap[e] == kInvalidIndex) continue;
    for (Index hi : {Index(2 * e), Index(2 * e + 1)}) {
      HalfedgeConnectivity& c = hconn_[Halfedge(hi)];
      c.to = Vertex(vmap[c.to.idx()]);
      c.face_or_prev = renumbered_face_or_prev(
          c.face_or_prev, [&](Index f) { return fmap[f]; }, [&](Index p) { return hmap(Halfedge(p)).idx(); });
      c.next = hmap(c.next);
    }
  }
  vprops_.compact({vmap, vkept, false});
  hprops_.compact({emap, 2 * ekept, true});
  eprops_.compact({emap, ekept, false});
  fprops_.compact({fmap, fkept, false});
  deleted_vertices_ = deleted_edges_ = deleted_faces_ = 0;
}

// ---------------------------------------------------------------------------
// SurfaceMesh Conversion
// ---------------------------------------------------------------------------

SurfaceMesh SurfaceMesh::from_indexed_mesh(const IndexedMesh& m) {
  SurfaceMesh mesh;
  mesh.reserve(m.positions.size(), m.triangles.size());
  for (const Vec3& p : m.positions) mesh.add_vertex(p);
  const std::size_t nv = m.positions.size();
  for (std::size_t j = 0; j < m.triangles.size(); ++j) {
    const auto& t = m.triangles[j];
    auto where = [&] {
      return "SurfaceMesh::from_indexed_mesh: triangle " + std::to_string(j) + " (" + std::to_string(t[0]) + ", " +
             std::to_string(t[1]) + ", " + std::to_string(t[2]) + "): ";
    };
    if (t[0] >= nv || t[1] >= nv || t[2] >= nv)
      throw TopologyError(where() + "vertex index out of range (" + std::to_string(nv) + " vertices)");
    try {
      mesh.add_triangle(Vertex(t[0]), Vertex(t[1]), Vertex(t[2]));
    } catch (const TopologyError& e) {
      throw TopologyError(where() + e.what());
    }
  }
  for (Vertex v : mesh.vertices())
    if (!mesh.is_manifold(v))
      throw TopologyError("SurfaceMesh::from_indexed_mesh: vertex " + std::to_string(v.idx()) + " is non-manifold (" +
                          std::to_string(mesh.boundary_gaps(v)) + " fans meet there)");
  return mesh;
}

IndexedMesh SurfaceMesh::to_indexed_mesh() const {
  IndexedMesh m;
  m.positions.resize(n_vertices());
  m.triangles.resize(n_faces());
  write_indexed(m.positions, m.triangles, 0, 0);
  return m;
}

void SurfaceMesh::write_indexed(std::span<Vec3> positions, std::span<std::array<Index, 3>> triangles,
                                std::size_t vertex_base, std::size_t face_base) const {
  std::size_t i = vertex_base;
  for (Vertex v : vertices()) positions[i++] = position(v);
  write_indexed_triangles(triangles, vertex_base, face_base);
}

void SurfaceMesh::write_indexed_triangles(std::span<std::array<Index, 3>> triangles, std::size_t vertex_base,
                                          std::size_t face_base) const {
  std::vector<Index> map(vertices_size(), kInvalidIndex);
  std::size_t i = vertex_base;
  for (Vertex v : vertices()) map[v.idx()] = Index(i++);
  std::size_t j = face_base;
  for (Face f : faces()) {
    Halfedge h = halfedge(f);
    for (int k = 0; k < 3; ++k, h = next(h)) triangles[j][k] = map[from_vertex(h).idx()];
    ++j;
  }
}

// ---------------------------------------------------------------------------
// SurfaceMesh Debugging
// ---------------------------------------------------------------------------

void SurfaceMesh::check_consistency() const {
  auto fail = [](const std::string& what) { throw std::logic_error("SurfaceMesh::check_consistency: " + what); };
  const std::size_t nv = vertices_size(), nh = halfedges_size(), ne = edges_size(), nf = faces_size();
  // Sizes and counters.
  if (nh != 2 * ne) fail("half-edge count " + std::to_string(nh) + " != 2 * edge count");
  if (vconn_.vector().size() != nv || vpoint_.vector().size() != nv || vdeleted_.vector().size() != nv ||
      hconn_.vector().size() != nh || edeleted_.vector().size() != ne || fconn_.vector().size() != nf ||
      fdeleted_.vector().size() != nf)
    fail("a built-in property array has the wrong size");
  std::size_t dv = 0, de = 0, df = 0;
  for (std::size_t i = 0; i < nv; ++i) dv += vdeleted_.vector()[i] ? 1 : 0;
  for (std::size_t i = 0; i < ne; ++i) de += edeleted_.vector()[i] ? 1 : 0;
  for (std::size_t i = 0; i < nf; ++i) df += fdeleted_.vector()[i] ? 1 : 0;
  if (dv != deleted_vertices_ || de != deleted_edges_ || df != deleted_faces_)
    fail("deletion counters do not match the deletion flags");

  auto live = [&](auto hnd, std::size_t n) { return hnd.idx() < n && !is_deleted(hnd); };
  // Half-edges.
  std::vector<std::size_t> outgoing(nv, 0);
  std::vector<bool> on_checked_loop(nh, false);
  for (Halfedge h : halfedges()) {
    auto hs = [&] { return str(h); };  // built only for a message
    const Halfedge n = next(h), p = prev(h);
    if (!live(n, nh)) fail("next(" + hs() + ") = " + str(n) + " is invalid or deleted");
    if (!live(p, nh)) fail("prev(" + hs() + ") = " + str(p) + " is invalid or deleted");
    if (prev(n) != h) fail("prev(next(" + hs() + ")) != " + hs());
    if (next(p) != h) fail("next(prev(" + hs() + ")) != " + hs());
    const Vertex t = to_vertex(h);
    if (!live(t, nv)) fail("to_vertex(" + hs() + ") = " + str(t) + " is invalid or deleted");
    if (from_vertex(n) != t) fail("next(" + hs() + ") does not start where " + hs() + " ends");
    if (from_vertex(h) == t) fail(hs() + " is a loop at " + str(t));
    if (is_boundary(h) && is_boundary(opposite(h))) fail("edge " + str(edge(h)) + " has no face on either side");
    const Face f = face(h);
    if (f.is_valid()) {
      if (!live(f, nf)) fail("face(" + hs() + ") = " + str(f) + " is deleted or out of range");
      if (next(next(next(h))) != h) fail("face " + str(f) + " is not a cycle of length 3 at " + hs());
      if (face(n) != f) fail("next(" + hs() + ") is not in face " + str(f));
    } else if (!on_checked_loop[h.idx()]) {
      // A boundary loop is closed and boundary all along (walked once per loop).
      Halfedge g = h;
      std::size_t len = 0;
      do {
        if (!is_boundary(g)) fail("boundary loop through " + hs() + " contains non-boundary " + str(g));
        on_checked_loop[g.idx()] = true;
        g = next(g);
        if (++len > nh) fail("boundary loop through " + hs() + " does not close");
      } while (g != h);
      if (len < 3) fail("boundary loop through " + hs() + " has length " + std::to_string(len));
    }
    ++outgoing[from_vertex(h).idx()];
  }
  // Faces.
  for (Face f : faces()) {
    const Halfedge h = halfedge(f);
    if (!live(h, nh)) fail("halfedge(" + str(f) + ") is invalid or deleted");
    if (face(h) != f) fail("face(halfedge(" + str(f) + ")) != " + str(f));
  }
  // Vertices: outgoing half-edge, boundary preference, complete circulation,
  // no duplicate edges.
  std::vector<Index> ring;
  for (Vertex v : vertices()) {
    auto vs = [&] { return str(v); };
    const Halfedge h0 = halfedge(v);
    if (!h0.is_valid()) {
      if (outgoing[v.idx()] != 0)
        fail(vs() + " has no half-edge but " + std::to_string(outgoing[v.idx()]) + " outgoing ones");
      continue;
    }
    if (!live(h0, nh)) fail("halfedge(" + vs() + ") = " + str(h0) + " is deleted or out of range");
    if (from_vertex(h0) != v) fail("halfedge(" + vs() + ") does not start at " + vs());
    std::size_t count = 0;
    bool any_boundary = false;
    ring.clear();
    Halfedge h = h0;
    do {
      if (from_vertex(h) != v) fail("circulation around " + vs() + " leaves the vertex at " + str(h));
      any_boundary = any_boundary || is_boundary(h);
      ring.push_back(to_vertex(h).idx());
      h = ccw_rotated(h);
      if (++count > outgoing[v.idx()]) fail("circulation around " + vs() + " does not return");
    } while (h != h0);
    if (count != outgoing[v.idx()])
      fail("circulation around " + vs() + " visits " + std::to_string(count) + " of " +
           std::to_string(outgoing[v.idx()]) + " outgoing half-edges");
    if (any_boundary && !is_boundary(h0))
      fail("halfedge(" + vs() + ") is interior although " + vs() + " is on the boundary");
    std::sort(ring.begin(), ring.end());
    if (std::adjacent_find(ring.begin(), ring.end()) != ring.end()) fail(vs() + " has two edges to the same vertex");
  }
}

// ---------------------------------------------------------------------------
// SurfaceMesh Binary Files
// ---------------------------------------------------------------------------

namespace {

/// The first bytes of a binary mesh, and a value whose bytes say the byte order.
constexpr char kBinaryMagic[8] = {'s', 'k', 'm', 'e', 's', 'h', 'M', '1'};
constexpr std::uint32_t kByteOrder = 0x01020304;

void write_container(std::ostream& os, const detail::PropertyContainer& c) {
  put_raw<std::uint64_t>(os, c.size());
  put_raw<std::uint64_t>(os, c.arrays().size());
  for (const auto& a : c.arrays()) {
    put_string(os, a->name());
    put_raw<std::uint32_t>(os, a->tag());
    put_raw<std::uint64_t>(os, a->value_size());
    a->write_raw(os);
  }
}

void read_container(std::istream& is, detail::PropertyContainer& c, const std::string& file) {
  const std::uint64_t n = get_count(is, file);
  const std::uint64_t arrays = get_count(is, file, 1024);
  std::vector<const detail::BasePropertyArray*> read;
  for (std::uint64_t i = 0; i < arrays; ++i) {
    const std::string name = get_string(is, file);
    const auto tag = get_raw<std::uint32_t>(is, file);
    const auto size = get_raw<std::uint64_t>(is, file);
    detail::BasePropertyArray* a = c.find(name);
    if (a == nullptr) a = c.add_of_tag(name, tag);
    if (a == nullptr || a->tag() != tag || a->value_size() != size)
      throw InputError(file, 0, "the mesh property '" + name + "' has a type this reader does not know");
    a->read_raw(is, file);
    if (a->size() != n)
      throw InputError(file, 0, "the mesh property '" + name + "' has the wrong count (a damaged file)");
    read.push_back(a);
  }
  // An array the file does not hold keeps its default values.
  for (const auto& a : c.arrays())
    if (std::find(read.begin(), read.end(), a.get()) == read.end()) a->resize(n);
  c.set_size(n);
}

}  // namespace

namespace detail {

BasePropertyArray* PropertyContainer::add_of_tag(const std::string& name, std::uint32_t tag) {
  switch (tag) {
    case 1:
      return add<bool>(name, false);
    case 2:
      return add<std::uint8_t>(name, 0);
    case 3:
      return add<std::int8_t>(name, 0);
    case 4:
      return add<std::uint16_t>(name, 0);
    case 5:
      return add<std::int16_t>(name, 0);
    case 6:
      return add<std::uint32_t>(name, 0);
    case 7:
      return add<std::int32_t>(name, 0);
    case 8:
      return add<std::uint64_t>(name, 0);
    case 9:
      return add<std::int64_t>(name, 0);
    case 10:
      return add<float>(name, 0.0f);
    case 11:
      return add<double>(name, 0.0);
    case 12:
      return add<Vec3>(name, Vec3::Zero());
    default:
      return nullptr;
  }
}

}  // namespace detail

void SurfaceMesh::write_binary(std::ostream& os) const {
  os.write(kBinaryMagic, sizeof kBinaryMagic);
  put_raw(os, kByteOrder);
  for (const detail::PropertyContainer* c : {&vprops_, &hprops_, &eprops_, &fprops_}) write_container(os, *c);
  put_raw<std::uint64_t>(os, deleted_vertices_);
  put_raw<std::uint64_t>(os, deleted_edges_);
  put_raw<std::uint64_t>(os, deleted_faces_);
}

SurfaceMesh SurfaceMesh::read_binary(std::istream& is, const std::string& file) {
  char magic[sizeof kBinaryMagic];
  get_bytes(is, magic, sizeof magic, file);
  if (!std::equal(magic, magic + sizeof magic, kBinaryMagic))
    throw InputError(file, 0, "not a mesh written by skinmesh (no binary mesh marker)");
  if (get_raw<std::uint32_t>(is, file) != kByteOrder)
    throw InputError(file, 0, "the mesh was written on a machine of the other byte order");
  SurfaceMesh m;
  for (detail::PropertyContainer* c : {&m.vprops_, &m.hprops_, &m.eprops_, &m.fprops_}) read_container(is, *c, file);
  m.deleted_vertices_ = get_count(is, file, m.vprops_.size());
  m.deleted_edges_ = get_count(is, file, m.eprops_.size());
  m.deleted_faces_ = get_count(is, file, m.fprops_.size());
  if (m.hprops_.size() != 2 * m.eprops_.size())
    throw InputError(file, 0, "the mesh's half-edges are not twice its edges (a damaged file)");
  try {
    m.check_consistency();
  } catch (const std::logic_error& e) {
    throw InputError(file, 0, std::string("the mesh read is not consistent (a damaged file): ") + e.what());
  }
  return m;
}

}  // namespace skinmesh::geometry
