#include "reference/union_outline.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>

namespace radquad {

bool UnionOutline::add(const std::vector<SourceRing>& rings,
                       const std::vector<std::size_t>& members,
                       const std::vector<Eigen::Vector4d>& bounds,
                       const std::vector<std::vector<std::uint32_t>>& onBorder,
                       const SourceRing& border, double sign, VisibleRings& out) {
  // The union's boundary is made of the pieces of the shadows' edges that lie outside every
  // other shadow; each keeps its shadow's (counter-clockwise) direction, so the pieces about
  // a hole of the union run clockwise about it. A piece of an edge of shadow i is covered by
  // shadow j where it lies on the inner side of every edge line of j (the shadows are
  // convex).
  //  - Where two edges cross, both pieces end at one point, computed once from the two
  //    lines in a fixed order: the outline closes up exactly, however small their angle.
  //  - Two edges along one line (the shorter's ends within 1e-13 of the coordinates' unit of
  //    the longer's line, the rounding of the projections; the pieces then differ by a
  //    sliver of that width): running opposite ways, the shadows lie on either side and the
  //    line is inside the union (touching occluders), so the line does not bound what the
  //    other covers; running the same way (two shadows cut by one pyramid plane), both lie on
  //    one side and the line is on the boundary once: the earlier shadow keeps it.
  //  - An edge shorter than 1e-12 of the shadows' extent (a vertex repeated where an
  //    occluder's vertex lies on a pyramid plane) cuts nothing as a line, its direction being
  //    rounding (its neighbours' lines bound the shadow there); as a piece it counts.
  Eigen::Vector2d low(1e300, 1e300), high(-1e300, -1e300);
  for (std::size_t i : members) {
    low = low.cwiseMin(bounds[i].head<2>());
    high = high.cwiseMax(bounds[i].tail<2>());
  }
  constexpr double kOnLine = 1e-13;
  const double shortest = 1e-12 * (high - low).maxCoeff();
  // Edge e of shadow i, as (i, e).
  using EdgeKey = std::pair<std::size_t, std::size_t>;
  const auto ends = [&](const EdgeKey& key) {
    const SourceRing& ring = rings[key.first];
    return std::pair<const Eigen::Vector2d&, const Eigen::Vector2d&>(
        ring[key.second], ring[(key.second + 1) % ring.size()]);
  };
  // Where the lines of two edges cross: the same bits whichever edge asks.
  const auto crossing = [&](EdgeKey first, EdgeKey second, const Eigen::Vector2d& fallback) {
    if (second < first) std::swap(first, second);
    const auto [a, b] = ends(first);
    const auto [c, d] = ends(second);
    const Eigen::Vector2d ab = b - a, cd = d - c, ac = c - a;
    const double denominator = ab.x() * cd.y() - ab.y() * cd.x();
    if (denominator == 0.0) return fallback;
    const double s = (ac.x() * cd.y() - ac.y() * cd.x()) / denominator;
    return Eigen::Vector2d(a + s * ab);
  };
  // Whether edges (p, q) and (a, b) lie along one line: the shorter's ends on the longer's
  // line (the longer's direction is the better known), the first key's on a tie.
  const auto alongOneLine = [&](const Eigen::Vector2d& p, const Eigen::Vector2d& q,
                                const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                                bool firstIsEarlier) {
    const Eigen::Vector2d pq = q - p, ab = b - a;
    const double lengthPQ = pq.norm(), lengthAB = ab.norm();
    const bool referencePQ = lengthPQ > lengthAB || (lengthPQ == lengthAB && firstIsEarlier);
    const Eigen::Vector2d& origin = referencePQ ? p : a;
    const Eigen::Vector2d& line = referencePQ ? pq : ab;
    const Eigen::Vector2d& u = referencePQ ? a : p;
    const Eigen::Vector2d& w = referencePQ ? b : q;
    const double onLine = kOnLine * std::max(lengthPQ, lengthAB);
    return std::fabs(line.x() * (u.y() - origin.y()) - line.y() * (u.x() - origin.x())) <= onLine &&
           std::fabs(line.x() * (w.y() - origin.y()) - line.y() * (w.x() - origin.x())) <= onLine;
  };
  // S' (`border`; every shadow lies inside it): a shadow edge along one of its edges
  // (both ends on the pyramid plane through x and that edge, as the 3D clip placed them)
  // bounds the union wherever it runs, and as a line it cuts nothing inside S'. Those edges
  // are not pieces: per edge of S', the parts of it they cover are merged and given as
  // segments from the first edge's start to the last one's end, vertices of the shadows
  // themselves, where the shadows' other edges begin and end: the outline closes up there to
  // the bit.
  const SourceRing& front = border;
  const std::size_t sides = front.size();
  // Per shadow and edge: (edge vector, squared length or 0 if too short to cut by, the edge of
  // S' it runs along or -1).
  if (edgeLines_.size() < rings.size()) edgeLines_.resize(rings.size());
  std::vector<BorderPart>& along = borderParts_;
  along.clear();
  for (std::size_t i : members) {
    const SourceRing& ring = rings[i];
    const std::vector<std::uint32_t>& on = onBorder[i];
    std::vector<Eigen::Vector4d>& lines = edgeLines_[i];
    lines.clear();
    for (std::size_t f = 0, m = ring.size(); f < m; ++f) {
      const Eigen::Vector2d& a = ring[f];
      const Eigen::Vector2d& b = ring[(f + 1) % m];
      const Eigen::Vector2d line = b - a;
      const bool cuts = line.cwiseAbs().maxCoeff() >= shortest;
      double borderSide = -1.0;
      const std::uint32_t common = on[f] & on[(f + 1) % m];
      if (common != 0 && cuts) {
        const std::size_t k = std::size_t(std::countr_zero(common));
        const Eigen::Vector2d& c = front[k];
        const Eigen::Vector2d side = front[(k + 1) % sides] - c;
        if (line.dot(side) > 0.0) {
          borderSide = double(k);
          const double squared = side.squaredNorm();
          along.push_back({k, (a - c).dot(side) / squared, (b - c).dot(side) / squared, a, b,
                            on[f], on[(f + 1) % m]});
        }
      }
      lines.push_back({line.x(), line.y(), cuts ? line.squaredNorm() : 0.0, borderSide});
    }
  }
  std::vector<CoveredPart>& covered = covered_;
  const std::size_t first = out.segmentCount();
  // The border: per edge of S', its covered parts in order along it, merged where they
  // overlap. Where the border turns a corner of S' (the last part on one side ends on the
  // next side's plane, and the first part there starts on this side's), the shadows' corners
  // may be different vertices an ulp apart: both parts end at S''s own corner.
  std::sort(along.begin(), along.end(), [](const BorderPart& x, const BorderPart& y) {
    return x.side < y.side || (x.side == y.side && x.from < y.from);
  });
  std::vector<BorderPart>& merged = mergedBorder_;
  merged.clear();
  for (std::size_t k = 0; k < along.size();) {
    BorderPart part = along[k];
    for (++k; k < along.size() && along[k].side == part.side && along[k].from <= part.to; ++k) {
      if (along[k].to > part.to) {
        part.to = along[k].to;
        part.end = along[k].end;
        part.endOn = along[k].endOn;
      }
    }
    merged.push_back(part);
  }
  for (std::size_t k = 0; k < merged.size(); ++k) {
    // The last part on its side, and the first part on the next side.
    BorderPart& part = merged[k];
    if (k + 1 < merged.size() && merged[k + 1].side == part.side) continue;
    const std::size_t nextSide = (part.side + 1) % sides;
    if (!(part.endOn >> nextSide & 1u)) continue;
    for (BorderPart& next : merged) {
      if (next.side != nextSide) continue;
      if (next.startOn >> part.side & 1u) {
        part.end = front[nextSide];
        next.start = front[nextSide];
      }
      break;  // the first on that side (in order)
    }
  }
  for (const BorderPart& part : merged) out.addSegment(part.start, part.end, sign);
  for (std::size_t i : members) {
    const SourceRing& shadow = rings[i];
    for (std::size_t e = 0, n = shadow.size(); e < n; ++e) {
      const Eigen::Vector2d& p = shadow[e];
      const Eigen::Vector2d& q = shadow[(e + 1) % n];
      const Eigen::Vector2d pq = q - p;
      if (!(pq.cwiseAbs().maxCoeff() > 0.0) || edgeLines_[i][e][3] >= 0.0) continue;
      const EdgeKey self{i, e};
      const double lengthSquared = pq.squaredNorm();
      const Eigen::Vector2d edgeLow = p.cwiseMin(q), edgeHigh = p.cwiseMax(q);
      covered.clear();
      for (std::size_t j : members) {
        if (j == i) continue;
        const Eigen::Vector4d& box = bounds[j];
        if (box[0] > edgeHigh.x() + kOnLine || edgeLow.x() > box[2] + kOnLine ||
            box[1] > edgeHigh.y() + kOnLine || edgeLow.y() > box[3] + kOnLine) {
          continue;
        }
        // The part [from, to] of the edge (p + t pq, t in [0, 1]) inside shadow j, and the
        // edges of j it enters and leaves by (none: the edge's own end).
        const SourceRing& cover = rings[j];
        const std::vector<Eigen::Vector4d>& lines = edgeLines_[j];
        CoveredPart part{0.0, 1.0, kNoEdge, kNoEdge};
        for (std::size_t f = 0, m = cover.size(); f < m && part.from < part.to; ++f) {
          if (lines[f].z() == 0.0 || lines[f][3] >= 0.0) continue;
          const Eigen::Vector2d& a = cover[f];
          const Eigen::Vector2d line = lines[f].head<2>();
          // Heights of p and q over the line, times its length: > 0 on the inner side.
          const double hp = line.x() * (p.y() - a.y()) - line.y() * (p.x() - a.x());
          const double hq = line.x() * (q.y() - a.y()) - line.y() * (q.x() - a.x());
          // hq - hp = line x pq: edges along one line have it within 2 kOnLine of the longer's
          // length (the test below), so the others skip it.
          const double turn = hq - hp;
          if (turn * turn <= 4.0 * kOnLine * kOnLine * std::max(lengthSquared, lines[f].z()) &&
              alongOneLine(p, q, a, cover[(f + 1) % m], self < EdgeKey{j, f})) {
            if (pq.dot(line) < 0.0 || j < i) continue;
            part.from = part.to;
            break;
          }
          if (hp >= 0.0 && hq >= 0.0) continue;
          if (hp <= 0.0 && hq <= 0.0) {
            part.from = part.to;
            break;
          }
          const double t = hp / (hp - hq);
          if (hp < 0.0 && t > part.from) {
            part.from = t;
            part.fromEdge = f;
          } else if (hp > 0.0 && t < part.to) {
            part.to = t;
            part.toEdge = f;
          }
        }
        if (part.from < part.to) {
          part.cover = j;
          covered.push_back(part);
        }
      }
      // The pieces of [0, 1] outside the covered parts, from crossing to crossing.
      std::sort(covered.begin(), covered.end(),
                [](const CoveredPart& x, const CoveredPart& y) { return x.from < y.from; });
      const auto pointAt = [&](std::size_t cover, std::size_t edge, double t) {
        const Eigen::Vector2d estimate = p + t * pq;
        return edge == kNoEdge ? (t <= 0.0 ? p : q) : crossing(self, {cover, edge}, estimate);
      };
      double start = 0.0;
      Eigen::Vector2d startPoint = p;
      for (const CoveredPart& part : covered) {
        if (part.from > start) {
          out.addSegment(startPoint, pointAt(part.cover, part.fromEdge, part.from), sign);
        }
        if (part.to > start) {
          start = part.to;
          startPoint = pointAt(part.cover, part.toEdge, part.to);
        }
        if (start >= 1.0) break;
      }
      if (start < 1.0) out.addSegment(startPoint, q, sign);
    }
  }
  if (close(first, 1e-11 * std::max(1.0, (high - low).maxCoeff()), sign, out)) return true;
  out.truncateSegments(first);
  return false;
}

bool UnionOutline::close(std::size_t first, double tolerance, double sign, VisibleRings& out) {
  // Pieces meet where an edge's own vertex ends one and starts the next, or at the crossing of
  // two edges computed once: the same point to the bit. Where the choice between two edges
  // along one line changes hands, where a vertex lies on another shadow's edge, or where a
  // shadow's edge along S''s border lies just past the clip's slack while another's lies
  // within it, an end may miss every start by rounding. The gap would count: each piece's
  // term is a triangle from the foot of x, and at higher degrees, the foot far outside the
  // source, the basis there is thousands of times its size on the source, so a gap of 1e-15
  // shows at 1e-11. A short piece from such an end to the nearest unmatched start closes the
  // outline (the region changes by slivers of that width); an end with no start within
  // `tolerance` fails the outline.
  const std::size_t count = out.segmentCount();
  // First a check that costs little: the starts and the ends are the same points, as many
  // times, if the sum of a hash of each start's coordinates (modulo 2^64) equals that of the
  // ends' (collisions aside: 2^-64).
  const auto hash = [](const Eigen::Vector2d& point) {
    const auto mix = [](std::uint64_t z) {  // splitmix64's finaliser
      z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
      z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
      return z ^ (z >> 31);
    };
    // + 0.0: -0 and +0 are one point.
    return mix(std::bit_cast<std::uint64_t>(point.x() + 0.0) ^
               mix(std::bit_cast<std::uint64_t>(point.y() + 0.0)));
  };
  std::uint64_t balance = 0;
  for (std::size_t s = first; s < count; ++s) {
    balance += hash(out.segmentStart(s)) - hash(out.segmentEnd(s));
  }
  if (balance == 0) return true;
  std::vector<std::pair<Eigen::Vector2d, std::size_t>>& starts = starts_;
  std::vector<std::pair<Eigen::Vector2d, std::size_t>>& ends = ends_;
  starts.clear();
  ends.clear();
  for (std::size_t s = first; s < count; ++s) {
    starts.push_back({out.segmentStart(s), s});
    ends.push_back({out.segmentEnd(s), s});
  }
  const auto before = [](const std::pair<Eigen::Vector2d, std::size_t>& a,
                         const std::pair<Eigen::Vector2d, std::size_t>& b) {
    return a.first.x() < b.first.x() || (a.first.x() == b.first.x() && a.first.y() < b.first.y());
  };
  std::sort(starts.begin(), starts.end(), before);
  std::sort(ends.begin(), ends.end(), before);
  // Match equal points (a merge of the two sorted lists); the unmatched stay, marked by
  // their index, the matched get kNoEdge.
  std::size_t a = 0, b = 0;
  while (a < starts.size() && b < ends.size()) {
    if (starts[a].first == ends[b].first) {
      starts[a++].second = kNoEdge;
      ends[b++].second = kNoEdge;
    } else if (before(starts[a], ends[b])) {
      ++a;
    } else {
      ++b;
    }
  }
  for (auto& [end, endIndex] : ends) {
    if (endIndex == kNoEdge) continue;
    double nearest = tolerance;
    std::size_t chosen = kNoEdge;
    for (std::size_t k = 0; k < starts.size(); ++k) {
      if (starts[k].second == kNoEdge) continue;
      const double distance = (starts[k].first - end).cwiseAbs().maxCoeff();
      if (distance <= nearest) {
        nearest = distance;
        chosen = k;
      }
    }
    if (chosen == kNoEdge) return false;
    out.addSegment(end, starts[chosen].first, sign);
    starts[chosen].second = kNoEdge;
    endIndex = kNoEdge;
  }
  return true;
}

}  // namespace radquad
