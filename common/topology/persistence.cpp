#include "common/topology/persistence.hpp"

#include <algorithm>
#include <bit>
#include <cassert>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <span>
#include <stdexcept>
#include <type_traits>
#include <utility>
#include <vector>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif
#if defined(__linux__)
#include <sys/mman.h>
#endif

#include "common/topology/huge_pages.hpp"

namespace fnet {
namespace {

// One sweep over the edges in filtration order does everything: union-find for PD0, the
// triangles each edge closes (found among the neighbours its endpoints have so far, which are
// exactly their neighbours through stronger edges), and their boundary columns reduced on the
// spot. Each diagram point is recorded at its birth edge, so reading the edges out in order
// gives the canonical order without sorting.
//
// Per edge the work is small and its branches are coin flips on the data (is this vertex new,
// does it close a triangle, which root is deeper), so the hot path avoids them: selects by
// mask, unconditional writes, loops of fixed length. One stays, merge or cycle: each side skips
// half the work (measured to pay). On frames larger than the cache the sweep is bound by memory
// latency instead, hence one cache line per vertex and prefetches two steps ahead.

using Index = std::uint32_t;
constexpr Index kNone = std::numeric_limits<Index>::max();
constexpr double kNotABirth = std::numeric_limits<double>::infinity();  // never kept: no birth > it

constexpr std::uint8_t kInline = 6;
constexpr std::uint8_t kSpilled = kInline + 1;

struct Neighbour {
  Index vertex, edge;
};

// Branch-free selection: compilers turn `c ? a : b` on unpredictable data into jumps more often
// than not (even when told it is a coin flip); masks they leave alone.
inline Index pick(bool c, Index if_true, Index if_false) { return if_false ^ ((if_false ^ if_true) & (Index{0} - c)); }

inline double pick(bool c, double if_true, double if_false) {
  const auto t = std::bit_cast<std::uint64_t>(if_true), f = std::bit_cast<std::uint64_t>(if_false);
  return std::bit_cast<double>(f ^ ((f ^ t) & (std::uint64_t{0} - c)));
}

// (min, max) without a jump.
inline std::pair<Index, Index> ordered(Index a, Index b) {
  const Index low = pick(a < b, a, b);
  return {low, a ^ b ^ low};
}

// Everything the sweep keeps about a vertex, in one cache line.
struct alignas(64) Vertex {
  Index nbr[kInline];  // neighbours through earlier edges...
  Index via[kInline];  // ...and the positions of those edges
  Index parent;        // union-find
  Index birth;         // a root's: position of the edge its component was born with
  Index spill;         // its list in Workspace::spill once it has more than kInline neighbours
  std::uint8_t count;  // neighbours held inline, or kSpilled
  std::uint8_t rank;
};
static_assert(sizeof(Vertex) == 64);

// Every vertex's full neighbour list sorted by neighbour: used only when two long lists meet
// (a vertex of high degree, never seen in a physical packing), built on first need.
struct SortedAdjacency {
  std::vector<Index> start;
  std::vector<Neighbour> list;

  explicit SortedAdjacency(const ForceNetwork& net) : start(net.vertex_count + 1, 0), list(2 * net.edges.size()) {
    for (const Edge& e : net.edges) ++start[e.u + 1], ++start[e.v + 1];
    for (std::size_t v = 0; v < net.vertex_count; ++v) start[v + 1] += start[v];
    std::vector<Index> fill(start.begin(), start.end() - 1);
    for (Index k = 0; k < net.edges.size(); ++k) {
      const Edge& e = net.edges[k];
      list[fill[e.u]++] = {e.v, k};
      list[fill[e.v]++] = {e.u, k};
    }
    for (std::size_t v = 0; v < net.vertex_count; ++v)
      std::sort(list.begin() + start[v], list.begin() + start[v + 1],
                [](const Neighbour& a, const Neighbour& b) { return a.vertex < b.vertex; });
  }

  // Filtration position of edge (v, w), or kNone.
  Index find_edge(Index v, Index w) const {
    const auto first = list.begin() + start[v], last = list.begin() + start[v + 1];
    const auto it = std::partition_point(first, last, [w](const Neighbour& n) { return n.vertex < w; });
    return it != last && it->vertex == w ? it->edge : kNone;
  }
};

// Uninitialized storage kept between calls. It is reallocated when too small, and also when
// more than four times too large, so that one huge frame does not pin its memory for good.
template <class T>
class Buffer {
 public:
  T* get(std::size_t n) {
    if (n > capacity_ || 4 * n < capacity_) {
      data_.reset();
      data_ = std::make_unique_for_overwrite<T[]>(n);
      capacity_ = n;
      prefer_huge_pages(data_.get(), n * sizeof(T));
    }
    return data_.get();
  }

  // Room for n, keeping the first `used` entries.
  T* grow(std::size_t n, std::size_t used) {
    auto bigger = std::make_unique_for_overwrite<T[]>(n);
    prefer_huge_pages(bigger.get(), n * sizeof(T));
    std::copy(data_.get(), data_.get() + used, bigger.get());
    data_ = std::move(bigger);
    capacity_ = n;
    return data_.get();
  }

  std::size_t capacity() const { return capacity_; }

 private:
  std::unique_ptr<T[]> data_;
  std::size_t capacity_ = 0;
};

// Kept by each thread between calls: a service analyses frame after frame of similar size, and
// fresh memory costs a page fault per page on every call.
struct Workspace {
  Buffer<Vertex> vertices;
  Buffer<Index> link;                  // per edge: the column in the pool that owns it as a pivot
  Buffer<double> death;                // per edge: death of the class born there, or kNotABirth; + a spare
  Buffer<std::uint8_t> loop;           // per edge: it closes a cycle
  Buffer<PersistencePoint> points[2];  // PD0 and PD1 before they are copied out
  Buffer<Index> killer;                // pairs only, per edge: where its class dies; + a spare
  Buffer<Index> third;                 // pairs only, per edge: the far vertex of the killing triangle
  Buffer<Index> pool;                  // reduced columns: size, then sorted edge positions
  std::vector<std::vector<Neighbour>> spill;
  std::vector<std::pair<Index, Index>> closing;
  std::vector<Neighbour> list_a, list_b;
  std::vector<Index> column[2];
};

// kPairs: also record which simplex kills each class (compute_persistence_pairs); without it the
// code is the diagrams-only sweep, unchanged.
template <bool kPairs>
class Sweep {
 public:
  using Result = std::conditional_t<kPairs, PairedDiagrams, FrameDiagrams>;

  Sweep(const ForceNetwork& net, Workspace& ws)
      : net_(net),
        edges_(net.edges.data()),
        m_(static_cast<Index>(net.edges.size())),
        vertex_(ws.vertices.get(net.vertex_count)),
        link_(ws.link.get(net.edges.size())),
        death_(ws.death.get(net.edges.size() + 1)),
        loop_(ws.loop.get(net.edges.size())),
        pool_(ws.pool.get(4 * net.edges.size() + 64)),
        ws_(ws) {
    if (net.edges.size() >= kNone / 8) throw std::length_error("compute_persistence: too many edges");
    ws.spill.clear();
    if constexpr (kPairs) {
      killer_ = ws.killer.get(net.edges.size() + 1);
      third_ = ws.third.get(net.edges.size());
    }
  }

  Result run() {
    for (Index v = 0; v < net_.vertex_count; ++v) vertex_[v] = Vertex{{}, {}, v, kNone, 0, 0, 0};
    sweep();
    if constexpr (kPairs) {
      return paired_diagrams();
    } else {
      return diagrams();
    }
  }

 private:
  // The hot loop keeps its counters in locals (registers) and leaves the rare paths (a vertex
  // of degree > kInline, a second triangle on the same edge) to out-of-line members.
  void sweep() {
    Vertex* const vertex = vertex_;
    const Edge* const edges = edges_;
    double* const death = death_;
    Index* const link = link_;
    std::uint8_t* const loop = loop_;
    std::size_t touched = 0, births = 0, cycles = 0, triangles = 0;
    static constexpr double kFirstDeath[2] = {kNotABirth, kNeverDies};
    // Edge k + 16 brings its endpoints' lines in (from DRAM on a large frame, from L2 on a
    // small one); by edge k + 8 they have arrived, and their parents' lines (mostly the roots)
    // are requested in turn.
    constexpr Index kFar = 16, kNear = 8;
    for (Index k = 0; k < m_; ++k) {
      if (k + kFar < m_) [[likely]] {
        __builtin_prefetch(&vertex[edges[k + kFar].u]);
        __builtin_prefetch(&vertex[edges[k + kFar].v]);
      }
      if (k + kNear < m_) [[likely]] {
        __builtin_prefetch(&vertex[vertex[edges[k + kNear].u].parent]);
        __builtin_prefetch(&vertex[vertex[edges[k + kNear].v].parent]);
      }
      const Index u = edges[k].u, v = edges[k].v;
      Vertex& x = vertex[u];
      Vertex& y = vertex[v];
      const bool fresh_u = x.count == 0, fresh_v = y.count == 0;  // a vertex enters with its strongest edge
      touched += fresh_u + fresh_v;
      const bool born = fresh_u & fresh_v;  // only then does a component survive edge k
      births += born;

      const Index ru = find(u), rv = find(v);
      loop[k] = ru == rv;
      if (ru != rv) {
        // Elder rule: the component born at the later position dies at k (if that is k
        // itself, it is a fresh vertex, whose birth still reads kNone: zero persistence). Trees
        // are linked by rank; the surviving root carries the elder birth. A merge edge closes
        // no triangle: its endpoints have no common neighbour yet.
        Vertex& a = vertex[ru];
        Vertex& b = vertex[rv];
        const auto [elder, younger] = ordered(std::min(a.birth, k), std::min(b.birth, k));
        death[pick(younger == k, m_, younger)] = edges[k].value;
        if constexpr (kPairs) killer_[pick(younger == k, m_, younger)] = k;
        death[k] = kFirstDeath[born];
        link[k] = kNone;
        const bool under_b = a.rank < b.rank;
        const Index root = pick(under_b, rv, ru);
        vertex[root].rank = static_cast<std::uint8_t>(std::max(a.rank, b.rank) + (a.rank == b.rank));
        vertex[pick(under_b, ru, rv)].parent = root;
        vertex[root].birth = elder;
      } else {
        // A loop is born at k, unless k closes a triangle: the first such triangle pairs with k
        // itself (an apparent pair, zero persistence). Its column is written whether or not
        // there is a triangle, and kept only if there is one; the pool always has room for 4
        // more entries per edge to come (see store_column).
        ++cycles;
        std::pair<Index, Index> found[kInline];
        std::span<const std::pair<Index, Index>> closing;
        if (x.count > kInline || y.count > kInline) [[unlikely]] {
          closing = collect_triangles_spilled(k, x, y);
          found[0] = {};
        } else {
          closing = {found, collect_triangles(x, y, found)};
        }
        const bool any = !closing.empty();
        const std::pair<Index, Index>* const first[2] = {found, closing.data()};
        const auto [a, b] = ordered(first[any]->first, first[any]->second);
        Index* at = pool_ + pool_size_;
        at[0] = 3, at[1] = a, at[2] = b, at[3] = k;
        link[k] = pick(any, static_cast<Index>(pool_size_), kNone);
        pool_size_ += 4 & (std::size_t{0} - any);
        death[k] = kFirstDeath[!any];
        triangles += closing.size();
        if (closing.size() > 1) [[unlikely]]
          reduce(k, closing.subspan(1));
      }

      append(x, v, k);
      append(y, u, k);
    }
    touched_ = touched, births_ = births, cycles_ = cycles, triangles_ = triangles;
  }

  // Path halving. Trees linked by rank are shallow: depth <= 2 is checked without a loop.
  Index find(Index x) {
    const Index p = vertex_[x].parent, g = vertex_[p].parent;
    if (vertex_[g].parent == g) [[likely]] {
      vertex_[x].parent = g;
      return g;
    }
    while (vertex_[x].parent != x) {
      const Index grandparent = vertex_[vertex_[x].parent].parent;
      vertex_[x].parent = grandparent;
      x = grandparent;
    }
    return x;
  }

  void append(Vertex& x, Index w, Index k) {
    if (x.count < kInline) [[likely]] {
      x.nbr[x.count] = w;
      x.via[x.count] = k;
      ++x.count;
    } else {
      append_spilled(x, {w, k});
    }
  }

  [[gnu::noinline]] void append_spilled(Vertex& x, Neighbour n) {
    if (x.count == kInline) {
      x.spill = static_cast<Index>(ws_.spill.size());
      auto& list = ws_.spill.emplace_back();
      for (std::size_t i = 0; i < kInline; ++i) list.push_back({x.nbr[i], x.via[i]});
      x.count = kSpilled;
    }
    ws_.spill[x.spill].push_back(n);
  }

  // Common neighbours of two vertices with inline lists, as the pair of edges reaching each;
  // returns how many. Each neighbour of the shorter list is compared with all slots of the
  // other at once, masked to the filled ones; a vertex is in a list once, so it matches once
  // at most. The match is written whether or not there is one, and counted only if there is.
  // Three rounds always (94% of edges need no more), so the loop's end is no coin flip.
  static std::size_t collect_triangles(const Vertex& x, const Vertex& y, std::pair<Index, Index>* found) {
    const Vertex* const xy[2] = {&x, &y};
    const bool y_shorter = y.count < x.count;
    const Vertex& s = *xy[y_shorter];
    const Vertex& l = *xy[!y_shorter];
    std::size_t n = 0;
#if defined(__SSE2__)
    const __m128i low = _mm_load_si128(reinterpret_cast<const __m128i*>(l.nbr));
    const __m128i high = _mm_loadu_si128(reinterpret_cast<const __m128i*>(l.nbr + 4));  // 2 slots + via[0..1]
    const unsigned filled = (1u << l.count) - 1;
    const auto round = [&](std::size_t i) {
      const __m128i w = _mm_set1_epi32(static_cast<int>(s.nbr[i]));
      const unsigned hits = (static_cast<unsigned>(_mm_movemask_ps(_mm_castsi128_ps(_mm_cmpeq_epi32(w, low)))) |
                             static_cast<unsigned>(_mm_movemask_ps(_mm_castsi128_ps(_mm_cmpeq_epi32(w, high)))) << 4) &
                            filled & (0u - (i < s.count));
      found[n] = {s.via[i], l.via[std::countr_zero(hits | (1u << (kInline - 1)))]};
      n += hits != 0;
    };
    round(0), round(1), round(2);
    for (std::size_t i = 3; i < s.count; ++i) round(i);
#else
    for (std::size_t i = 0; i < s.count; ++i)
      for (std::size_t j = 0; j < l.count; ++j)
        if (s.nbr[i] == l.nbr[j]) found[n++] = {s.via[i], l.via[j]};
#endif
    return n;
  }

  static void list_of(const Vertex& x, const std::vector<std::vector<Neighbour>>& spill, std::vector<Neighbour>& out) {
    out.clear();
    if (x.count == kSpilled) {
      out = spill[x.spill];
    } else {
      for (std::size_t i = 0; i < x.count; ++i) out.push_back({x.nbr[i], x.via[i]});
    }
  }

  [[gnu::noinline]] std::span<const std::pair<Index, Index>> collect_triangles_spilled(Index k, const Vertex& x,
                                                                                       const Vertex& y) {
    auto& closing = ws_.closing;
    closing.clear();
    list_of(x, ws_.spill, ws_.list_a);
    list_of(y, ws_.spill, ws_.list_b);
    const bool a_shorter = ws_.list_a.size() <= ws_.list_b.size();
    const auto& a = a_shorter ? ws_.list_a : ws_.list_b;
    const auto& b = a_shorter ? ws_.list_b : ws_.list_a;
    if (a.size() * b.size() <= 256) {
      for (const Neighbour& p : a)
        for (const Neighbour& q : b)
          if (p.vertex == q.vertex) closing.push_back(ordered(p.edge, q.edge));
      return closing;
    }
    // A long list: look each neighbour of the shorter one up in the other's sorted list.
    if (!sorted_) sorted_.emplace(net_);
    const Index other = a_shorter ? edges_[k].v : edges_[k].u;
    for (const Neighbour& p : a) {
      const Index e = sorted_->find_edge(other, p.vertex);
      if (e < k) closing.push_back(ordered(p.edge, e));
    }
    return closing;
  }

  bool closes_cycle(Index k) const { return loop_[k]; }

  // The column of a triangle that owns `pivot`, killing the loop born there at k. The pool
  // keeps room for the apparent pairs of all edges after k, 4 entries each.
  Index* store_column(Index pivot, Index k, std::size_t size, Index far_vertex) {
    const std::size_t needed = pool_size_ + size + 1 + 4 * static_cast<std::size_t>(m_ - k) + 64;
    if (needed > ws_.pool.capacity()) pool_ = ws_.pool.grow(std::max(needed, 2 * ws_.pool.capacity()), pool_size_);
    if (pool_size_ + size + 1 >= kNone) throw std::length_error("compute_persistence: column pool full");
    Index* at = pool_ + pool_size_;
    link_[pivot] = static_cast<Index>(pool_size_);
    death_[pivot] = edges_[k].value;
    if constexpr (kPairs) killer_[pivot] = k, third_[pivot] = far_vertex;
    at[0] = static_cast<Index>(size);
    pool_size_ += size + 1;
    return at + 1;
  }

  // Z/2 reduction of the boundary columns of the other triangles closed by edge k, against the
  // columns owning their pivots, until the pivot is new (the triangle kills the loop born
  // there) or the column vanishes (it closes a 2-cycle, possible only in non-planar graphs).
  // The pivot of a column is always an edge that closed a cycle: merge edges own nothing.
  [[gnu::noinline]] void reduce(Index k, std::span<const std::pair<Index, Index>> closing) {
    for (const auto& [e, f] : closing) {
      Index* column = scratch(0, 3);
      const auto [a, b] = ordered(e, f);
      column[0] = a, column[1] = b, column[2] = k;
      std::size_t size = 3, in = 0;
      while (size > 0 && link_[column[size - 1]] != kNone) {
        const Index* other = pool_ + link_[column[size - 1]];
        Index* sum = scratch(1 - in, size + other[0]);
        size = symmetric_difference(column, size, other + 1, other[0], sum);
        column = sum, in = 1 - in;
      }
      if (size == 0) continue;
      assert(closes_cycle(column[size - 1]));
      // The triangle (e, f, k) kills the loop born at the pivot; its far vertex is e's end off k.
      Index far_vertex = 0;
      if constexpr (kPairs) {
        const Edge& side = edges_[e];
        far_vertex = side.u == edges_[k].u || side.u == edges_[k].v ? side.v : side.u;
      }
      std::copy(column, column + size, store_column(column[size - 1], k, size, far_vertex));
    }
  }

  // Column buffer `which` (0 or 1) with room for `size` entries.
  Index* scratch(std::size_t which, std::size_t size) {
    auto& buffer = ws_.column[which];
    if (buffer.size() < size) buffer.resize(std::max<std::size_t>(2 * size, 64));
    return buffer.data();
  }

  // out = a + b over Z/2, for sorted columns; returns the size of out.
  static std::size_t symmetric_difference(const Index* a, std::size_t na, const Index* b, std::size_t nb, Index* out) {
    std::size_t i = 0, j = 0, n = 0;
    while (i < na && j < nb) {
      const Index x = a[i], y = b[j];
      out[n] = x < y ? x : y;
      n += x != y;
      i += x <= y;
      j += y <= x;
    }
    while (i < na) out[n++] = a[i++];
    while (j < nb) out[n++] = b[j++];
    return n;
  }

  // Each edge is the birth of at most one class: a component (it brought in two fresh
  // vertices) or a loop (it closed a cycle); death_ holds that class's death. Every slot is
  // written, and kept only if it holds a point of positive persistence.
  FrameDiagrams diagrams() {
    PersistencePoint* const first0 = ws_.points[0].get(births_ + 1);
    PersistencePoint* const first1 = ws_.points[1].get(cycles_ + 1);
    PersistencePoint *p0 = first0, *p1 = first1;
    for (Index k = 0; k < m_; ++k) {
      const double birth = edges_[k].value, death = death_[k];
      const bool loop = loop_[k], kept = (death == kNeverDies) | (birth > death);
      *p0 = *p1 = {birth, death};
      p1 += loop & kept;
      p0 += !loop & kept;
    }
    FrameDiagrams out;
    out.vertices = net_.vertex_count;
    out.edges = m_;
    out.triangles = triangles_;
    const std::size_t rattlers = net_.vertex_count - touched_;
    export_points(first0, p0, rattlers, out.pd0);
    export_points(first1, p1, 0, out.pd1);
    out.pd0.insert(out.pd0.end(), rattlers, PersistencePoint{0.0, kNeverDies});  // they come last: birth 0
    return out;
  }

  // As diagrams(), with each kept point's simplices beside it. Not on the analysis path: plain code.
  PairedDiagrams paired_diagrams() {
    PairedDiagrams out;
    FrameDiagrams& d = out.diagrams;
    d.vertices = net_.vertex_count;
    d.edges = m_;
    d.triangles = triangles_;
    std::vector<std::pair<PersistencePoint, PointSimplices>> points[2];
    points[0].reserve(births_ + net_.vertex_count - touched_);
    points[1].reserve(cycles_);
    for (Index k = 0; k < m_; ++k) {
      const double birth = edges_[k].value, death = death_[k];
      if (!(death == kNeverDies || birth > death)) continue;
      const Edge& e = edges_[k];
      PointSimplices s;
      if (loop_[k]) {
        s.birth = {{e.u, e.v, 0}, 2};
        if (death != kNeverDies) s.death = triangle(killer_[k], third_[k]);
      } else {
        s.birth = {{e.u, 0, 0}, 1};  // both ends enter with e; the lower index is the elder
        if (death != kNeverDies) {
          const Edge& merge = edges_[killer_[k]];
          s.death = {{merge.u, merge.v, 0}, 2};
        }
      }
      points[loop_[k]].push_back({{birth, death}, s});
    }
    for (auto& p : points) order_paired_ties(p);
    for (Index v = 0; v < net_.vertex_count; ++v)  // rattlers, after every point of birth > 0
      if (vertex_[v].count == 0) points[0].push_back({{0.0, kNeverDies}, {{{v, 0, 0}, 1}, {}}});
    for (int dim = 0; dim < 2; ++dim) {
      Diagram& diagram = dim == 0 ? d.pd0 : d.pd1;
      std::vector<PointSimplices>& simplices = dim == 0 ? out.pd0 : out.pd1;
      diagram.reserve(points[dim].size());
      simplices.reserve(points[dim].size());
      for (const auto& [point, s] : points[dim]) diagram.push_back(point), simplices.push_back(s);
    }
    return out;
  }

  // The triangle of edge k and vertex w, vertices ascending.
  Simplex triangle(Index k, Index w) const {
    std::array<std::uint32_t, 3> v{edges_[k].u, edges_[k].v, w};
    std::sort(v.begin(), v.end());
    return {v, 3};
  }

  static void order_paired_ties(std::vector<std::pair<PersistencePoint, PointSimplices>>& d) {
    for (std::size_t i = 0, j = 0; i < d.size(); i = j) {
      for (j = i + 1; j < d.size() && d[j].first.birth == d[i].first.birth;) ++j;
      if (j - i > 1)
        std::sort(d.begin() + static_cast<std::ptrdiff_t>(i), d.begin() + static_cast<std::ptrdiff_t>(j),
                  [](const auto& a, const auto& b) { return a.first.death > b.first.death; });
    }
  }

  // Copies points into a diagram allocated once at its final size.
  static void export_points(const PersistencePoint* first, const PersistencePoint* last, std::size_t extra,
                            Diagram& out) {
    const auto n = static_cast<std::size_t>(last - first);
    out.reserve(n + extra);
    prefer_huge_pages(out.data(), (n + extra) * sizeof(PersistencePoint));
    out.assign(first, last);
    order_ties(out);
  }

  // Points come out by birth, descending; equal births (ties in force) need death descending.
  static void order_ties(Diagram& d) {
    for (std::size_t i = 0, j = 0; i < d.size(); i = j) {
      for (j = i + 1; j < d.size() && d[j].birth == d[i].birth;) ++j;
      if (j - i > 1)
        std::sort(d.begin() + static_cast<std::ptrdiff_t>(i), d.begin() + static_cast<std::ptrdiff_t>(j),
                  [](const PersistencePoint& a, const PersistencePoint& b) { return a.death > b.death; });
    }
  }

  const ForceNetwork& net_;
  const Edge* edges_;
  Index m_;
  Vertex* vertex_;
  Index* link_;
  double* death_;
  std::uint8_t* loop_;
  Index* killer_ = nullptr;  // pairs only
  Index* third_ = nullptr;   // pairs only
  Index* pool_;
  Workspace& ws_;
  std::optional<SortedAdjacency> sorted_;
  std::pair<Index, Index> found_[kInline] = {};
  std::size_t pool_size_ = 1;  // offset 0 is never a column
  std::size_t touched_ = 0, births_ = 0, cycles_ = 0, triangles_ = 0;
};

}  // namespace

namespace {
Workspace& thread_workspace() {
  thread_local Workspace workspace;
  return workspace;
}
}  // namespace

FrameDiagrams compute_persistence(const ForceNetwork& network) {
  return Sweep<false>(network, thread_workspace()).run();
}

PairedDiagrams compute_persistence_pairs(const ForceNetwork& network) {
  return Sweep<true>(network, thread_workspace()).run();
}

}  // namespace fnet
