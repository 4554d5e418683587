// Cross-sections and the neck on surfaces of revolution with a known neck: a
// sphere on a neck of given radius, spherical caps with and without an overhang,
// planes that have no closed section around the axis, and a budded closed vesicle
// on an oblique axis.

#include <membrane/analysis/cross_sections.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

using namespace Membrane;
using dealii::Point;

namespace
{
  const Point<2> axis(0.5, 0.5); // the centre of the unit period, as on the patch

  /// Quads of the surface of revolution of the profile (r_i, z_i) about the axis,
  /// with `angles` cells around.
  std::vector<SurfaceQuad> revolve(const std::vector<std::pair<double, double>> &profile, const unsigned int angles)
  {
    std::vector<SurfaceQuad> quads;
    const auto point = [&](const std::pair<double, double> &rz, const unsigned int k) {
      const double theta = 2 * M_PI * k / angles;
      return Point<3>(axis[0] + rz.first * std::cos(theta), axis[1] + rz.first * std::sin(theta), rz.second);
    };
    for (std::size_t i = 0; i + 1 < profile.size(); ++i)
      for (unsigned int k = 0; k < angles; ++k)
        quads.push_back({{point(profile[i], k), point(profile[i], k + 1), point(profile[i + 1], k),
                          point(profile[i + 1], k + 1)}});
    return quads;
  }

  /// The flat membrane from r = 0.45 in to r = r_end at z = 0.
  void add_plane(std::vector<std::pair<double, double>> &profile, const double r_end)
  {
    for (int i = 0; i <= 20; ++i)
      profile.emplace_back(0.45 + (r_end - 0.45) * i / 20.0, 0.0);
  }

  /// The sphere of radius R centred on the axis at height zc, from the angle psi0
  /// (measured from its bottom) to its top.
  void add_sphere(std::vector<std::pair<double, double>> &profile, const double R, const double zc, const double psi0)
  {
    for (int i = 1; i <= 200; ++i)
      {
        const double psi = psi0 + (M_PI - psi0) * i / 200.0;
        profile.emplace_back(R * std::sin(psi), zc - R * std::cos(psi));
      }
  }
} // namespace

// A sphere of radius 0.25 on a neck of radius 0.1: the membrane rises through a
// quarter-circle fillet (radius 0.05) to a vertical tangent at the neck, where the
// sphere starts. The neck is found at its height with its radius, the bud radius is
// the sphere's, and the ratio is their quotient, each within 3 %.
TEST(CrossSections, SphereOnANeckOfKnownRadius)
{
  const double r_neck = 0.1, R = 0.25, a = 0.05;
  std::vector<std::pair<double, double>> profile;
  add_plane(profile, r_neck + a);
  for (int i = 1; i <= 40; ++i)
    {
      const double phi = 0.5 * M_PI * i / 40;
      profile.emplace_back(r_neck + a - a * std::sin(phi), a - a * std::cos(phi));
    }
  const double zc = a + std::sqrt(R * R - r_neck * r_neck);
  add_sphere(profile, R, zc, std::asin(r_neck / R));
  const auto quads = revolve(profile, 128);

  const Neck neck = find_neck(quads, axis, 0.0, zc + R, 1.0);
  EXPECT_NEAR(neck.radius / r_neck, 1.0, 0.03);
  EXPECT_NEAR(neck.height, a, 0.01);
  EXPECT_NEAR(neck.bud_radius / R, 1.0, 0.03);
  EXPECT_NEAR(neck.ratio / (r_neck / R), 1.0, 0.03);
  // The section through the sphere's centre is a circle of radius R (a 128-gon: within 0.1 %).
  EXPECT_NEAR(section_radius(quads, axis, zc, 1.0) / R, 1.0, 1e-3);
}

// Spherical caps of radius 0.2 on the plane. A cap beyond the hemisphere (135
// degrees from the apex) has its neck at the rim, R sin 45, below its equator, so
// the ratio is sin 45 = 0.707 (within 3 %: the lowest section sampled lies just above
// the rim). A cap of 60 degrees only narrows upwards: no neck, ratio 1.
TEST(CrossSections, SphericalCaps)
{
  const double R = 0.2;
  for (const double opening : {135.0, 60.0})
    {
      const double psi0 = M_PI - opening * M_PI / 180; // rim angle from the sphere's bottom
      const double rim = R * std::sin(psi0), zc = R * std::cos(psi0);
      std::vector<std::pair<double, double>> profile;
      add_plane(profile, rim);
      add_sphere(profile, R, zc, psi0);
      const Neck neck = find_neck(revolve(profile, 128), axis, 0.0, zc + R, 1.0);
      if (opening > 90)
        {
          EXPECT_NEAR(neck.ratio / std::sin(M_PI / 4), 1.0, 0.03);
          EXPECT_NEAR(neck.radius / rim, 1.0, 0.03);
          EXPECT_NEAR(neck.bud_radius / R, 1.0, 0.01);
        }
      else
        EXPECT_EQ(neck.ratio, 1.0);
    }
}

// No closed section around the axis: a level the surface does not reach, and a
// sphere beside the axis (its sections do not enclose it). The innermost section is
// chosen when there are two: concentric cylinders give the inner one.
TEST(CrossSections, OnlyClosedSectionsAroundTheAxisCount)
{
  std::vector<std::pair<double, double>> plane;
  add_plane(plane, 0.0);
  EXPECT_EQ(section_radius(revolve(plane, 64), axis, 0.1, 1.0), 0.0);

  std::vector<std::pair<double, double>> sphere;
  add_sphere(sphere, 0.1, 0.0, 0.0);
  auto beside = revolve(sphere, 64);
  for (auto &quad : beside)
    for (auto &p : quad)
      p[0] += 0.2;
  EXPECT_EQ(section_radius(beside, axis, 0.0, 1.0), 0.0);

  std::vector<std::pair<double, double>> inner = {{0.1, -1}, {0.1, 1}}, outer = {{0.3, -1}, {0.3, 1}};
  auto cylinders = revolve(inner, 256);
  for (const auto &quad : revolve(outer, 256))
    cylinders.push_back(quad);
  EXPECT_NEAR(section_radius(cylinders, axis, 0.0, 1.0), 0.1, 1e-4);
}

// A closed vesicle with a bud, as a vesicle run measures it: a mother sphere of radius 1,
// a quarter-circle fillet (radius 0.05) from its top to a neck of radius 0.1, and a bud
// sphere of radius 0.35 above, turned to an oblique axis and shifted. The sections normal
// to that axis, from the mother's centre to the bud's top, find the neck and the bud
// within 3 %; a sphere alone has no neck.
TEST(CrossSections, NeckAlongAnObliqueAxisOfAClosedVesicle)
{
  const double r_neck = 0.1, R_bud = 0.35, a = 0.05, R_mother = 1.0;
  std::vector<std::pair<double, double>> profile;
  const double z_fillet = std::sqrt(R_mother * R_mother - (r_neck + a) * (r_neck + a)); // where the fillet starts
  for (int i = 0; i <= 200; ++i)
    {
      const double psi = (M_PI - std::asin((r_neck + a) / R_mother)) * i / 200.0;
      profile.emplace_back(R_mother * std::sin(psi), -R_mother * std::cos(psi));
    }
  for (int i = 1; i <= 40; ++i)
    {
      const double t = 0.5 * M_PI * i / 40;
      profile.emplace_back(r_neck + a - a * std::sin(t), z_fillet + a - a * std::cos(t));
    }
  const double zc = z_fillet + a + std::sqrt(R_bud * R_bud - r_neck * r_neck);
  add_sphere(profile, R_bud, zc, std::asin(r_neck / R_bud));
  auto quads = revolve(profile, 128);

  // Turn about the y axis by 50 degrees, then about z by 30, and shift.
  const double       b = 50 * M_PI / 180, c = 30 * M_PI / 180;
  const auto         turn = [&](const dealii::Tensor<1, 3> &v) {
    const dealii::Tensor<1, 3> w({std::cos(b) * v[0] + std::sin(b) * v[2], v[1], -std::sin(b) * v[0] + std::cos(b) * v[2]});
    return dealii::Tensor<1, 3>({std::cos(c) * w[0] - std::sin(c) * w[1], std::sin(c) * w[0] + std::cos(c) * w[1], w[2]});
  };
  const Point<3> origin(0.3, -0.2, 0.7);
  for (auto &quad : quads)
    for (auto &p : quad)
      p = origin + turn(p - Point<3>(axis[0], axis[1], 0.0));
  const dealii::Tensor<1, 3> direction = turn(dealii::Tensor<1, 3>({0., 0., 1.}));

  const Neck neck = find_neck_along(quads, origin, direction, 0.0, zc + R_bud);
  EXPECT_NEAR(neck.radius / r_neck, 1.0, 0.03);
  EXPECT_NEAR(neck.height, z_fillet + a, 0.02);
  EXPECT_NEAR(neck.bud_radius / R_bud, 1.0, 0.03);
  EXPECT_NEAR(neck.ratio / (r_neck / R_bud), 1.0, 0.03);

  std::vector<std::pair<double, double>> sphere;
  add_sphere(sphere, R_mother, 0.0, 0.0);
  auto ball = revolve(sphere, 128);
  for (auto &quad : ball)
    for (auto &p : quad)
      p = origin + turn(p - Point<3>(axis[0], axis[1], 0.0));
  EXPECT_EQ(find_neck_along(ball, origin, direction, 0.0, R_mother).ratio, 1.0);
}
