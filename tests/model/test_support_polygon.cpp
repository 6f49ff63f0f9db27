// Convex polygons as half-planes (eq. 2.61–2.64, with the sign erratum): inside points satisfy
// A p ≤ b, outside points violate a row, either vertex order gives the same half-planes, and
// non-convex or degenerate vertex lists are rejected with a reason.

#include "walkgen/model/support_polygon.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include "walkgen/core/math.hpp"

namespace {

using Polygon = Eigen::Matrix<double, Eigen::Dynamic, 2>;

Polygon pentagon() {
  Polygon p(5, 2);
  p << -0.28, 0.2, -0.20, 0.3, 0.00, 0.4, 0.20, 0.3, 0.28, 0.2;  // HRP-2 left foot hull
  return p;
}

TEST(SupportPolygon, HalfPlanesContainTheInsideAndExcludeTheOutside) {
  for (bool reversed : {false, true}) {
    Polygon p = pentagon();
    if (reversed) p = p.colwise().reverse().eval();
    Eigen::Matrix<double, 5, 2> A;
    Eigen::Matrix<double, 5, 1> b;
    walkgen::polygon_halfplanes(p, A, b);
    // Every vertex lies on two edges and inside the rest.
    for (int v = 0; v < 5; ++v) {
      const Eigen::Vector2d x = p.row(v).transpose();
      EXPECT_LE((A * x - b).maxCoeff(), 1e-12);
      EXPECT_EQ(((A * x - b).array().abs() < 1e-12).count(), 2);
    }
    const Eigen::Vector2d centroid(0.0, 0.28), above(0.0, 0.41), left(-0.29, 0.25), below(0, 0.19);
    EXPECT_LT((A * centroid - b).maxCoeff(), 0.0);
    EXPECT_GT((A * above - b).maxCoeff(), 0.0);
    EXPECT_GT((A * left - b).maxCoeff(), 0.0);
    EXPECT_GT((A * below - b).maxCoeff(), 0.0);
  }
}

TEST(SupportPolygon, RejectsNonConvexAndDegeneratePolygons) {
  Polygon dent(5, 2);  // a notch at the top: not convex
  dent << -0.28, 0.2, -0.20, 0.3, 0.00, 0.25, 0.20, 0.3, 0.28, 0.2;
  EXPECT_STREQ(walkgen::convex_polygon_problem(dent), "the polygon is not convex");

  Polygon star(5, 2);  // a pentagram: turns one way only, but winds twice
  for (int i = 0; i < 5; ++i) {
    const double a = 2 * walkgen::kPi * (2 * i) / 5;
    star.row(i) << std::cos(a), std::sin(a);
  }
  EXPECT_STREQ(walkgen::convex_polygon_problem(star),
               "the polygon winds more than once (self-intersecting)");

  Polygon two(2, 2);
  two << 0, 0, 1, 0;
  EXPECT_NE(walkgen::convex_polygon_problem(two), nullptr);

  Polygon collinear(3, 2);
  collinear << 0, 0, 1, 0, 2, 0;
  EXPECT_NE(walkgen::convex_polygon_problem(collinear), nullptr);

  Polygon nan = pentagon();
  nan(2, 1) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(walkgen::convex_polygon_problem(nan), nullptr);

  Eigen::Matrix<double, 5, 2> A;
  Eigen::Matrix<double, 5, 1> b;
  try {
    walkgen::polygon_halfplanes(dent, A, b);
    FAIL() << "no exception";
  } catch (const walkgen::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("expected the vertices of a convex polygon, got 5 "
                                         "vertices: the polygon is not convex"),
              std::string::npos)
        << e.what();
  }
}

TEST(SupportPolygon, WrongOutputSizesThrow) {
  Eigen::Matrix<double, 4, 2> A;
  Eigen::Matrix<double, 4, 1> b;
  Polygon p = pentagon();
  EXPECT_THROW(walkgen::polygon_halfplanes(p, A, b), walkgen::invalid_argument);
}

}  // namespace
