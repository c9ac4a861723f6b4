// Cost of the ellipsoid narrow phase (docs/ellipsoid-contact.md, "Cost"): ns per
// ellipsoid-ellipsoid contact test, cold and warm started, against ns per sphere-sphere test,
// measured in the same run on near-touching pairs 1-2.5 mm in size, 1-2 m from the origin.
//   bench_ellipsoid_contact [pairs=20000] [repeats=20]
#include <Eigen/Geometry>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <vector>

#include "dem/contact/ellipsoid_geometry.h"

using namespace upgrain::dem;

namespace {

Vec3 random_unit(std::mt19937_64& rng) {
  std::normal_distribution<double> g;
  return Vec3(g(rng), g(rng), g(rng)).normalized();
}

// Near-touching pairs: body 2 placed along a random normal so that f(n) = delta there (the
// test suite's construction, in double), delta log-uniform in 1e-6 c .. 1e-2 c.
std::vector<std::pair<Ellipsoid, Ellipsoid>> make_pairs(const Vec3& ratio, int count, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> size(1e-3, 2.5e-3), far(1.0, 2.0), exponent(-6.0, -2.0);
  std::normal_distribution<double> g;
  std::vector<std::pair<Ellipsoid, Ellipsoid>> pairs;
  for (int i = 0; i < count; ++i) {
    Ellipsoid e1, e2;
    e1.semi_axes = ratio * size(rng);
    e2.semi_axes = ratio * size(rng);
    e1.orientation = Eigen::Quaterniond(g(rng), g(rng), g(rng), g(rng)).normalized();
    e2.orientation = Eigen::Quaterniond(g(rng), g(rng), g(rng), g(rng)).normalized();
    e1.centre = random_unit(rng) * far(rng);
    const Vec3 n = random_unit(rng);
    const Mat3 r1 = e1.orientation.toRotationMatrix(), r2 = e2.orientation.toRotationMatrix();
    const Mat3 m1 = r1 * e1.semi_axes.cwiseAbs2().asDiagonal() * r1.transpose();
    const Mat3 m2 = r2 * e2.semi_axes.cwiseAbs2().asDiagonal() * r2.transpose();
    const double delta = std::pow(10.0, exponent(rng)) * std::min(e1.semi_axes.z(), e2.semi_axes.z());
    e2.centre = e1.centre + m1 * n / std::sqrt(n.dot(m1 * n)) - delta * n + m2 * n / std::sqrt(n.dot(m2 * n));
    pairs.emplace_back(e1, e2);
  }
  return pairs;
}

template <class F>
double ns_per_call(int calls, int repeats, F&& body) {
  double best = 1e300;
  for (int r = 0; r < repeats; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    body();
    const auto t1 = std::chrono::steady_clock::now();
    best = std::min(best, std::chrono::duration<double, std::nano>(t1 - t0).count() / calls);
  }
  return best;  // the fastest repeat: least disturbed by the other jobs on the machine
}

}  // namespace

int main(int argc, char** argv) {
  const int count = argc > 1 ? std::atoi(argv[1]) : 20000;
  const int repeats = argc > 2 ? std::atoi(argv[2]) : 20;
  std::mt19937_64 rng(42);

  // Spheres: the same number of near-touching pairs, radii 1-2.5 mm.
  std::vector<Vec3> c1s, c2s;
  std::vector<double> r1s, r2s;
  std::uniform_real_distribution<double> size(1e-3, 2.5e-3), gap(-1e-3, 1e-3);
  for (int i = 0; i < count; ++i) {
    r1s.push_back(size(rng));
    r2s.push_back(size(rng));
    c1s.push_back(random_unit(rng) * 1.5);
    c2s.push_back(c1s.back() + random_unit(rng) * (r1s.back() + r2s.back()) * (1.0 + gap(rng)));
  }
  double sink = 0.0;
  // The sphere-sphere overlap test of a DEM force loop: squared distance against (r1 + r2)^2,
  // then the depth and normal for contacts.
  const double sphere_test = ns_per_call(count, repeats, [&] {
    for (int i = 0; i < count; ++i) {
      const Vec3 d = c2s[i] - c1s[i];
      const double reach = r1s[i] + r2s[i];
      const double dist2 = d.squaredNorm();
      if (dist2 < reach * reach) {
        const double dist = std::sqrt(dist2);
        sink += reach - dist + d.x() / dist;
      }
    }
  });
  const double sphere_full = ns_per_call(count, repeats, [&] {
    for (int i = 0; i < count; ++i) sink += sphere_sphere_contact(c1s[i], r1s[i], c2s[i], r2s[i]).depth;
  });
  std::printf("sphere-sphere overlap test       %8.1f ns\n", sphere_test);
  std::printf("sphere-sphere full geometry      %8.1f ns\n", sphere_full);

  const struct {
    const char* name;
    Vec3 ratio;
  } shapes[] = {
      {"1:0.8:0.6", Vec3(1, 0.8, 0.6)}, {"1:0.2:0.1", Vec3(1, 0.2, 0.1)}, {"1:1:0.1", Vec3(1, 1, 0.1)}};
  std::printf(
      "\n| shape | cold (ns) | warm (ns) | rejection test (ns) | cold / sphere | warm / sphere | "
      "mean warm iterations | fallbacks |\n|---|---|---|---|---|---|---|---|\n");
  for (const auto& shape : shapes) {
    auto pairs = make_pairs(shape.ratio, count, rng);
    std::vector<Vec3> normals(count);
    ContactSolverStats cold_stats, warm_stats;
    const double cold = ns_per_call(count, repeats, [&] {
      for (int i = 0; i < count; ++i) {
        const ContactGeometry g = ellipsoid_contact(pairs[i].first, pairs[i].second, cold_stats);
        normals[i] = g.normal;
        sink += g.depth;
      }
    });
    // One step later: body 2 moved by 1e-4 c, both turned by 1e-4 rad; warm start from the
    // previous normal.
    for (auto& [e1, e2] : pairs) {
      e2.centre += random_unit(rng) * 1e-4 * e1.semi_axes.z();
      e1.orientation = (Eigen::AngleAxisd(1e-4, random_unit(rng)) * e1.orientation).normalized();
      e2.orientation = (Eigen::AngleAxisd(1e-4, random_unit(rng)) * e2.orientation).normalized();
    }
    std::int64_t iterations_before = 0;
    const double warm = ns_per_call(count, repeats, [&] {
      iterations_before = warm_stats.newton_iterations;
      for (int i = 0; i < count; ++i) {
        const ContactGeometry g = ellipsoid_contact(pairs[i].first, pairs[i].second, warm_stats, normals[i]);
        sink += g.depth;
      }
    });
    const double mean_warm_iterations =
        static_cast<double>(warm_stats.newton_iterations - iterations_before) / count;
    const double reject = ns_per_call(count, repeats, [&] {
      for (int i = 0; i < count; ++i) sink += proven_separated(pairs[i].first, pairs[i].second);
    });
    std::printf("| %s | %.0f | %.0f | %.0f | %.0f | %.0f | %.2f | %lld |\n", shape.name, cold, warm, reject,
                cold / sphere_test, warm / sphere_test, mean_warm_iterations,
                static_cast<long long>(cold_stats.fallbacks + warm_stats.fallbacks));
  }
  std::printf("\n(checksum %g)\n", sink);
  return 0;
}
