#include "dem/scene/grain_shape.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <iterator>
#include <numbers>
#include <numeric>
#include <sstream>

#include "dem/core/error.h"
#include "dem/shape/grain_shapes.h"

namespace upgrain::dem {

namespace {

// The kind whose row is named `name`, if any.
bool kind_named(const std::string& name, ShapeKind& kind) {
  bool found = false;
  shapes::for_each_shape([&]<class S>() {
    if (name == S::name) {
      kind = S::kind;
      found = true;
    }
  });
  return found;
}

std::string ostream_number(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

}  // namespace

std::size_t ratio_count(ShapeKind k) {
  return shapes::visit_shape(k, []<class S>() { return std::size(S::ratios); });
}

std::span<const double> GrainShape::dimensions() const { return {ratios.data(), ratio_count(kind)}; }

GrainShape grain_shape(ShapeKind k, std::span<const double> ratios, double number_fraction) {
  GrainShape s;
  s.number_fraction = number_fraction;
  if (std::all_of(ratios.begin(), ratios.end(), [](double r) { return r == 1.0; })) return s;
  s.kind = k;
  std::copy(ratios.begin(), ratios.end(), s.ratios.begin());
  return s;
}

GrainShape ellipsoid_grain(double b_over_a, double c_over_a, double number_fraction) {
  const std::array<double, 2> r{b_over_a, c_over_a};
  return grain_shape(ShapeKind::ellipsoid, r, number_fraction);
}

GrainShape read_grain_shape(const std::string& item) {
  const auto at = item.find('@');
  std::istringstream words(item.substr(0, at));
  std::string first;
  words >> first;
  ShapeKind kind = ShapeKind::ellipsoid;
  std::string numbers = first;
  const bool named = !first.empty() && std::isalpha(static_cast<unsigned char>(first[0]));
  if (named && !kind_named(first, kind)) {
    std::string known;
    shapes::for_each_shape([&]<class S>() {
      if (!known.empty()) known += ", ";
      known += S::name;
    });
    throw Error("cannot read the shape '" + item + "': no shape is named '" + first +
                "' (the shapes: " + known + ")");
  }
  if (named) words >> numbers;
  std::string rest;
  bool ok = !numbers.empty() && !(words >> rest);
  for (char& c : numbers)
    if (c == ':') c = ' ';
  std::istringstream r(numbers);
  double a = 0.0;
  std::array<double, kMaxShapeRatios> ratios{};
  const std::size_t count = ratio_count(kind);
  ok = ok && static_cast<bool>(r >> a) && a > 0.0;
  for (std::size_t k = 0; ok && k < count; ++k) ok = static_cast<bool>(r >> ratios[k]);
  ok = ok && !(r >> rest);
  double fraction = 1.0;
  if (ok && at != std::string::npos) {
    std::istringstream f(item.substr(at + 1));
    ok = static_cast<bool>(f >> fraction) && !(f >> rest);
  }
  if (!ok)
    throw Error("cannot read the shape '" + item +
                "'; write aspect ratios 'a:b:c' with an optional '@fraction', separated by commas, "
                "e.g. '1:0.8:0.6, 1:0.6:0.4@2'");
  // Ratios to a (the dimensions may be given in any unit, e.g. 10:8:6).
  for (std::size_t k = 0; k < count; ++k) ratios[k] /= a;
  return grain_shape(kind, std::span<const double>(ratios.data(), count), fraction);
}

std::string format_grain_shape(const GrainShape& s, const std::function<std::string(double)>& number) {
  // The sphere is written as the ellipsoid of equal axes, and the ellipsoid without its name:
  // the mix's text of every scene before other shapes.
  if (s.is_sphere()) return "1:1:1";
  std::string text;
  if (s.kind != ShapeKind::ellipsoid) {
    text = shapes::visit_shape(s.kind, []<class S>() { return std::string(S::name); });
    text += ' ';
  }
  text += '1';
  for (const double r : s.dimensions()) {
    text += ':';
    text += number(r);
  }
  return text;
}

void validate_shapes(const std::vector<GrainShape>& shapes) {
  for (std::size_t k = 0; k < shapes.size(); ++k) {
    const GrainShape& s = shapes[k];
    const bool valid = shapes::visit_shape(s.kind, [&]<class S>() { return S::valid(s.dimensions()); });
    if (!valid || !(s.number_fraction > 0.0 && std::isfinite(s.number_fraction))) {
      const std::string rule = shapes::visit_shape(s.kind, []<class S>() { return std::string(S::rule); });
      std::ostringstream m;
      m << "shape " << k + 1 << " (" << format_grain_shape(s, ostream_number) << ", fraction "
        << s.number_fraction << ") needs " << rule << (rule.empty() ? "" : " and ") << "a positive fraction";
      throw Error(m.str());
    }
  }
}

bool has_shapes(const std::vector<GrainShape>& shapes) {
  return std::any_of(shapes.begin(), shapes.end(), [](const GrainShape& s) { return !s.is_sphere(); });
}

std::string shape_nouns(const std::vector<GrainShape>& shapes) {
  std::string nouns;
  shapes::for_each_shape([&]<class S>() {
    if (S::kind == ShapeKind::sphere) return;
    if (std::none_of(shapes.begin(), shapes.end(), [](const GrainShape& s) { return s.kind == S::kind; }))
      return;
    if (!nouns.empty()) nouns += " and ";
    nouns += S::name;
    nouns += 's';
  });
  return nouns;
}

ShapeScales scales(const GrainShape& s) {
  return shapes::visit_shape(s.kind, [&]<class S>() { return S::scales(s.dimensions()); });
}

void add_grain(ParticleStore& p, const GrainShape& s, GlobalId id, double a, double density,
               const Eigen::Quaterniond& orientation, const GrainMotion& motion) {
  shapes::visit_shape(s.kind,
                      [&]<class S>() { S::add(p, id, a, s.dimensions(), density, orientation, motion); });
}

GrainShape grain_shape_of(const ParticleStore& p, std::size_t i) {
  GrainShape s;
  s.kind = p.kind(i);
  shapes::visit_shape(s.kind, [&]<class S>() {
    S::ratios_of(p, i, std::span<double>(s.ratios.data(), std::size(S::ratios)));
  });
  return s;
}

std::vector<int> assign_shapes(const std::vector<GrainShape>& shapes, long n, std::mt19937_64& rng) {
  std::vector<int> index(static_cast<std::size_t>(n), 0);
  if (shapes.size() < 2) return index;
  double total = 0.0;
  for (const GrainShape& s : shapes) total += s.number_fraction;
  // Largest remainder: floor of each share, the rest to the largest fractional parts.
  std::vector<long> count(shapes.size());
  std::vector<std::pair<double, std::size_t>> remainder(shapes.size());
  long given = 0;
  for (std::size_t k = 0; k < shapes.size(); ++k) {
    const double share = n * shapes[k].number_fraction / total;
    count[k] = static_cast<long>(std::floor(share));
    remainder[k] = {share - count[k], k};
    given += count[k];
  }
  std::stable_sort(remainder.begin(), remainder.end(), [](auto& a, auto& b) { return a.first > b.first; });
  for (long r = 0; r < n - given; ++r) ++count[remainder[static_cast<std::size_t>(r)].second];
  std::size_t at = 0;
  for (std::size_t k = 0; k < shapes.size(); ++k)
    for (long c = 0; c < count[k]; ++c) index[at++] = static_cast<int>(k);
  std::shuffle(index.begin(), index.end(), rng);
  return index;
}

Eigen::Quaterniond random_orientation(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double u1 = u(rng), u2 = 2.0 * std::numbers::pi * u(rng), u3 = 2.0 * std::numbers::pi * u(rng);
  const double s1 = std::sqrt(1.0 - u1), s2 = std::sqrt(u1);
  return Eigen::Quaterniond(s2 * std::cos(u3), s1 * std::sin(u2), s1 * std::cos(u2), s2 * std::sin(u3));
}

}  // namespace upgrain::dem
