// geometry/mesh/surface_mesh.h: SurfaceMesh, the half-edge triangle mesh that the
// advancing front (front/) and the local refinement (refine/) edit together.
// Design after pmp-library's SurfaceMesh (papers/conventions.md §1): typed
// handles, paired half-edges, named per-element properties, check-then-modify
// operations.
#pragma once

#include <array>
#include <compare>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <istream>
#include <iterator>
#include <memory>
#include <ostream>
#include <span>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <typeinfo>
#include <utility>
#include <vector>

#include "core/binary_io.h"
#include "core/growable_array.h"
#include "core/types.h"
#include "geometry/mesh/indexed_mesh.h"

namespace skinmesh::geometry {

// ---------------------------------------------------------------------------
// Handles
// ---------------------------------------------------------------------------

namespace detail {

/// Common part of the four handle types: one Index, kInvalidIndex when invalid.
/// CRTP so that handles of different kinds cannot be compared or mixed.
template <class Derived>
class Handle {
 public:
  /// An invalid handle.
  constexpr Handle() = default;
  /// A handle on element number `idx` (0-based).
  constexpr explicit Handle(Index idx) : idx_(idx) {}
  /// The element number (kInvalidIndex if invalid).
  constexpr Index idx() const { return idx_; }
  /// True unless the handle is the invalid value. Says nothing about deletion.
  constexpr bool is_valid() const { return idx_ != kInvalidIndex; }
  /// Handles compare by index (same kind only).
  friend constexpr bool operator==(Derived a, Derived b) { return a.idx_ == b.idx_; }
  friend constexpr std::strong_ordering operator<=>(Derived a, Derived b) { return a.idx_ <=> b.idx_; }

 private:
  Index idx_ = kInvalidIndex;
};

}  // namespace detail

/// Handle on a mesh vertex.
class Vertex : public detail::Handle<Vertex> {
 public:
  using Handle::Handle;
};
/// Handle on a half-edge. Half-edges come in pairs: 2e and 2e+1 belong to edge e.
class Halfedge : public detail::Handle<Halfedge> {
 public:
  using Handle::Handle;
};
/// Handle on an (undirected) edge, i.e. a pair of half-edges.
class Edge : public detail::Handle<Edge> {
 public:
  using Handle::Handle;
};
/// Handle on a triangle.
class Face : public detail::Handle<Face> {
 public:
  using Handle::Handle;
};

/// Print handles as "v12", "h3", "e7", "f0" ("v-" when invalid), for messages and tests.
std::ostream& operator<<(std::ostream& os, Vertex v);
std::ostream& operator<<(std::ostream& os, Halfedge h);
std::ostream& operator<<(std::ostream& os, Edge e);
std::ostream& operator<<(std::ostream& os, Face f);

// ---------------------------------------------------------------------------
// Properties
// ---------------------------------------------------------------------------

namespace detail {

/// The old -> new index map of a compaction (SurfaceMesh::garbage_collection):
/// element i goes to index (*this)(i), or is dropped if that is
/// kInvalidIndex. Kept elements keep their order, so (*this)(i) <= i and an
/// array compacts in place, front to back. With `pairs` (the half-edges) the
/// map is per edge: half-edge i goes where its edge goes, times two, plus i's
/// parity. Only the map is held (4 bytes per vertex, edge and face): a list of
/// the kept elements beside it would double that at a slab's end, the sweep's
/// peak (papers/decompose/history.md, "Normals and rho from the cell").
struct CompactionMap {
  std::span<const Index> map;
  std::size_t kept = 0;  ///< elements kept
  bool pairs = false;
  std::size_t size() const { return pairs ? 2 * map.size() : map.size(); }
  Index operator()(std::size_t i) const {
    if (!pairs) return map[i];
    const Index e = map[i >> 1];
    return e == kInvalidIndex ? kInvalidIndex : 2 * e + Index(i & 1u);
  }
};

/// Type-erased array of per-element values, owned by a PropertyContainer.
/// The value type of a property as SurfaceMesh::write_binary() names it:
/// 1–11 the arithmetic types (bool, the fixed-width integers, float,
/// double), 12 Vec3, 255 any other type whose bytes are its value (an
/// opaque struct: readable only into an array that exists already with
/// the same size of value), 0 a type that cannot be written.
template <class T>
constexpr std::uint32_t raw_tag() {
  if constexpr (std::is_same_v<T, bool>)
    return 1;
  else if constexpr (std::is_same_v<T, std::uint8_t>)
    return 2;
  else if constexpr (std::is_same_v<T, std::int8_t>)
    return 3;
  else if constexpr (std::is_same_v<T, std::uint16_t>)
    return 4;
  else if constexpr (std::is_same_v<T, std::int16_t>)
    return 5;
  else if constexpr (std::is_same_v<T, std::uint32_t>)
    return 6;
  else if constexpr (std::is_same_v<T, std::int32_t>)
    return 7;
  else if constexpr (std::is_same_v<T, std::uint64_t>)
    return 8;
  else if constexpr (std::is_same_v<T, std::int64_t>)
    return 9;
  else if constexpr (std::is_same_v<T, float>)
    return 10;
  else if constexpr (std::is_same_v<T, double>)
    return 11;
  else if constexpr (std::is_same_v<T, Vec3>)
    return 12;
  else if constexpr (kRelocatable<T> && std::is_trivially_destructible_v<T>)
    return 255;
  else
    return 0;
}

class BasePropertyArray {
 public:
  explicit BasePropertyArray(std::string name) : name_(std::move(name)) {}
  virtual ~BasePropertyArray() = default;
  BasePropertyArray(const BasePropertyArray&) = default;
  BasePropertyArray& operator=(const BasePropertyArray&) = delete;
  /// Resize to n elements; new elements get the default value.
  virtual void resize(std::size_t n) = 0;
  /// Capacity for n elements.
  virtual void reserve(std::size_t n) = 0;
  /// No element and no capacity: the memory goes back.
  virtual void release() = 0;
  /// Append one element with the default value.
  virtual void push_back() = 0;
  /// Appends the n elements of `src` if it holds this array's type (else n
  /// default values), then empties `src`: copied in chunks, each chunk's
  /// pages of `src` given back as soon as it is copied, so the peak holds one
  /// copy of the elements plus a chunk. Pre: src is nullptr or has n elements.
  virtual void append_consuming(BasePropertyArray* src, std::size_t n) = 0;
  /// Moves every element i to map(i) and drops the others (CompactionMap).
  virtual void compact(const CompactionMap& map) = 0;
  /// Deep copy.
  virtual std::unique_ptr<BasePropertyArray> clone() const = 0;
  /// The value type.
  virtual const std::type_info& type() const = 0;
  /// The number of elements.
  virtual std::size_t size() const = 0;
  /// raw_tag() of the value type, and its size in bytes.
  virtual std::uint32_t tag() const = 0;
  virtual std::size_t value_size() const = 0;
  /// Writes the default value, the element count and the elements, as
  /// their bytes (SurfaceMesh::write_binary()). Throws std::invalid_argument
  /// for a value type of tag 0.
  virtual void write_raw(std::ostream& os) const = 0;
  /// Reads what write_raw() wrote into this array (same tag and value size):
  /// the default value and the elements, replacing both. Throws InputError
  /// naming `file` if the stream ends first.
  virtual void read_raw(std::istream& is, const std::string& file) = 0;
  /// The property's name.
  const std::string& name() const { return name_; }

 private:
  std::string name_;
};

/// Storage of a property of type T: a GrowableArray (grown by realloc, an
/// eighth at a time: little unused capacity, no copy for large arrays) for
/// relocatable types, std::vector for the others.
template <class T>
using PropertyStorage =
    std::conditional_t<kRelocatable<T> && std::is_trivially_destructible_v<T>, GrowableArray<T>, std::vector<T>>;

/// Array of values of type T with a default value for new elements.
template <class T>
class PropertyArray final : public BasePropertyArray {
 public:
  PropertyArray(std::string name, T init) : BasePropertyArray(std::move(name)), init_(std::move(init)) {}
  void resize(std::size_t n) override { data_.resize(n, init_); }
  void reserve(std::size_t n) override { data_.reserve(n); }
  void release() override { data_ = PropertyStorage<T>(); }
  void push_back() override { data_.push_back(init_); }
  void append_consuming(BasePropertyArray* src, std::size_t n) override {
    const std::size_t base = data_.size();
    if (src == nullptr || src->type() != typeid(T)) {
      data_.resize(base + n, init_);
      return;
    }
    auto& from = static_cast<PropertyArray<T>*>(src)->data_;
    data_.reserve(base + n);
    // [chosen] about 1 MiB a chunk: a few hundred pages given back at a time.
    constexpr std::size_t kChunk = std::max<std::size_t>(1, (std::size_t{1} << 20) / sizeof(T));
    for (std::size_t i = 0; i < n; i += kChunk) {
      const std::size_t end = std::min(n, i + kChunk);
      for (std::size_t j = i; j < end; ++j) data_.push_back(from[j]);
      if constexpr (!std::is_same_v<PropertyStorage<T>, std::vector<T>>) from.discard_front(end);
    }
    src->release();
  }
  void compact(const CompactionMap& map) override {
    for (std::size_t i = 0, n = map.size(); i < n; ++i) {
      const Index j = map(i);
      if (j != kInvalidIndex && j != i) data_[j] = data_[i];
    }
    data_.resize(map.kept);
  }
  std::unique_ptr<BasePropertyArray> clone() const override { return std::make_unique<PropertyArray<T>>(*this); }
  const std::type_info& type() const override { return typeid(T); }
  std::size_t size() const override { return data_.size(); }
  std::uint32_t tag() const override { return raw_tag<T>(); }
  std::size_t value_size() const override { return sizeof(T); }
  void write_raw(std::ostream& os) const override {
    if constexpr (raw_tag<T>() != 0) {
      os.write(reinterpret_cast<const char*>(&init_), sizeof(T));
      const std::uint64_t n = data_.size();
      os.write(reinterpret_cast<const char*>(&n), sizeof n);
      os.write(reinterpret_cast<const char*>(data_.data()), static_cast<std::streamsize>(n * sizeof(T)));
    } else {
      (void)os;
      throw std::invalid_argument("SurfaceMesh: the property '" + name() + "' has a type that cannot be written");
    }
  }
  void read_raw(std::istream& is, const std::string& file) override {
    if constexpr (raw_tag<T>() != 0) {
      get_bytes(is, &init_, sizeof(T), file);
      std::uint64_t n = 0;
      get_bytes(is, &n, sizeof n, file);
      if (n > (std::uint64_t{1} << 40) / sizeof(T))
        throw InputError(file, 0, "the property '" + name() + "' has too many elements (a damaged file)");
      data_.resize(n, init_);
      get_bytes(is, data_.data(), n * sizeof(T), file);
    } else {
      (void)is;
      throw InputError(file, 0, "the property '" + name() + "' has a type that cannot be read");
    }
  }
  PropertyStorage<T>& data() { return data_; }

 private:
  PropertyStorage<T> data_;
  T init_;
};

/// The set of property arrays of one element kind; all have the same size.
class PropertyContainer {
 public:
  PropertyContainer() = default;
  PropertyContainer(const PropertyContainer& other) { *this = other; }
  PropertyContainer& operator=(const PropertyContainer& other) {
    if (this == &other) return *this;
    arrays_.clear();
    for (const auto& a : other.arrays_) arrays_.push_back(a->clone());
    size_ = other.size_;
    return *this;
  }
  PropertyContainer(PropertyContainer&&) noexcept = default;
  PropertyContainer& operator=(PropertyContainer&&) noexcept = default;

  std::size_t size() const { return size_; }
  BasePropertyArray* find(const std::string& name) const {
    for (const auto& a : arrays_)
      if (a->name() == name) return a.get();
    return nullptr;
  }
  template <class T>
  PropertyArray<T>* add(const std::string& name, T init) {
    auto a = std::make_unique<PropertyArray<T>>(name, std::move(init));
    a->resize(size_);
    PropertyArray<T>* p = a.get();
    arrays_.push_back(std::move(a));
    return p;
  }
  template <class T>
  PropertyArray<T>* get(const std::string& name) const {
    BasePropertyArray* a = find(name);
    if (a == nullptr || a->type() != typeid(T)) return nullptr;
    return static_cast<PropertyArray<T>*>(a);
  }
  void remove(const BasePropertyArray* p) {
    for (auto it = arrays_.begin(); it != arrays_.end(); ++it)
      if (it->get() == p) {
        arrays_.erase(it);
        return;
      }
  }
  void push_back() {
    for (auto& a : arrays_) a->push_back();
    ++size_;
  }
  void resize(std::size_t n) {
    for (auto& a : arrays_) a->resize(n);
    size_ = n;
  }
  void reserve(std::size_t n) {
    for (auto& a : arrays_) a->reserve(n);
  }
  /// Appends `other`'s elements: each array gets the values of `other`'s
  /// array of the same name and type, or default values where it has none
  /// (BasePropertyArray::append_consuming). `other` is left with no element
  /// and no memory (its properties stay).
  void append_consuming(PropertyContainer& other) {
    const std::size_t n = other.size_;
    for (auto& a : arrays_) a->append_consuming(other.find(a->name()), n);
    size_ += n;
    other.release();
  }
  /// Every array emptied and its memory given back (the properties stay).
  void release() {
    for (auto& a : arrays_) a->release();
    size_ = 0;
  }
  void compact(const CompactionMap& map) {
    for (auto& a : arrays_) a->compact(map);
    size_ = map.kept;
  }
  /// The arrays, in the order they were added.
  const std::vector<std::unique_ptr<BasePropertyArray>>& arrays() const { return arrays_; }
  /// A new array of the arithmetic type or Vec3 of raw_tag() `tag`, named
  /// `name`, added last; nullptr for any other tag.
  BasePropertyArray* add_of_tag(const std::string& name, std::uint32_t tag);
  /// The element count, once read_raw() has filled every array with it.
  void set_size(std::size_t n) { size_ = n; }

 private:
  std::vector<std::unique_ptr<BasePropertyArray>> arrays_;
  std::size_t size_ = 0;
};

}  // namespace detail

/// A named per-element array of T inside a SurfaceMesh, indexed by handles of
/// kind H only (a VertexProperty cannot be indexed by a Face). A property is a
/// light reference: copying it does not copy the values. It stays valid until
/// it is removed or the mesh is destroyed, also across garbage_collection()
/// (whose compaction it follows); it is not valid on a copy of the mesh (ask the
/// copy for its own property by name).
template <class H, class T>
class Property {
 public:
  using reference = typename detail::PropertyStorage<T>::reference;
  using const_reference = typename detail::PropertyStorage<T>::const_reference;

  /// An invalid property (what get_*_property returns when the name is unknown).
  Property() = default;
  /// True if the property refers to an existing array.
  bool is_valid() const { return array_ != nullptr; }
  explicit operator bool() const { return is_valid(); }
  /// The value of element h. Pre: valid property, h.idx() < number of elements.
  reference operator[](H h) { return array_->data()[h.idx()]; }
  const_reference operator[](H h) const { return array_->data()[h.idx()]; }
  /// All values, indexed by element number (deleted elements included): a
  /// GrowableArray<T> (std::vector<T> for types that are not relocatable).
  detail::PropertyStorage<T>& vector() { return array_->data(); }
  const detail::PropertyStorage<T>& vector() const { return array_->data(); }
  /// The property's name.
  const std::string& name() const { return array_->name(); }

 private:
  friend class SurfaceMesh;
  explicit Property(detail::PropertyArray<T>* a) : array_(a) {}
  detail::PropertyArray<T>* array_ = nullptr;
};

/// Per-vertex property of type T.
template <class T>
using VertexProperty = Property<Vertex, T>;
/// Per-half-edge property of type T.
template <class T>
using HalfedgeProperty = Property<Halfedge, T>;
/// Per-edge property of type T.
template <class T>
using EdgeProperty = Property<Edge, T>;
/// Per-face property of type T.
template <class T>
using FaceProperty = Property<Face, T>;

/// The name and value type of a vertex property that several stages share:
/// declared once (constexpr), used wherever the property is added or read, so
/// that a mismatch of name or type cannot compile.
template <class T>
struct VertexPropertyKey {
  const char* name;
};

// ---------------------------------------------------------------------------
// Ranges and circulators
// ---------------------------------------------------------------------------

class SurfaceMesh;

/// Range over all non-deleted elements of kind H, in index order.
template <class H>
class HandleRange {
 public:
  /// Input iterator yielding handles by value.
  class Iterator {
   public:
    using iterator_category = std::input_iterator_tag;
    using value_type = H;
    using reference = H;
    using pointer = void;
    using difference_type = std::ptrdiff_t;
    Iterator() = default;
    Iterator(const SurfaceMesh* m, Index i, Index n) : mesh_(m), i_(i), n_(n) { skip(); }
    H operator*() const { return H(i_); }
    Iterator& operator++() {
      ++i_;
      skip();
      return *this;
    }
    Iterator operator++(int) {
      Iterator t = *this;
      ++*this;
      return t;
    }
    bool operator==(const Iterator& o) const { return i_ == o.i_; }

   private:
    void skip();
    const SurfaceMesh* mesh_ = nullptr;
    Index i_ = 0, n_ = 0;
  };
  /// Elements 0 .. n-1 of mesh m, deleted ones skipped.
  HandleRange(const SurfaceMesh* m, Index n) : mesh_(m), n_(n) {}
  /// First non-deleted element.
  Iterator begin() const { return Iterator(mesh_, 0, n_); }
  /// Past the end.
  Iterator end() const { return Iterator(mesh_, n_, n_); }

 private:
  const SurfaceMesh* mesh_;
  Index n_;
};

/// The kinds of circulation SurfaceMesh offers (see Circulator).
enum class CirculatorKind {
  kVertexOutgoing,  ///< outgoing half-edges of a vertex, counter-clockwise
  kVertexVertices,  ///< the one-ring vertices, counter-clockwise
  kVertexFaces,     ///< the faces around a vertex, counter-clockwise, no invalid faces
  kFaceHalfedges,   ///< the half-edges of a face (or of a boundary loop) along next()
  kFaceVertices,    ///< the vertices of a face, in its order
};

/// Range over the elements around a vertex or a face, starting at a half-edge
/// and stepping until it comes back to it. Around a vertex the step is
/// ccw_rotated(h) = opposite(prev(h)): through faces and, across a boundary gap,
/// along the boundary links, so all fans of a pinched vertex are visited.
template <CirculatorKind K>
class Circulator {
 public:
  /// What the circulator yields: Halfedge, Vertex or Face.
  using value_type = std::conditional_t<K == CirculatorKind::kVertexOutgoing || K == CirculatorKind::kFaceHalfedges,
                                        Halfedge, std::conditional_t<K == CirculatorKind::kVertexFaces, Face, Vertex>>;
  /// Input iterator yielding handles by value.
  class Iterator {
   public:
    using iterator_category = std::input_iterator_tag;
    using value_type = Circulator::value_type;
    using reference = value_type;
    using pointer = void;
    using difference_type = std::ptrdiff_t;
    Iterator() = default;
    Iterator(const SurfaceMesh* m, Halfedge start, bool at_end)
        : mesh_(m), start_(start), h_(start), lap_(at_end || !start.is_valid() ? 1 : 0) {
      if (lap_ == 0 && !accept()) advance();
    }
    value_type operator*() const;
    Iterator& operator++() {
      advance();
      return *this;
    }
    Iterator operator++(int) {
      Iterator t = *this;
      advance();
      return t;
    }
    bool operator==(const Iterator& o) const { return h_ == o.h_ && lap_ == o.lap_; }
    /// The current half-edge (for vertex circulators: outgoing from the centre).
    Halfedge halfedge() const { return h_; }

   private:
    bool accept() const;
    void advance();
    const SurfaceMesh* mesh_ = nullptr;
    Halfedge start_, h_;
    int lap_ = 1;
  };
  /// Circulate in mesh m from half-edge `start` (empty if start is invalid).
  Circulator(const SurfaceMesh* m, Halfedge start) : mesh_(m), start_(start) {}
  /// The element at `start` (or the first accepted one after it).
  Iterator begin() const { return Iterator(mesh_, start_, false); }
  /// Back at `start`.
  Iterator end() const { return Iterator(mesh_, start_, true); }

 private:
  const SurfaceMesh* mesh_;
  Halfedge start_;
};

// ---------------------------------------------------------------------------
// SurfaceMesh
// ---------------------------------------------------------------------------

/// Half-edge triangle mesh (pmp-library style, papers/conventions.md §1 and §3).
///
/// Storage. Half-edges come in pairs: opposite(h) = h ^ 1, edge(h) = h >> 1.
/// Every half-edge stores its target vertex, next, and one more field: its
/// face, or on the boundary (no face) its prev. Inside a face prev(h) is
/// next(next(h)), the faces being triangles, so storing it there too would
/// cost 4 bytes a half-edge, 12 a triangle, for a value one step away; a
/// boundary half-edge's prev (the front's previous edge) cannot be derived
/// that way. Every vertex stores one outgoing half-edge, every face one
/// half-edge. Hence at most 2^31 - 1 faces and half-edges (the field's top
/// bit says which of the two it holds); new_edge() and new_face() throw
/// std::length_error beyond.
/// Connectivity, positions ("v:point") and the deletion flags are ordinary
/// properties, so garbage_collection() compacts user properties with them.
///
/// Orientation. Faces are counter-clockwise seen from outside (normal
/// (b-a)x(c-a) points out). A boundary half-edge has an invalid face and the
/// hole on its left; next()/prev() of boundary half-edges walk the boundary
/// loop. These loops are the advancing front.
///
/// Boundary vertices. halfedge(v) of a boundary vertex is an outgoing boundary
/// half-edge. A vertex may temporarily carry several boundary gaps ("pinch",
/// several fans joined only at the vertex), as it happens while the front is
/// advancing; is_manifold(v) is false for it. Circulation goes through every fan.
///
/// Not supported: polygons other than triangles, edges without faces, vertices
/// whose fans close into a disk while other fans remain (refused by add_triangle).
///
/// Errors. Invalid input to an operation (a non-manifold edge, a wrong
/// orientation, an edge that cannot be flipped) throws skinmesh::TopologyError
/// and leaves the mesh unchanged; a handle that is out of range or deleted
/// throws std::invalid_argument. check_consistency() throws std::logic_error.
class SurfaceMesh {
 public:
  // SurfaceMesh Public Types
  /// Connectivity of a vertex: one outgoing half-edge (boundary one if any).
  struct VertexConnectivity {
    Halfedge halfedge;
  };
  /// Connectivity of a half-edge: 12 bytes.
  struct HalfedgeConnectivity {
    Vertex to;  ///< target vertex
    /// The face on the left (top bit clear) or, on the boundary, kBoundaryTag
    /// | prev's index (kNoPrev while not linked yet).
    Index face_or_prev = kInvalidIndex;
    Halfedge next;
  };
  static_assert(sizeof(HalfedgeConnectivity) == 12, "HalfedgeConnectivity: 12 bytes a half-edge");
  /// The top bit of HalfedgeConnectivity::face_or_prev: a boundary half-edge.
  static constexpr Index kBoundaryTag = Index{1} << 31;
  /// The prev of a boundary half-edge not linked yet (the low bits all set).
  static constexpr Index kNoPrev = kBoundaryTag - 1;
  /// Connectivity of a face: one of its half-edges.
  struct FaceConnectivity {
    Halfedge halfedge;
  };

  // SurfaceMesh Construction
  /// An empty mesh.
  SurfaceMesh();
  /// Deep copy, properties included. Property handles of `other` stay tied to `other`.
  SurfaceMesh(const SurfaceMesh& other);
  /// Deep copy assignment (see the copy constructor).
  SurfaceMesh& operator=(const SurfaceMesh& other);
  /// Move: property handles of `other` now refer to this mesh's data; `other`
  /// is left an empty mesh with only the built-in properties.
  SurfaceMesh(SurfaceMesh&& other) noexcept;
  /// Move assignment (see the move constructor).
  SurfaceMesh& operator=(SurfaceMesh&& other) noexcept;
  ~SurfaceMesh();
  /// Remove all elements; user properties are kept (empty).
  void clear();
  /// Gives back the memory of every half-edge, edge and face (with their
  /// properties) and keeps the vertices with theirs: for a caller that has
  /// read the faces and still reads vertex properties (the pipeline's output,
  /// which frees the mesh part by part). Afterwards the mesh has no face and
  /// no half-edge, and the vertices' outgoing half-edges are invalid: only
  /// vertices(), positions and vertex properties may be read.
  void release_faces();
  /// Reserve space for about nv vertices and nf faces (edges: nv + nf).
  void reserve(std::size_t nv, std::size_t nf);

  /// Writes the mesh as it is held — every element, deleted ones included,
  /// every property with its default value, in index order — for
  /// read_binary() in another process of the same build: the mesh read back
  /// has the same elements, links and values, so every operation on it does
  /// what it would do on this one. Native byte order. Throws
  /// std::invalid_argument for a property whose type cannot be written
  /// (raw_tag() 0).
  void write_binary(std::ostream& os) const;
  /// The mesh write_binary() wrote. Properties of arithmetic types and Vec3
  /// are made by name; other types only if they are built in. Throws
  /// InputError naming `file` for a stream that is not such a mesh, is
  /// truncated or was written with another byte order.
  static SurfaceMesh read_binary(std::istream& is, const std::string& file);

  /// Build from an IndexedMesh (positions + triangles; normals/atom ignored).
  /// Vertex i of the result is positions[i] (unreferenced vertices become
  /// isolated vertices), face j is triangles[j]. Triangles may come in any order.
  /// Throws TopologyError for a repeated index, an index out of range, a
  /// non-manifold edge, inconsistent orientation or a non-manifold vertex.
  static SurfaceMesh from_indexed_mesh(const IndexedMesh& m);
  /// Non-deleted vertices and faces as an IndexedMesh, in index order
  /// (positions and triangles only; normals and atom are left empty for the
  /// caller). Isolated vertices are kept.
  IndexedMesh to_indexed_mesh() const;
  /// to_indexed_mesh()'s positions and triangles written in place: vertex i
  /// (in index order, deleted ones skipped) to positions[vertex_base + i],
  /// face j to triangles[face_base + j], its vertex indices offset by
  /// vertex_base; for a caller that joins several meshes into one array.
  /// Pre: the spans hold n_vertices() and n_faces() entries from the bases.
  void write_indexed(std::span<Vec3> positions, std::span<std::array<Index, 3>> triangles, std::size_t vertex_base,
                     std::size_t face_base) const;
  /// write_indexed()'s triangles alone (for a caller that writes the
  /// positions later, after release_faces()).
  void write_indexed_triangles(std::span<std::array<Index, 3>> triangles, std::size_t vertex_base,
                               std::size_t face_base) const;

  // SurfaceMesh Counts (deleted elements excluded)
  /// Number of vertices not marked deleted (isolated ones included).
  std::size_t n_vertices() const { return vprops_.size() - deleted_vertices_; }
  /// Number of half-edges not marked deleted (2 x n_edges()).
  std::size_t n_halfedges() const { return hprops_.size() - 2 * deleted_edges_; }
  /// Number of edges not marked deleted.
  std::size_t n_edges() const { return eprops_.size() - deleted_edges_; }
  /// Number of faces not marked deleted.
  std::size_t n_faces() const { return fprops_.size() - deleted_faces_; }
  /// True if some element is marked deleted (garbage_collection() would act).
  bool has_garbage() const { return deleted_vertices_ + deleted_edges_ + deleted_faces_ > 0; }
  /// Array size including deleted vertices (every vertex handle is below it).
  std::size_t vertices_size() const { return vprops_.size(); }
  /// Array size including deleted half-edges.
  std::size_t halfedges_size() const { return hprops_.size(); }
  /// Array size including deleted edges.
  std::size_t edges_size() const { return eprops_.size(); }
  /// Array size including deleted faces.
  std::size_t faces_size() const { return fprops_.size(); }

  // SurfaceMesh Element Creation
  /// Append a vertex at p (Å). It is isolated until a face uses it.
  Vertex add_vertex(const Vec3& p);
  /// Appends a copy of `other`'s vertices, edges and faces, with their
  /// connectivity: its vertex i becomes vertex vertices_size() + i of this
  /// mesh (taken before the call), and likewise for its half-edges, edges
  /// and faces, so its boundary stays boundary here, ready for add_triangle().
  /// Only the built-in properties are copied; the user properties of this
  /// mesh get their initial value on the new elements. O(size of `other`).
  /// Throws std::invalid_argument if `other` has deleted elements (call its
  /// garbage_collection() first) or is this mesh, and std::length_error if
  /// the result would pass 2^31 - 1 half-edges or faces.
  void append(const SurfaceMesh& other);
  /// append(other), with every property of this mesh that `other` also has
  /// (the same name and type) given `other`'s values on the new elements (the
  /// others their initial value), and `other` emptied as it is read: its
  /// arrays go back to the system a chunk at a time once copied, so the two
  /// meshes together never hold much more than the result (the decomposed
  /// sweep's glue, papers/decompose/README.md, "The glue"). Afterwards `other` has no
  /// element; its properties stay. O(size of `other`). Throws as append()
  /// does, before anything changes.
  void append_consuming(SurfaceMesh& other);

  /// Add the triangle (a, b, c), counter-clockwise seen from outside, and return it.
  /// Supported: any of the three edges may be new or an existing boundary
  /// half-edge in the direction a->b, b->c, c->a; each vertex must be isolated or
  /// on the boundary. At a vertex where both triangle edges already exist in
  /// different boundary gaps, the fans between them are moved into another gap
  /// of the vertex (patch re-linking); a vertex where both edges are new and
  /// that already has faces gets the triangle in the gap before halfedge(v),
  /// which may create a pinch (a second gap).
  /// Throws TopologyError (mesh unchanged) for: a repeated or deleted vertex;
  /// a vertex with a closed one-ring; a directed edge that already has a face
  /// on its left (wrong orientation if its twin is boundary, non-manifold edge
  /// if both sides have faces); a triangle that would close one fan of a vertex
  /// into a disk while the vertex has other fans (non-manifold vertex).
  /// Source: the patch re-linking of pmp-library's SurfaceMesh::add_face,
  /// rederived for triangles.
  Face add_triangle(Vertex a, Vertex b, Vertex c);

  // SurfaceMesh Connectivity
  /// Outgoing half-edge of v: a boundary one if v is on the boundary; invalid if v is isolated.
  Halfedge halfedge(Vertex v) const { return vconn_[v].halfedge; }
  /// A half-edge of face f.
  Halfedge halfedge(Face f) const { return fconn_[f].halfedge; }
  /// Half-edge i (0 or 1) of edge e; halfedge(e, 1) = opposite(halfedge(e, 0)).
  Halfedge halfedge(Edge e, unsigned i) const { return Halfedge((e.idx() << 1) + i); }
  /// The edge of h (h >> 1).
  Edge edge(Halfedge h) const { return Edge(h.idx() >> 1); }
  /// The twin of h (h ^ 1).
  Halfedge opposite(Halfedge h) const { return Halfedge(h.idx() ^ 1u); }
  /// Next half-edge in h's face, or along the boundary loop if h is a boundary half-edge.
  Halfedge next(Halfedge h) const { return hconn_[h].next; }
  /// Previous half-edge (inverse of next): next(next(h)) in a face, the
  /// stored link on the boundary.
  Halfedge prev(Halfedge h) const {
    const HalfedgeConnectivity& c = hconn_[h];
    if (c.face_or_prev & kBoundaryTag) {
      const Index p = c.face_or_prev & kNoPrev;
      return p == kNoPrev ? Halfedge() : Halfedge(p);
    }
    return hconn_[c.next].next;
  }
  /// Target vertex of h.
  Vertex to_vertex(Halfedge h) const { return hconn_[h].to; }
  /// Source vertex of h.
  Vertex from_vertex(Halfedge h) const { return hconn_[opposite(h)].to; }
  /// Vertex i (0 or 1) of e: to_vertex(halfedge(e, i)).
  Vertex vertex(Edge e, unsigned i) const { return to_vertex(halfedge(e, i)); }
  /// Face on the left of h; invalid if h is a boundary half-edge.
  Face face(Halfedge h) const {
    const Index f = hconn_[h].face_or_prev;
    return f & kBoundaryTag ? Face() : Face(f);
  }
  /// Face i (0 or 1) of e; invalid on the boundary side.
  Face face(Edge e, unsigned i) const { return face(halfedge(e, i)); }
  /// Next outgoing half-edge around from_vertex(h), counter-clockwise: opposite(prev(h)).
  Halfedge ccw_rotated(Halfedge h) const { return opposite(prev(h)); }

  /// True if h has no face (the hole is on its left).
  bool is_boundary(Halfedge h) const { return (hconn_[h].face_or_prev & kBoundaryTag) != 0; }
  /// True if one of e's half-edges is a boundary half-edge.
  bool is_boundary(Edge e) const { return is_boundary(halfedge(e, 0)) || is_boundary(halfedge(e, 1)); }
  /// True if v is isolated or has an outgoing boundary half-edge.
  bool is_boundary(Vertex v) const {
    Halfedge h = halfedge(v);
    return !h.is_valid() || is_boundary(h);
  }
  /// True if one of f's edges is a boundary edge.
  bool is_boundary(Face f) const;
  /// True if v has no half-edge.
  bool is_isolated(Vertex v) const { return !halfedge(v).is_valid(); }
  /// True if v is isolated, interior (one closed fan) or has exactly one boundary gap.
  bool is_manifold(Vertex v) const;
  /// Number of edges at v (outgoing half-edges).
  std::size_t valence(Vertex v) const;
  /// Number of boundary gaps at v (0 interior, 1 regular boundary, >1 pinch).
  std::size_t boundary_gaps(Vertex v) const;
  /// The half-edge from a to b, or invalid if there is none.
  Halfedge find_halfedge(Vertex a, Vertex b) const;
  /// The edge between a and b, or invalid.
  Edge find_edge(Vertex a, Vertex b) const;
  /// The boundary loop through boundary half-edge h, in next() order (starting at h).
  /// Pre: is_boundary(h).
  std::vector<Halfedge> boundary_loop(Halfedge h) const;
  /// All boundary loops, each in next() order, each starting at its lowest half-edge.
  std::vector<std::vector<Halfedge>> boundary_loops() const;

  // SurfaceMesh Deletion Flags
  /// True if v is marked deleted (until garbage_collection()). Pre: v in range.
  bool is_deleted(Vertex v) const { return vdeleted_[v]; }
  /// True if h's edge is marked deleted. Pre: h in range.
  bool is_deleted(Halfedge h) const { return edeleted_[edge(h)]; }
  /// True if e is marked deleted. Pre: e in range.
  bool is_deleted(Edge e) const { return edeleted_[e]; }
  /// True if f is marked deleted. Pre: f in range.
  bool is_deleted(Face f) const { return fdeleted_[f]; }
  /// True if v is in range and not deleted (any handle may be passed).
  bool is_valid(Vertex v) const { return v.idx() < vertices_size() && !is_deleted(v); }
  /// True if h is in range and not deleted.
  bool is_valid(Halfedge h) const { return h.idx() < halfedges_size() && !is_deleted(h); }
  /// True if e is in range and not deleted.
  bool is_valid(Edge e) const { return e.idx() < edges_size() && !is_deleted(e); }
  /// True if f is in range and not deleted.
  bool is_valid(Face f) const { return f.idx() < faces_size() && !is_deleted(f); }

  // SurfaceMesh Positions
  /// Position of v (Å). Pre: v in range.
  const Vec3& position(Vertex v) const { return vpoint_[v]; }
  /// Position of v (Å), writable (moving a vertex changes no connectivity).
  Vec3& position(Vertex v) { return vpoint_[v]; }
  /// The position property "v:point".
  VertexProperty<Vec3>& positions() { return vpoint_; }
  const VertexProperty<Vec3>& positions() const { return vpoint_; }

  // SurfaceMesh Iteration
  /// Non-deleted vertices in index order. Adding elements while iterating is
  /// allowed (the range ends at the size it had when it was made).
  HandleRange<Vertex> vertices() const { return {this, Index(vertices_size())}; }
  /// Non-deleted half-edges in index order.
  HandleRange<Halfedge> halfedges() const { return {this, Index(halfedges_size())}; }
  /// Non-deleted edges in index order.
  HandleRange<Edge> edges() const { return {this, Index(edges_size())}; }
  /// Non-deleted faces in index order.
  HandleRange<Face> faces() const { return {this, Index(faces_size())}; }
  /// Outgoing half-edges of v, counter-clockwise, starting at halfedge(v); empty if isolated.
  Circulator<CirculatorKind::kVertexOutgoing> halfedges(Vertex v) const { return {this, halfedge(v)}; }
  /// One-ring vertices of v, counter-clockwise, starting at to_vertex(halfedge(v)).
  Circulator<CirculatorKind::kVertexVertices> vertices(Vertex v) const { return {this, halfedge(v)}; }
  /// Faces around v, counter-clockwise (boundary gaps skipped).
  Circulator<CirculatorKind::kVertexFaces> faces(Vertex v) const { return {this, halfedge(v)}; }
  /// The three half-edges of f, starting at halfedge(f).
  Circulator<CirculatorKind::kFaceHalfedges> halfedges(Face f) const { return {this, halfedge(f)}; }
  /// The half-edges of the face or boundary loop through h, along next(), starting at h.
  Circulator<CirculatorKind::kFaceHalfedges> loop(Halfedge h) const { return {this, h}; }
  /// The three vertices of f, counter-clockwise, starting at to_vertex(halfedge(f)).
  Circulator<CirculatorKind::kFaceVertices> vertices(Face f) const { return {this, halfedge(f)}; }

  // SurfaceMesh Properties
  // The stages share per-vertex data through named vertex properties; each
  // name is declared once with its type as a VertexPropertyKey (the skin's:
  // skin/vertex_data.h), and the key overloads below are how code outside the
  // mesh names them. The half-edge, edge and face properties are the mesh's
  // own (connectivity, deletion flags).

  /// Add a vertex property named `name` with default value `init` for existing
  /// and new elements. Throws std::invalid_argument if the name is taken for
  /// vertices.
  template <class T>
  VertexProperty<T> add_vertex_property(const std::string& name, T init = T()) {
    return VertexProperty<T>(add_property<T>(vprops_, name, std::move(init)));
  }
  /// The vertex property `name` of type T, or an invalid property if there is
  /// none of that name and type. Likewise for the other kinds below.
  template <class T>
  VertexProperty<T> get_vertex_property(const std::string& name) const {
    return VertexProperty<T>(vprops_.get<T>(name));
  }
  /// The property `name` if it exists with type T, else a new one with default `init`.
  /// Throws std::invalid_argument if the name exists with another type.
  template <class T>
  VertexProperty<T> vertex_property(const std::string& name, T init = T()) {
    auto p = get_vertex_property<T>(name);
    return p ? p : add_vertex_property<T>(name, std::move(init));
  }
  /// add_vertex_property / get_vertex_property / vertex_property /
  /// has_vertex_property of the property that `key` names, with its type.
  template <class T>
  VertexProperty<T> add_vertex_property(VertexPropertyKey<T> key, std::type_identity_t<T> init = T()) {
    return add_vertex_property<T>(key.name, std::move(init));
  }
  template <class T>
  VertexProperty<T> get_vertex_property(VertexPropertyKey<T> key) const {
    return get_vertex_property<T>(key.name);
  }
  template <class T>
  VertexProperty<T> vertex_property(VertexPropertyKey<T> key, std::type_identity_t<T> init = T()) {
    return vertex_property<T>(key.name, std::move(init));
  }
  template <class T>
  bool has_vertex_property(VertexPropertyKey<T> key) const {
    return get_vertex_property<T>(key.name).is_valid();
  }
  /// True if a vertex property of that name exists (any type).
  bool has_vertex_property(const std::string& name) const { return vprops_.find(name) != nullptr; }
  /// Remove a property and invalidate the handle. Built-in properties ("v:point",
  /// "v:connectivity", ...) cannot be removed: std::invalid_argument.
  template <class T>
  void remove_vertex_property(VertexProperty<T>& p) {
    remove_property(vprops_, p.array_);
    p.array_ = nullptr;
  }

  // SurfaceMesh Refinement Operations (check first, then modify)
  /// True if the interior edge e = (a, b) with faces (a, b, c) and (b, a, d) can
  /// be replaced by (c, d): e is not deleted and not on the boundary, c != d and
  /// c, d are not already adjacent.
  bool is_flip_ok(Edge e) const;
  /// Flip e: faces (a,b,c), (b,a,d) become (a,d,c), (b,c,d); afterwards
  /// to_vertex(halfedge(e,0)) = c and to_vertex(halfedge(e,1)) = d. Counts do
  /// not change. Throws TopologyError (mesh unchanged) if !is_flip_ok(e).
  void flip(Edge e);

  /// True if h = (v0 -> v1) can be collapsed (v0 removed, v1 kept). Supported:
  /// interior edges and boundary edges, with v0 and v1 manifold. Refused: a face
  /// at h or at its twin whose two other edges are both boundary edges (the
  /// triangle would become a dangling edge); an interior edge between two
  /// boundary vertices; a vertex w adjacent to both v0 and v1 other than the
  /// apexes of h's faces (link condition: w would get a doubled edge, or a
  /// boundary loop of three edges would close); an apex that is interior with
  /// valence 3 (its two faces would coincide); a pinched v0 or v1.
  /// Source: link condition (Dey et al. 1999), as in pmp's is_collapse_ok.
  bool is_collapse_ok(Halfedge h) const;
  /// Collapse h: v0 = from_vertex(h) is deleted and its edges move to
  /// v1 = to_vertex(h), which keeps its position; the face(s) of h are deleted and
  /// at each of them the edge (v0, apex) is deleted, (v1, apex) kept. Removes
  /// 1 vertex, 3 edges, 2 faces for an interior edge (1 / 2 / 1 on the boundary),
  /// so the Euler characteristic is kept. Throws TopologyError (mesh unchanged)
  /// if !is_collapse_ok(h).
  void collapse(Halfedge h);

  /// Insert a vertex at p (Å) inside f and connect it to f's corners (1 -> 3
  /// faces; f is reused as one of them). Returns the new vertex (valence 3).
  Vertex split_face(Face f, const Vec3& p);
  /// Insert a vertex at p (Å) on e, connected to the apex of each face of e:
  /// interior edge 2 -> 4 faces, boundary edge 1 -> 2 faces. halfedge(e, 0)
  /// keeps its source vertex and now ends at the new vertex. Returns the new
  /// vertex (valence 4 inside, 3 on the boundary).
  Vertex split_edge(Edge e, const Vec3& p);

  /// Mark f deleted; its edges that lose their last face and its vertices that
  /// lose their last edge are deleted too. Boundary loops are re-linked (a new
  /// hole, or an enlarged one; a corner may become a pinch).
  void delete_face(Face f);
  /// Delete all faces around v, then v itself.
  void delete_vertex(Vertex v);
  /// Remove deleted elements and compact every property (user ones too);
  /// handles taken before become meaningless, property handles stay valid.
  void garbage_collection();

  // SurfaceMesh Debugging
  /// Check every invariant of the structure and throw std::logic_error naming the
  /// first broken one: property sizes, opposite/next/prev symmetry, face cycles
  /// of length 3 with one face, closed boundary loops, vertex half-edges valid
  /// and boundary-preferring, circulation visiting every outgoing half-edge, no
  /// duplicate edges, no edge without faces, no reference to a deleted element,
  /// deletion counters. O(n log n).
  void check_consistency() const;

 private:
  template <class T>
  static detail::PropertyArray<T>* add_property(detail::PropertyContainer& c, const std::string& name, T init);
  static void remove_property(detail::PropertyContainer& c, const detail::BasePropertyArray* p);
  void bind_builtin_properties();
  void require_valid(Vertex v, const char* where) const;
  void require_valid(Face f, const char* where) const;
  void require_valid(Edge e, const char* where) const;
  void require_valid(Halfedge h, const char* where) const;

  /// Throws std::length_error if this mesh and `other` together would pass
  /// the limit of 2^31 - 1 half-edges or faces (nothing changed).
  void require_room_for(const SurfaceMesh& other) const;
  Halfedge new_edge(Vertex a, Vertex b);  // returns the half-edge a -> b
  Face new_face();
  // The links are set face first: set_next(h, n) records h as n's prev only
  // if n is on the boundary then (inside a face prev is derived), so a
  // half-edge that becomes boundary gets its face cleared (set_boundary)
  // before, or with, its prev.
  void set_next(Halfedge h, Halfedge n) {
    hconn_[h].next = n;
    Index& fp = hconn_[n].face_or_prev;
    if (fp & kBoundaryTag) fp = kBoundaryTag | h.idx();
  }
  void set_vertex(Halfedge h, Vertex v) { hconn_[h].to = v; }
  /// h gets face f (valid).
  void set_face(Halfedge h, Face f) { hconn_[h].face_or_prev = f.idx(); }
  /// h becomes a boundary half-edge whose prev is p (invalid: set later by set_next).
  void set_boundary(Halfedge h, Halfedge p = Halfedge()) {
    hconn_[h].face_or_prev = kBoundaryTag | (p.is_valid() ? p.idx() : kNoPrev);
  }
  void set_halfedge(Vertex v, Halfedge h) { vconn_[v].halfedge = h; }
  void set_halfedge(Face f, Halfedge h) { fconn_[f].halfedge = h; }
  /// Make halfedge(v) a boundary half-edge if v has one (v not isolated).
  void adjust_outgoing_halfedge(Vertex v);
  /// Incoming boundary half-edge where the fans of v are continued after the
  /// fan that starts at outgoing half-edge `from` (walking clockwise), or invalid
  /// if the walk reaches `stop` first.
  Halfedge find_gap_after(Halfedge from, Halfedge stop) const;

  // SurfaceMesh Private Members
  detail::PropertyContainer vprops_, hprops_, eprops_, fprops_;
  VertexProperty<VertexConnectivity> vconn_;
  HalfedgeProperty<HalfedgeConnectivity> hconn_;
  FaceProperty<FaceConnectivity> fconn_;
  VertexProperty<Vec3> vpoint_;
  VertexProperty<bool> vdeleted_;
  EdgeProperty<bool> edeleted_;
  FaceProperty<bool> fdeleted_;
  std::size_t deleted_vertices_ = 0, deleted_edges_ = 0, deleted_faces_ = 0;
};

// ---------------------------------------------------------------------------
// Inline definitions
// ---------------------------------------------------------------------------

template <class T>
detail::PropertyArray<T>* SurfaceMesh::add_property(detail::PropertyContainer& c, const std::string& name, T init) {
  if (c.find(name) != nullptr)
    throw std::invalid_argument("SurfaceMesh: a property named '" + name + "' exists already");
  return c.add<T>(name, std::move(init));
}

template <class H>
void HandleRange<H>::Iterator::skip() {
  while (i_ < n_ && mesh_->is_deleted(H(i_))) ++i_;
}

template <CirculatorKind K>
typename Circulator<K>::value_type Circulator<K>::Iterator::operator*() const {
  if constexpr (K == CirculatorKind::kVertexOutgoing || K == CirculatorKind::kFaceHalfedges)
    return h_;
  else if constexpr (K == CirculatorKind::kVertexVertices || K == CirculatorKind::kFaceVertices)
    return mesh_->to_vertex(h_);
  else
    return mesh_->face(h_);
}

template <CirculatorKind K>
bool Circulator<K>::Iterator::accept() const {
  if constexpr (K == CirculatorKind::kVertexFaces)
    return mesh_->face(h_).is_valid();
  else
    return true;
}

template <CirculatorKind K>
void Circulator<K>::Iterator::advance() {
  do {
    if constexpr (K == CirculatorKind::kFaceHalfedges || K == CirculatorKind::kFaceVertices)
      h_ = mesh_->next(h_);
    else
      h_ = mesh_->ccw_rotated(h_);
    if (h_ == start_) ++lap_;
  } while (lap_ == 0 && !accept());
}

}  // namespace skinmesh::geometry

/// Hash of handles, for unordered containers.
template <>
struct std::hash<skinmesh::geometry::Vertex> {
  std::size_t operator()(skinmesh::geometry::Vertex h) const noexcept { return h.idx(); }
};
template <>
struct std::hash<skinmesh::geometry::Halfedge> {
  std::size_t operator()(skinmesh::geometry::Halfedge h) const noexcept { return h.idx(); }
};
template <>
struct std::hash<skinmesh::geometry::Edge> {
  std::size_t operator()(skinmesh::geometry::Edge h) const noexcept { return h.idx(); }
};
template <>
struct std::hash<skinmesh::geometry::Face> {
  std::size_t operator()(skinmesh::geometry::Face h) const noexcept { return h.idx(); }
};
