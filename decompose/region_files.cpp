// decompose/region_files.cpp: the cut and region files (decompose/region_files.h).
// Each file: an 8-byte marker, a byte-order value, a format version, the
// run's fingerprint, then its values as their bytes. Files are written to a
// temporary name and renamed, so a reader never sees half a file and a
// failed write leaves nothing.
// Notes: papers/decompose/README.md ("One structure over several processes")
#include "decompose/region_files.h"

#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <type_traits>

#include "core/binary_io.h"
#include "core/errors.h"

namespace skinmesh::decompose {

namespace {

constexpr char kCutsMagic[8] = {'s', 'k', 'm', 'e', 's', 'h', 'C', '1'};
constexpr char kRegionMagic[8] = {'s', 'k', 'm', 'e', 's', 'h', 'R', '1'};
constexpr std::uint32_t kByteOrder = 0x01020304;
/// Raised whenever a layout below changes: a reader refuses other versions.
constexpr std::uint32_t kVersion = 1;

static_assert(std::is_trivially_copyable_v<front::SweepStats>, "SweepStats is written as its bytes");
static_assert(std::is_trivially_copyable_v<refine::RefineStats>, "RefineStats is written as its bytes");

void put_header(std::ostream& os, const char (&magic)[8], std::uint64_t fingerprint) {
  os.write(magic, sizeof magic);
  put_raw(os, kByteOrder);
  put_raw(os, kVersion);
  put_raw(os, fingerprint);
}

std::uint64_t get_header(std::istream& is, const char (&magic)[8], const char* what, const std::string& path) {
  char m[8];
  get_bytes(is, m, sizeof m, path);
  if (!std::equal(m, m + 8, magic)) throw InputError(path, 0, std::string("not a skinmesh ") + what + " file");
  if (get_raw<std::uint32_t>(is, path) != kByteOrder)
    throw InputError(path, 0, "written on a machine of the other byte order");
  if (const auto v = get_raw<std::uint32_t>(is, path); v != kVersion)
    throw InputError(path, 0,
                     "written by another version of skinmesh (format " + std::to_string(v) + ", this one reads " +
                         std::to_string(kVersion) + ")");
  return get_raw<std::uint64_t>(is, path);
}

void put_curve(std::ostream& os, const morse::LevelCurve& c) {
  put_vector(os, c.points);
  put_vector(os, c.rho);
  put_vector(os, c.cells);
  put_vector(os, c.detour);
  put_vector(os, c.ball);
  put_raw(os, c.length);
}

morse::LevelCurve get_curve(std::istream& is, const std::string& path) {
  morse::LevelCurve c;
  c.points = get_vector<Vec3>(is, path);
  c.rho = get_vector<double>(is, path);
  c.cells = get_vector<Index>(is, path);
  c.detour = get_vector<Index>(is, path);
  c.ball = get_vector<Index>(is, path);
  c.length = get_raw<double>(is, path);
  const std::size_t n = c.points.size();
  if (c.rho.size() != n || c.cells.size() != n || (!c.detour.empty() && c.detour.size() != n) ||
      c.ball.size() != c.detour.size())
    throw InputError(path, 0, "a cut curve's arrays differ in length (a damaged file)");
  return c;
}

void put_loops(std::ostream& os, const std::vector<std::vector<Index>>& loops) {
  put_raw<std::uint64_t>(os, loops.size());
  for (const std::vector<Index>& l : loops) put_vector(os, l);
}

std::vector<std::vector<Index>> get_loops(std::istream& is, const std::string& path) {
  std::vector<std::vector<Index>> loops(get_count(is, path, std::uint64_t{1} << 32));
  for (std::vector<Index>& l : loops) l = get_vector<Index>(is, path);
  return loops;
}

/// Writes through `write` to a temporary file beside `path`, renamed to
/// `path` once complete.
template <class Write>
void write_atomically(const std::string& path, Write&& write) {
  const std::string tmp = path + ".part";
  {
    std::ofstream os(tmp, std::ios::binary | std::ios::trunc);
    if (!os) throw std::runtime_error(path + ": cannot be written");
    write(os);
    os.flush();
    if (!os) {
      os.close();
      std::remove(tmp.c_str());
      throw std::runtime_error(path + ": the write failed (disk full?)");
    }
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    std::remove(tmp.c_str());
    throw std::runtime_error(path + ": cannot be written (rename failed)");
  }
}

std::ifstream open_for_reading(const std::string& path) {
  std::ifstream is(path, std::ios::binary);
  if (!is) throw InputError(path, 0, "cannot be opened");
  return is;
}

/// After the last value: nothing may follow.
void require_end(std::istream& is, const std::string& path) {
  if (is.peek() != std::char_traits<char>::eof())
    throw InputError(path, 0, "bytes follow the last value (a damaged file)");
}

}  // namespace

void write_cuts(const std::string& path, const CutsFile& file) {
  write_atomically(path, [&](std::ostream& os) {
    put_header(os, kCutsMagic, file.fingerprint);
    put_raw<std::uint64_t>(os, file.cuts.size());
    for (const Cut& cut : file.cuts) {
      put_raw(os, cut.height);
      put_raw<std::uint8_t>(os, cut.detoured ? 1 : 0);
      put_raw<std::uint64_t>(os, cut.curves.size());
      for (const morse::LevelCurve& c : cut.curves) put_curve(os, c);
      put_raw<std::uint64_t>(os, cut.detours.size());
      for (const morse::CutDetour& d : cut.detours) {
        put_raw<std::uint8_t>(os, d.upper ? 1 : 0);
        put_raw<std::uint64_t>(os, d.balls.size());
        for (const morse::DetourBall& b : d.balls) {
          put_raw(os, b.center.x()), put_raw(os, b.center.y()), put_raw(os, b.center.z());
          put_raw(os, b.radius);
          put_raw(os, b.critical);
        }
      }
    }
  });
}

CutsFile read_cuts(const std::string& path) {
  std::ifstream is = open_for_reading(path);
  CutsFile file;
  file.fingerprint = get_header(is, kCutsMagic, "cuts", path);
  file.cuts.resize(get_count(is, path, std::uint64_t{1} << 24));
  for (Cut& cut : file.cuts) {
    cut.height = get_raw<double>(is, path);
    cut.detoured = get_raw<std::uint8_t>(is, path) != 0;
    cut.curves.resize(get_count(is, path, std::uint64_t{1} << 32));
    for (morse::LevelCurve& c : cut.curves) c = get_curve(is, path);
    cut.detours.resize(get_count(is, path, std::uint64_t{1} << 32));
    for (morse::CutDetour& d : cut.detours) {
      d.upper = get_raw<std::uint8_t>(is, path) != 0;
      d.balls.resize(get_count(is, path, std::uint64_t{1} << 32));
      for (morse::DetourBall& b : d.balls) {
        const double x = get_raw<double>(is, path), y = get_raw<double>(is, path), z = get_raw<double>(is, path);
        b.center = Vec3(x, y, z);
        b.radius = get_raw<double>(is, path);
        b.critical = get_raw<Index>(is, path);
      }
    }
  }
  for (std::size_t c = 1; c < file.cuts.size(); ++c)
    if (!(file.cuts[c - 1].height < file.cuts[c].height))
      throw InputError(path, 0, "the cuts' heights do not increase (a damaged file)");
  require_end(is, path);
  return file;
}

void write_region(const std::string& path, const RegionFile& file) {
  write_atomically(path, [&](std::ostream& os) {
    put_header(os, kRegionMagic, file.fingerprint);
    put_raw<std::uint64_t>(os, file.slab.first);
    put_raw<std::uint64_t>(os, file.slab.second);
    const SlabOutcome& o = file.outcome;
    put_string(os, o.error);
    put_raw<std::uint8_t>(os, o.at_lower_cut ? 1 : 0);
    put_raw(os, o.seconds);
    put_raw(os, o.refinement);
    put_raw<std::uint8_t>(os, o.refined ? 1 : 0);
    put_raw<std::uint8_t>(os, o.result ? 1 : 0);
    if (!o.result) return;
    const front::RegionResult& r = *o.result;
    r.mesh.write_binary(os);
    put_raw(os, r.stats);
    put_loops(os, r.lower_loops);
    put_loops(os, r.upper_rims);
    put_vector(os, r.rim_curve);
    put_raw<std::uint64_t>(os, r.parked);
  });
}

RegionFile read_region(const std::string& path) {
  std::ifstream is = open_for_reading(path);
  RegionFile file;
  file.fingerprint = get_header(is, kRegionMagic, "region", path);
  file.slab.first = get_raw<std::uint64_t>(is, path);
  file.slab.second = get_raw<std::uint64_t>(is, path);
  SlabOutcome& o = file.outcome;
  o.error = get_string(is, path);
  o.at_lower_cut = get_raw<std::uint8_t>(is, path) != 0;
  o.seconds = get_raw<double>(is, path);
  o.refinement = get_raw<refine::RefineStats>(is, path);
  o.refined = get_raw<std::uint8_t>(is, path) != 0;
  if (get_raw<std::uint8_t>(is, path) != 0) {
    front::RegionResult& r = o.result.emplace();
    r.mesh = geometry::SurfaceMesh::read_binary(is, path);
    r.stats = get_raw<front::SweepStats>(is, path);
    r.lower_loops = get_loops(is, path);
    r.upper_rims = get_loops(is, path);
    r.rim_curve = get_vector<std::size_t>(is, path);
    r.parked = static_cast<std::size_t>(get_raw<std::uint64_t>(is, path));
    for (const std::vector<std::vector<Index>>* loops : {&r.lower_loops, &r.upper_rims})
      for (const std::vector<Index>& l : *loops)
        for (Index v : l)
          if (v >= r.mesh.vertices_size()) throw InputError(path, 0, "a loop names a vertex the mesh lacks");
  } else if (o.error.empty()) {
    throw InputError(path, 0, "a slab with neither a mesh nor a failure (a damaged file)");
  }
  require_end(is, path);
  return file;
}

}  // namespace skinmesh::decompose
