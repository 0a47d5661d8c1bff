// The grid form of the polygon form factor (include/vplkit/form_factor_grid.hpp) against the
// scalar forms, cell by cell: random receivers and random planar grids, many of them cut by the
// receiver's tangent plane, some wholly below it.
#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include <vplkit/form_factor_grid.hpp>

using namespace vplkit;

namespace {

template <typename T>
struct grid_case {
  glm::vec<3, T> x, n, origin, du, dv;
  int cells_u, cells_v;
};

grid_case<double> random_case(std::mt19937& random) {
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  const auto vec = [&] { return glm::dvec3(uniform(random), uniform(random), uniform(random)); };
  grid_case<double> c;
  c.x = vec() * 0.2;
  c.n = glm::normalize(vec() + glm::dvec3(0, 0, 1e-3));
  c.origin = vec() * 0.6 + glm::dvec3(0, 0, 0.3 * uniform(random));
  c.du = vec() * 0.15;
  c.dv = glm::cross(c.du, vec()) * 2.0;  // a parallelogram grid: planar cells of any shape
  c.cells_u = 1 + static_cast<int>(random() % 9u);
  c.cells_v = 1 + static_cast<int>(random() % 9u);
  return c;
}

}  // namespace

namespace {

void check_grid_equals_polygon(batch_isa isa) {
  std::mt19937 random(42);
  form_factor_grid_scratch<double> scratch_d;
  form_factor_grid_scratch<float> scratch_f;
  int cells = 0, cut = 0, above = 0, below = 0;
  double worst_double = 0.0, worst_float = 0.0, worst_scalar_float = 0.0;
  for (int trial = 0; trial < 400; ++trial) {
    const grid_case<double> c = random_case(random);
    CAPTURE(trial);
    const std::size_t count = static_cast<std::size_t>(c.cells_u * c.cells_v);
    std::vector<double> out_d(count, -1.0);
    std::vector<float> out_f(count, -1.0f);
    polygon_form_factor_grid(c.x, c.n, c.origin, c.du, c.dv, c.cells_u, c.cells_v, out_d.data(), scratch_d, isa);
    polygon_form_factor_grid(glm::vec3(c.x), glm::vec3(c.n), glm::vec3(c.origin), glm::vec3(c.du), glm::vec3(c.dv), c.cells_u, c.cells_v, out_f.data(),
                             scratch_f, isa);
    for (int j = 0; j < c.cells_v; ++j)
      for (int i = 0; i < c.cells_u; ++i) {
        // The cell's corners as the grid forms them.
        const auto corner = [&](int a, int b) { return c.origin + c.du * double(a) + c.dv * double(b); };
        const auto corner_f = [&](int a, int b) { return glm::vec3(c.origin) + glm::vec3(c.du) * float(a) + glm::vec3(c.dv) * float(b); };
        const glm::dvec3 c00 = corner(i, j), c10 = corner(i + 1, j), c11 = corner(i + 1, j + 1), c01 = corner(i, j + 1);
        const double exact = polygon_form_factor_exact(c.x, c.n, c00, c10, c11, c01);
        const float scalar_f = polygon_form_factor(glm::vec3(c.x), glm::vec3(c.n), corner_f(i, j), corner_f(i + 1, j), corner_f(i + 1, j + 1), corner_f(i, j + 1));
        const std::size_t k = static_cast<std::size_t>(j * c.cells_u + i);
        const int corners_above = int(glm::dot(c.n, c00 - c.x) >= 0) + int(glm::dot(c.n, c10 - c.x) >= 0) + int(glm::dot(c.n, c11 - c.x) >= 0) +
                                  int(glm::dot(c.n, c01 - c.x) >= 0);
        cut += corners_above > 0 && corners_above < 4 ? 1 : 0;
        above += corners_above == 4 ? 1 : 0;
        below += corners_above == 0 ? 1 : 0;
        ++cells;
        // double: polygon_form_factor's stated bound against the exact form, 2.1e-8, plus rounding.
        CHECK(std::abs(out_d[k] - exact) <= 2.1e-8 + 1e-12);
        if (corners_above == 0) CHECK(out_d[k] == 0.0);
        // float: no further from the exact form than 1e-6 (float's rounding of terms up to pi);
        // measured worst below, with the scalar float form's own for comparison.
        CHECK(std::abs(double(out_f[k]) - exact) <= 1e-6);
        worst_double = std::max(worst_double, std::abs(out_d[k] - exact));
        worst_float = std::max(worst_float, std::abs(double(out_f[k]) - exact));
        worst_scalar_float = std::max(worst_scalar_float, std::abs(double(scalar_f) - exact));
      }
  }
  MESSAGE(cells << " cells (" << above << " above, " << cut << " cut, " << below << " below); worst |F - exact|: double " << worst_double
                << ", float " << worst_float << " (scalar float form " << worst_scalar_float << ")");
  // Every kind of cell was met, many times.
  CHECK(above > 500);
  CHECK(cut > 200);
  CHECK(below > 200);
}

}  // namespace

TEST_CASE("polygon_form_factor_grid equals the polygon form factor of every cell") {
  SUBCASE("portable") { check_grid_equals_polygon(batch_isa::portable); }
  SUBCASE("AVX2") {
    if (batch_isa_supported(batch_isa::avx2)) check_grid_equals_polygon(batch_isa::avx2);
    else MESSAGE("this CPU or build has no AVX2: only the portable grid is compared");
  }
}

TEST_CASE("polygon_form_factor_grid's AVX2 path equals its portable path bit for bit") {
  if (!batch_isa_supported(batch_isa::avx2)) {
    MESSAGE("this CPU or build has no AVX2: nothing to compare");
    return;
  }
  // The random grids of the test above plus 32 x 32 grids (longer rows than a vector), whose
  // horizon crosses them at every angle: the same operations, so the same bits, cell by cell; a
  // difference means one path computed another term or read one it had not computed.
  std::mt19937 random(7);
  form_factor_grid_scratch<float> scratch_portable, scratch_avx2;
  form_factor_grid_scratch<double> scratch_portable_d, scratch_avx2_d;
  int differences = 0, nonzero = 0, cells = 0;
  for (int trial = 0; trial < 300; ++trial) {
    grid_case<double> c = random_case(random);
    if (trial % 2 == 1) {
      c.cells_u = c.cells_v = 32;
      c.du *= 0.25, c.dv *= 0.25;
    }
    const std::size_t count = static_cast<std::size_t>(c.cells_u * c.cells_v);
    std::vector<float> portable(count, -1.0f), avx2(count, -2.0f);
    std::vector<double> portable_d(count, -1.0), avx2_d(count, -2.0);
    const glm::vec3 x(c.x), n(c.n), origin(c.origin), du(c.du), dv(c.dv);
    polygon_form_factor_grid(x, n, origin, du, dv, c.cells_u, c.cells_v, portable.data(), scratch_portable, batch_isa::portable);
    polygon_form_factor_grid(x, n, origin, du, dv, c.cells_u, c.cells_v, avx2.data(), scratch_avx2, batch_isa::avx2);
    polygon_form_factor_grid(c.x, c.n, c.origin, c.du, c.dv, c.cells_u, c.cells_v, portable_d.data(), scratch_portable_d, batch_isa::portable);
    polygon_form_factor_grid(c.x, c.n, c.origin, c.du, c.dv, c.cells_u, c.cells_v, avx2_d.data(), scratch_avx2_d, batch_isa::avx2);
    for (std::size_t k = 0; k < count; ++k) {
      differences += std::memcmp(&portable[k], &avx2[k], sizeof(float)) != 0 ? 1 : 0;
      differences += std::memcmp(&portable_d[k], &avx2_d[k], sizeof(double)) != 0 ? 1 : 0;
      nonzero += portable[k] > 0.0f ? 1 : 0;
      ++cells;
    }
  }
  MESSAGE(cells << " cells, " << nonzero << " with light");
  CHECK(differences == 0);
  CHECK(nonzero > cells / 4);  // the comparison is of form factors, not of zeros
}

TEST_CASE("polygon_form_factor_grid: a grid wholly below the horizon is 0, one wholly above is the sum of its cells") {
  // The rows' spans of corners above the plane are empty, or whole: no edge term is read that was
  // not computed (an empty span runs no loop).
  form_factor_grid_scratch<float> scratch;
  for (const batch_isa isa : {batch_isa::portable, batch_isa::avx2}) {
    if (!batch_isa_supported(isa)) continue;
    CAPTURE(static_cast<int>(isa));
    std::vector<float> out(12 * 9, -1.0f);
    // Below: the grid lies under the receiver's tangent plane (normal +z, grid at z = -1).
    polygon_form_factor_grid(glm::vec3(0), glm::vec3(0, 0, 1), glm::vec3(-0.5f, -0.5f, -1.0f), glm::vec3(0.1f, 0, 0), glm::vec3(0, 0.1f, 0), 12, 9,
                             out.data(), scratch, isa);
    for (const float f : out) CHECK(f == 0.0f);
    // Above, facing the receiver: every cell as polygon_form_factor gives it, and the whole
    // grid's form factor is the sum of its cells' (the grid is one quad cut into cells).
    polygon_form_factor_grid(glm::vec3(0), glm::vec3(0, 0, 1), glm::vec3(-0.6f, -0.45f, 1.0f), glm::vec3(0.1f, 0, 0), glm::vec3(0, 0.1f, 0), 12, 9,
                             out.data(), scratch, isa);
    double sum = 0.0;
    for (int j = 0; j < 9; ++j)
      for (int i = 0; i < 12; ++i) {
        const glm::vec3 c00 = glm::vec3(-0.6f, -0.45f, 1.0f) + glm::vec3(0.1f, 0, 0) * float(i) + glm::vec3(0, 0.1f, 0) * float(j);
        const float expected = polygon_form_factor(glm::vec3(0), glm::vec3(0, 0, 1), c00, c00 + glm::vec3(0.1f, 0, 0), c00 + glm::vec3(0.1f, 0.1f, 0),
                                                   c00 + glm::vec3(0, 0.1f, 0));
        CHECK(out[static_cast<std::size_t>(j * 12 + i)] == doctest::Approx(expected).epsilon(1e-5));
        sum += out[static_cast<std::size_t>(j * 12 + i)];
      }
    const double whole = polygon_form_factor_exact(glm::dvec3(0), glm::dvec3(0, 0, 1), glm::dvec3(-0.6, -0.45, 1.0), glm::dvec3(0.6, -0.45, 1.0),
                                                   glm::dvec3(0.6, 0.45, 1.0), glm::dvec3(-0.6, 0.45, 1.0));
    CHECK(sum == doctest::Approx(whole).epsilon(1e-5));
  }
}

TEST_CASE("polygon_form_factor_grid writes nothing for an empty grid") {
  form_factor_grid_scratch<float> scratch;
  float out = -1.0f;
  polygon_form_factor_grid(glm::vec3(0), glm::vec3(0, 0, 1), glm::vec3(0, 0, 1), glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), 0, 3, &out, scratch);
  CHECK(out == -1.0f);
}
