// Tests of core/growable_array.h: the values survive every kind of growth
// (realloc below 64 KiB, the move into mapped pages, mremap beyond), copies and
// moves are deep and independent, and the capacity of a mapped block stays
// within an eighth of the size while it grows.
#include "core/growable_array.h"

#include <doctest/doctest.h>

#include <cstdint>
#include <span>
#include <vector>

#include "core/types.h"

using skinmesh::GrowableArray;
using skinmesh::Vec3;

namespace {

Vec3 value(std::size_t i) { return Vec3(double(i), 0.5 * double(i), -double(i) - 0.25); }

}  // namespace

TEST_CASE("growable_array: push_back through realloc, mmap and mremap keeps every value") {
  GrowableArray<Vec3> a;
  std::vector<Vec3> ref;
  // 24-byte values: 64 KiB is 2,731 of them; 200,000 crosses it and grows
  // by mremap many times after.
  for (std::size_t i = 0; i < 200000; ++i) {
    a.push_back(value(i));
    ref.push_back(value(i));
    CHECK(a.capacity() >= a.size());
    // Mapped (from 2,731 values on) the capacity grows by an eighth; below, or
    // without mapped blocks (AddressSanitizer, not Linux), it doubles.
    if (SKINMESH_GROWABLE_ARRAY_MMAP && a.size() > 8192) CHECK(double(a.capacity()) <= 1.126 * double(a.size()) + 16);
  }
  REQUIRE(a.size() == ref.size());
  bool same = true;
  for (std::size_t i = 0; i < ref.size(); ++i) same = same && a[i] == ref[i];
  CHECK(same);
  const std::span<const Vec3> s = a;
  CHECK(s.size() == ref.size());
  CHECK(s.back() == ref.back());
}

TEST_CASE("growable_array: push_back of its own element while growing") {
  GrowableArray<std::uint32_t> a;
  a.push_back(7);
  for (int i = 0; i < 300000; ++i) a.push_back(a[0]);  // a growth must read the value before moving the block
  bool all7 = true;
  for (std::uint32_t v : a) all7 = all7 && v == 7;
  CHECK(all7);
  CHECK(a.size() == 300001);
}

TEST_CASE("growable_array: resize, reserve, shrink, copy and move") {
  GrowableArray<double> a;
  a.resize(5000, 1.5);  // 40 kB: below the mapping size
  CHECK(a.size() == 5000);
  CHECK(a[4999] == 1.5);
  a.resize(300000, -2.0);  // 2.4 MB: moved into mapped pages with a copy
  CHECK(a[4999] == 1.5);
  CHECK(a[5000] == -2.0);
  CHECK(a[299999] == -2.0);
  a.reserve(1000000);
  CHECK(a.capacity() == 1000000);
  CHECK(a[0] == 1.5);
  GrowableArray<double> b = a;  // deep copy
  b[0] = 3.0;
  CHECK(a[0] == 1.5);
  CHECK(b.size() == a.size());
  a.resize(10);
  a.shrink_to_fit();  // from mapped pages back to malloc
  CHECK(a.capacity() == 10);
  CHECK(a[9] == 1.5);
  GrowableArray<double> c = std::move(b);
  CHECK(b.empty());
  CHECK(c.size() == 300000);
  CHECK(c[0] == 3.0);
  CHECK(c[200000] == -2.0);
  c = a;  // copy-assign over a mapped block
  CHECK(c.size() == 10);
  CHECK(c[5] == 1.5);
  c.resize(0);
  c.shrink_to_fit();
  CHECK(c.capacity() == 0);
  c.push_back(4.0);
  CHECK(c[0] == 4.0);
}

TEST_CASE("growable_array: discard_front gives back the front's pages and keeps the rest") {
  GrowableArray<Vec3> a;
  for (std::size_t i = 0; i < 100000; ++i) a.push_back(value(i));  // 2.4 MB: mapped on Linux
  const std::size_t n = 60000;
  a.discard_front(n);
  CHECK(a.size() == 100000);
  bool kept = true;
  for (std::size_t i = n; i < a.size(); ++i) kept = kept && a[i] == value(i);
  CHECK(kept);
  // A page given back to the system reads as zero bytes when touched again:
  // value(0) is not zero in its last two coordinates, so element 0 tells.
  if (SKINMESH_GROWABLE_ARRAY_MMAP)
    CHECK(a[0] == Vec3::Zero());
  else
    CHECK(a[0] == value(0));
  // Pages are whole: the element just below n may share a page with n's and stay.
  a.push_back(value(100000));
  CHECK(a[100000] == value(100000));

  GrowableArray<double> small;  // 8 kB: malloc'd, where discard_front does nothing
  for (int i = 0; i < 1000; ++i) small.push_back(i + 0.5);
  small.discard_front(1000);
  CHECK(small[0] == 0.5);
  CHECK(small[999] == 999.5);
}
