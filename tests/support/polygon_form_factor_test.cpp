// The contour-integral polygon form factor against closed forms (Howell C-11 and C-14),
// enclosure sums, reciprocity, additivity over triangles, rigid-motion invariance, and a direct
// high-order quadrature of the area integral for well-separated skew pairs.
#include "tests/support/polygon_form_factor.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "tests/support/analytic_form_factors.h"

namespace radquad::analytic {
namespace {

using Polygon = std::vector<Eigen::Vector3d>;
using Eigen::Vector3d;

constexpr double kRelTol = 1e-10;

// The parallelogram origin, origin + u, origin + u + v, origin + v: counter-clockwise about u x v.
Polygon parallelogram(const Vector3d& origin, const Vector3d& u, const Vector3d& v) {
  return {origin, origin + u, origin + u + v, origin + v};
}

double area(const Polygon& polygon) {
  Vector3d normal = Vector3d::Zero();
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    normal += polygon[i].cross(polygon[(i + 1) % polygon.size()]);
  }
  return 0.5 * normal.norm();
}

Polygon reversed(const Polygon& polygon) {
  return Polygon(polygon.rbegin(), polygon.rend());
}

Polygon transformed(const Polygon& polygon, const Eigen::Isometry3d& motion) {
  Polygon out;
  for (const Vector3d& v : polygon) out.push_back(motion * v);
  return out;
}

// A regular n-gon of circumradius r about `center`, counter-clockwise about `normal`.
Polygon regularPolygon(const Vector3d& center, const Vector3d& normal, double r, int n,
                       double phase) {
  const Vector3d n2 = normal.normalized();
  const Vector3d e1 = n2.unitOrthogonal();
  const Vector3d e2 = n2.cross(e1);
  Polygon out;
  for (int k = 0; k < n; ++k) {
    const double angle = phase + 2.0 * std::numbers::pi * k / n;
    out.push_back(center + r * (std::cos(angle) * e1 + std::sin(angle) * e2));
  }
  return out;
}

// The faces of the tetrahedron with vertices v[0..3], face k opposite vertex k, each
// counter-clockwise about its inward normal.
std::vector<Polygon> tetrahedronFaces(const std::vector<Vector3d>& v) {
  std::vector<Polygon> faces;
  for (int k = 0; k < 4; ++k) {
    Polygon face;
    for (int i = 0; i < 4; ++i) {
      if (i != k) face.push_back(v[i]);
    }
    const Vector3d normal = (face[1] - face[0]).cross(face[2] - face[0]);
    if (normal.dot(v[k] - face[0]) < 0) face = reversed(face);
    faces.push_back(face);
  }
  return faces;
}

void expectRelNear(double actual, double expected, double relTol) {
  EXPECT_NEAR(actual, expected, relTol * std::abs(expected))
      << "relative difference " << (actual - expected) / expected;
}

// Two directly opposed a x b rectangles at distance c, fronts facing each other.
struct ParallelCase {
  double a, b, c;
};

class ParallelRectanglesTest : public ::testing::TestWithParam<ParallelCase> {};

TEST_P(ParallelRectanglesTest, MatchesHowellC11) {
  const auto [a, b, c] = GetParam();
  const Polygon bottom = parallelogram({0, 0, 0}, {a, 0, 0}, {0, b, 0});  // normal +z
  const Polygon top = parallelogram({0, 0, c}, {0, b, 0}, {a, 0, 0});     // normal -z
  const double exact = parallelRectangles(a, b, c);
  expectRelNear(polygonToPolygonFormFactor(bottom, top), exact, kRelTol);
  expectRelNear(polygonToPolygonFormFactor(top, bottom), exact, kRelTol);
}

// The catalogue formula itself loses digits to cancellation when c is large (about 5e-12
// relative at c = 10a in double precision), which bounds the distances used here.
INSTANTIATE_TEST_SUITE_P(AspectRatiosAndDistances, ParallelRectanglesTest,
                         ::testing::Values(ParallelCase{1, 1, 1}, ParallelCase{2, 1, 1},
                                           ParallelCase{1, 3, 0.5}, ParallelCase{0.2, 5, 1},
                                           ParallelCase{3, 0.5, 2}, ParallelCase{1, 1, 10},
                                           ParallelCase{2, 1, 0.1}, ParallelCase{1, 1, 0.02}));

// From a w x l rectangle to an h x l rectangle sharing the edge of length l, at right angles.
struct PerpendicularCase {
  double w, h, l;
};

class PerpendicularRectanglesTest : public ::testing::TestWithParam<PerpendicularCase> {};

TEST_P(PerpendicularRectanglesTest, MatchesHowellC14) {
  const auto [w, h, l] = GetParam();
  const Polygon floor = parallelogram({0, 0, 0}, {w, 0, 0}, {0, l, 0});  // normal +z
  const Polygon wall = parallelogram({0, 0, 0}, {0, l, 0}, {0, 0, h});   // normal +x
  expectRelNear(polygonToPolygonFormFactor(floor, wall), perpendicularRectangles(w, h, l), kRelTol);
  expectRelNear(polygonToPolygonFormFactor(wall, floor), perpendicularRectangles(h, w, l), kRelTol);
}

INSTANTIATE_TEST_SUITE_P(AspectRatios, PerpendicularRectanglesTest,
                         ::testing::Values(PerpendicularCase{1, 1, 1}, PerpendicularCase{2, 1, 1},
                                           PerpendicularCase{1, 2, 1}, PerpendicularCase{0.5, 3, 2},
                                           PerpendicularCase{1, 1, 0.1},
                                           PerpendicularCase{0.1, 5, 1},
                                           PerpendicularCase{3, 0.25, 4}));

// The bottom of a closed box sees the five other faces: the fractions add up to one, and each
// of them is a catalogue value.
TEST(PolygonFormFactorTest, BoxFloorSeesEverythingOnce) {
  const double a = 1.0, b = 2.0, c = 0.7;
  const Polygon floor = parallelogram({0, 0, 0}, {a, 0, 0}, {0, b, 0});
  const std::vector<Polygon> others = {
      parallelogram({0, 0, c}, {0, b, 0}, {a, 0, 0}),  // ceiling, normal -z
      parallelogram({0, 0, 0}, {0, b, 0}, {0, 0, c}),  // x = 0, normal +x
      parallelogram({a, 0, 0}, {0, 0, c}, {0, b, 0}),  // x = a, normal -x
      parallelogram({0, 0, 0}, {0, 0, c}, {a, 0, 0}),  // y = 0, normal +y
      parallelogram({0, b, 0}, {a, 0, 0}, {0, 0, c}),  // y = b, normal -y
  };
  const std::vector<double> exact = {parallelRectangles(a, b, c), perpendicularRectangles(a, c, b),
                                     perpendicularRectangles(a, c, b),
                                     perpendicularRectangles(b, c, a),
                                     perpendicularRectangles(b, c, a)};
  double sum = 0.0;
  for (std::size_t k = 0; k < others.size(); ++k) {
    const double f = polygonToPolygonFormFactor(floor, others[k]);
    expectRelNear(f, exact[k], kRelTol);
    sum += f;
  }
  EXPECT_NEAR(sum, 1.0, 1e-12);
}

// In a regular tetrahedron every face sees each of the other three (triangles meeting along an
// edge at the dihedral angle acos(1/3)) with form factor exactly 1/3.
TEST(PolygonFormFactorTest, RegularTetrahedronFacesSeeEachOtherAThird) {
  const std::vector<Vector3d> v = {{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}};
  const std::vector<Polygon> faces = tetrahedronFaces(v);
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) {
      if (i != j) expectRelNear(polygonToPolygonFormFactor(faces[i], faces[j]), 1.0 / 3.0, kRelTol);
    }
  }
}

// An irregular tetrahedron: every row of form factors sums to one and the matrix obeys
// reciprocity.
TEST(PolygonFormFactorTest, IrregularTetrahedronIsAnEnclosure) {
  const std::vector<Vector3d> v = {{0, 0, 0}, {2.0, 0.1, 0}, {0.3, 1.4, 0.2}, {0.6, 0.5, 1.7}};
  const std::vector<Polygon> faces = tetrahedronFaces(v);
  double f[4][4] = {};
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) {
      if (i != j) f[i][j] = polygonToPolygonFormFactor(faces[i], faces[j]);
    }
  }
  for (int i = 0; i < 4; ++i) {
    EXPECT_NEAR(f[i][0] + f[i][1] + f[i][2] + f[i][3], 1.0, 1e-12) << "face " << i;
    for (int j = 0; j < i; ++j) {
      expectRelNear(area(faces[i]) * f[i][j], area(faces[j]) * f[j][i], 1e-12);
    }
  }
}

// Splitting the wall of the perpendicular pair along either diagonal: the triangles' form
// factors, to and (area-weighted) from the floor, add up to the catalogue values. One triangle
// keeps the common edge, the other touches the floor only at a vertex.
TEST(PolygonFormFactorTest, TrianglesAddUpToTheirRectangle) {
  const double w = 1.3, h = 0.8, l = 1.1;
  const Polygon floor = parallelogram({0, 0, 0}, {w, 0, 0}, {0, l, 0});
  const Polygon wall = parallelogram({0, 0, 0}, {0, l, 0}, {0, 0, h});
  for (int s = 0; s < 2; ++s) {  // the diagonal from vertex s to vertex s + 2
    const Polygon t1 = {wall[s], wall[s + 1], wall[s + 2]};
    const Polygon t2 = {wall[s + 2], wall[(s + 3) % 4], wall[s]};
    expectRelNear(polygonToPolygonFormFactor(floor, t1) + polygonToPolygonFormFactor(floor, t2),
                  perpendicularRectangles(w, h, l), kRelTol);
    const double fromWall = (area(t1) * polygonToPolygonFormFactor(t1, floor) +
                             area(t2) * polygonToPolygonFormFactor(t2, floor)) /
                            area(wall);
    expectRelNear(fromWall, perpendicularRectangles(h, w, l), kRelTol);
  }
}

// A wall standing on the middle part of a floor edge: the collinear bottom edges overlap only
// in part, and the floor strips beside the wall meet it end to end at a single point.
TEST(PolygonFormFactorTest, WallOnPartOfTheFloorEdge) {
  const double w = 1.2, h = 0.7;
  const Polygon wall = parallelogram({0, 0.3, 0}, {0, 0.5, 0}, {0, 0, h});  // normal +x
  const Polygon floor = parallelogram({0, 0, 0}, {w, 0, 0}, {0, 1, 0});
  const std::vector<Polygon> strips = {parallelogram({0, 0, 0}, {w, 0, 0}, {0, 0.3, 0}),
                                       parallelogram({0, 0.3, 0}, {w, 0, 0}, {0, 0.5, 0}),
                                       parallelogram({0, 0.8, 0}, {w, 0, 0}, {0, 0.2, 0})};
  expectRelNear(polygonToPolygonFormFactor(wall, strips[1]), perpendicularRectangles(h, w, 0.5),
                kRelTol);
  double sum = 0.0;
  for (const Polygon& strip : strips) sum += polygonToPolygonFormFactor(wall, strip);
  expectRelNear(sum, polygonToPolygonFormFactor(wall, floor), 1e-12);
}

// The same additivity for the opposed parallel rectangles, with triangles on both sides.
TEST(PolygonFormFactorTest, TrianglePairsAddUpBetweenParallelRectangles) {
  const double a = 1.0, b = 1.5, c = 0.6;
  const Polygon bottom = parallelogram({0, 0, 0}, {a, 0, 0}, {0, b, 0});
  const Polygon top = parallelogram({0, 0, c}, {0, b, 0}, {a, 0, 0});
  const std::vector<Polygon> bottomHalves = {{bottom[0], bottom[1], bottom[2]},
                                             {bottom[2], bottom[3], bottom[0]}};
  const std::vector<Polygon> topHalves = {{top[1], top[2], top[3]}, {top[3], top[0], top[1]}};
  double sum = 0.0;
  for (const Polygon& from : bottomHalves) {
    for (const Polygon& to : topHalves) sum += area(from) * polygonToPolygonFormFactor(from, to);
  }
  expectRelNear(sum / area(bottom), parallelRectangles(a, b, c), kRelTol);
}

// The form factor does not depend on where the polygons sit, nor on which vertex comes first.
TEST(PolygonFormFactorTest, InvariantUnderRigidMotionAndVertexCycling) {
  const double a = 1.7, b = 0.9, c = 0.8;
  Polygon bottom = parallelogram({0, 0, 0}, {a, 0, 0}, {0, b, 0});
  Polygon top = parallelogram({0, 0, c}, {0, b, 0}, {a, 0, 0});
  std::rotate(top.begin(), top.begin() + 1, top.end());
  Eigen::Isometry3d motion = Eigen::Isometry3d::Identity();
  motion.rotate(Eigen::AngleAxisd(0.7, Vector3d(1, -2, 0.5).normalized()));
  motion.pretranslate(Vector3d(3.0, -1.0, 12.0));
  expectRelNear(polygonToPolygonFormFactor(transformed(bottom, motion), transformed(top, motion)),
                parallelRectangles(a, b, c), kRelTol);
}

// A tilted pentagon above a triangle: neither parallel nor perpendicular edge pairs dominate,
// and the two directions must agree through A1 F12 = A2 F21.
TEST(PolygonFormFactorTest, ReciprocityForSkewPolygons) {
  const Polygon triangle = {{0, 0, 0}, {1.2, 0.1, 0}, {0.3, 0.9, 0}};  // normal +z
  const Polygon pentagon =
      regularPolygon({0.4, 0.3, 1.5}, {0.3, -0.2, -1.0}, 0.6, 5, 0.3);  // faces down
  const double f12 = polygonToPolygonFormFactor(triangle, pentagon);
  const double f21 = polygonToPolygonFormFactor(pentagon, triangle);
  EXPECT_GT(f12, 0.0);
  expectRelNear(area(triangle) * f12, area(pentagon) * f21, 1e-12);
}

// Gauss-Legendre nodes and weights on [0, 1], by Newton's method on the Legendre polynomial.
void gaussLegendre01(int n, std::vector<double>& x, std::vector<double>& w) {
  x.assign(n, 0.0);
  w.assign(n, 0.0);
  for (int i = 0; i < n; ++i) {
    double t = std::cos(std::numbers::pi * (i + 0.75) / (n + 0.5));
    double dp = 1.0;
    for (int iteration = 0; iteration < 100; ++iteration) {
      double p0 = 1.0, p1 = t;
      for (int k = 2; k <= n; ++k) {
        const double p2 = ((2.0 * k - 1.0) * t * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      dp = n * (t * p1 - p0) / (t * t - 1.0);
      const double step = p1 / dp;
      t -= step;
      if (std::abs(step) < 1e-16) break;
    }
    x[i] = 0.5 * (1.0 - t);
    w[i] = 1.0 / ((1.0 - t * t) * dp * dp);
  }
}

// Direct tensor-product Gauss-Legendre quadrature of the area integral between two
// parallelograms, converging exponentially when they are well separated.
double areaQuadrature(const Vector3d& o1, const Vector3d& u1, const Vector3d& v1,
                      const Vector3d& o2, const Vector3d& u2, const Vector3d& v2, int n) {
  std::vector<double> x, w;
  gaussLegendre01(n, x, w);
  const Vector3d n1 = u1.cross(v1), n2 = u2.cross(v2);  // length = area
  double sum = 0.0;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const Vector3d p = o1 + x[i] * u1 + x[j] * v1;
      for (int k = 0; k < n; ++k) {
        for (int m = 0; m < n; ++m) {
          const Vector3d d = o2 + x[k] * u2 + x[m] * v2 - p;
          const double r2 = d.squaredNorm();
          sum += w[i] * w[j] * w[k] * w[m] * n1.dot(d) * (-n2.dot(d)) / (r2 * r2);
        }
      }
    }
  }
  return sum / (std::numbers::pi * n1.norm());
}

TEST(PolygonFormFactorTest, AgreesWithDirectQuadratureForWellSeparatedSkewPair) {
  const Vector3d o1(0, 0, 0), u1(1.0, 0.2, 0.0), v1(0.3, 0.8, 0.0);  // normal +z
  const Vector3d o2(0.5, 0.2, 2.0), u2(0.1, 0.9, 0.3), v2(0.8, 0.0, -0.2);
  ASSERT_LT(u2.cross(v2).z(), 0.0);  // the second parallelogram faces down
  const double contour =
      polygonToPolygonFormFactor(parallelogram(o1, u1, v1), parallelogram(o2, u2, v2));
  const double direct = areaQuadrature(o1, u1, v1, o2, u2, v2, 20);
  expectRelNear(contour, direct, kRelTol);
}

// Far apart (distance about 25 times the size) the edge terms nearly cancel; the result must
// still carry nearly full precision.
TEST(PolygonFormFactorTest, AgreesWithDirectQuadratureForDistantSkewPair) {
  const Vector3d o1(0, 0, 0), u1(1.0, 0.2, 0.0), v1(0.3, 0.8, 0.0);  // normal +z
  const Vector3d o2(3.0, -2.0, 25.0), u2(0.1, 0.9, 0.3), v2(0.8, 0.0, -0.2);
  ASSERT_LT(u2.cross(v2).z(), 0.0);  // the second parallelogram faces down
  const double contour =
      polygonToPolygonFormFactor(parallelogram(o1, u1, v1), parallelogram(o2, u2, v2));
  const double direct = areaQuadrature(o1, u1, v1, o2, u2, v2, 12);
  expectRelNear(contour, direct, 1e-12);
}

}  // namespace
}  // namespace radquad::analytic
