// The batch gather (include/vplkit/rsm_gather_batch.hpp) against the scalar gather_rsm it batches:
// every receiver of a batch, in float and double, with and without Alg. 6, on a synthetic RSM with
// an occluding block, including receivers the pattern skips (behind the light, off the map) and a
// batch that does not fill its last lane block.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

#include <vplkit/rsm_gather_batch.hpp>

#include "tests/kernels/synthetic_rsm.hpp"

using namespace vplkit;
using namespace vplkit::testing;

TEST_CASE("hash_uint32_lanes equals hash_uint32") {
  // 2^20 values spread over the whole range (a multiplicative stride), every shift among them.
  int differences = 0;
  for (std::uint32_t top = 0; top < 16u; ++top)
    for (std::uint32_t low = 0; low < 65536u; ++low) {
      const std::uint32_t v = top * 268435456u + low * 2654435761u;
      differences += hash_uint32_lanes(v) != hash_uint32(v) ? 1 : 0;
      differences += hash_combine_lanes(v, low) != hash_combine(v, low) ? 1 : 0;
    }
  CHECK(differences == 0);
}

namespace {

template <typename T>
std::vector<gather_receiver<T>> batch_receivers() {
  std::vector<gather_receiver<T>> receivers;
  // 62 receivers (not a multiple of the lane count): under and beside the block, facing up, down
  // and sideways, on pixels that differ, plus one behind the light and two off the map (one
  // within the pattern's reach, one beyond it).
  for (int i = 0; i < 58; ++i) {
    const double x = -1.5 + 0.05 * i, z = 0.5 - 0.017 * i, y = 0.02 + 0.01 * (i % 5);
    const glm::dvec3 normal = i % 3 == 0 ? glm::dvec3(0, 1, 0) : i % 3 == 1 ? glm::dvec3(0, -1, 0) : glm::normalize(glm::dvec3(1, 0.3, 0));
    const gather_receiver<double> r = receiver_at(glm::dvec3(x, y, z), glm::uvec2(3u * static_cast<unsigned>(i), 7u + static_cast<unsigned>(i) / 4u), normal);
    receivers.push_back({glm::vec<3, T>(r.position), glm::vec<3, T>(r.normal), glm::vec<2, T>(r.rsm_coordinate), r.pixel});
  }
  for (const glm::dvec3 p : {glm::dvec3(0.1, 11.0, 0.0), glm::dvec3(2.8, 0.1, 0.0), glm::dvec3(9.0, 0.1, 0.0)}) {  // 9.0: beyond reach
    const gather_receiver<double> r = receiver_at(p, glm::uvec2(1, 2), glm::dvec3(0, 1, 0));
    receivers.push_back({glm::vec<3, T>(r.position), glm::vec<3, T>(r.normal), glm::vec<2, T>(r.rsm_coordinate), r.pixel});
  }
  // Far off the map (its projection ~1e12 texels away): skipped, and never converted to an int.
  receivers.push_back({glm::vec<3, T>(T(1e10), T(0), T(-10)), glm::vec<3, T>(0, 0, 1), glm::vec<2, T>(T(1e12), T(1e12)), glm::uvec2(4, 5)});
  return receivers;
}

// The synthetic RSM with an occluding block, the settings and the receivers every comparison below uses.
template <typename T>
struct batch_fixture {
  synthetic_rsm block;
  rsm_gather_settings<T> settings;
  std::vector<gather_receiver<T>> receivers = batch_receivers<T>();
  rsm_plane_storage<T> planes;
  batch_fixture() {
    block.block_x0 = 0.3, block.block_x1 = 0.8, block.block_height = 0.6;
    radial_pattern_settings<T> radial;
    radial.paths = 20;
    radial.samples_per_path = 15;
    radial.max_radius = T(120);
    settings.radial = make_radial_pattern_constants(radial);
    settings.slots = make_elevation_slots<T>(8);
    settings.rsm_size = glm::ivec2(rsm_size);
    planes = make_rsm_planes<T>(settings.rsm_size, [this](glm::ivec2 t) { return fetch(t); });
  }
  rsm_texel<T> fetch(glm::ivec2 t) const {
    const rsm_texel<double> d = block(t);
    // Empty texels where x > 2 (the off-map receiver within reach sees the edge of the lit area).
    const double empty = d.position.x > 2.0 ? 1.0 : 0.0;
    return rsm_texel<T>{glm::vec<3, T>(d.position.x, d.position.y, empty > 0.0 ? 1.0 : d.position.z), glm::vec<3, T>(d.normal), glm::vec<3, T>(d.flux)};
  }
  template <rsm_visibility V>
  std::vector<glm::vec<3, T>> batch(batch_isa isa) const {
    std::vector<glm::vec<3, T>> out(receivers.size(), glm::vec<3, T>(T(-1)));
    gather_rsm_batch<V>(receivers.data(), receivers.size(), planes.view(), settings, out.data(), isa);
    return out;
  }
};

template <typename T, rsm_visibility V>
void check_batch_equals_scalar(batch_isa isa) {
  const batch_fixture<T> f;
  const auto fetch = [&](glm::ivec2 t) { return f.fetch(t); };
  const rsm_gather_settings<T>& settings = f.settings;
  const std::vector<gather_receiver<T>>& receivers = f.receivers;
  const std::vector<glm::vec<3, T>> batch = f.template batch<V>(isa);
  // gather_rsm_batch repeats gather_rsm's operations in its order (with -ffp-contract=off, no
  // fusing on either side), so the sums are the same floats; the bound allowed is the parity
  // tests' for a gather of N terms, 2 N 2^-24 + 2e-6 relative (test_parity_rsm_gather.cpp), so a
  // compiler that reassociates stays within what the GLSL twin is held to.
  const double relative = 2.0 * settings.radial.paths * settings.radial.samples_per_path * 0x1p-24 + 2e-6;
  int lit = 0, occluded_somewhere = 0;
  double worst = 0.0;
  for (std::size_t i = 0; i < receivers.size(); ++i) {
    const glm::vec<3, T> scalar = gather_rsm<rsm_pattern::radial, V>(receivers[i], fetch, settings);
    CAPTURE(i);
    for (int c = 0; c < 3; ++c) {
      REQUIRE(std::isfinite(static_cast<double>(batch[i][c])));
      const double difference = std::abs(static_cast<double>(batch[i][c]) - static_cast<double>(scalar[c]));
      worst = std::max(worst, difference / std::max(1e-30, std::abs(static_cast<double>(scalar[c]))));
      CHECK(difference <= relative * std::abs(static_cast<double>(scalar[c])));
    }
    lit += scalar.x > T(0) ? 1 : 0;
    if constexpr (V == rsm_visibility::alg6)
      occluded_somewhere += gather_rsm<rsm_pattern::radial, rsm_visibility::none>(receivers[i], fetch, settings).x > scalar.x ? 1 : 0;
  }
  MESSAGE(lit << " of " << receivers.size() << " receivers lit; worst relative difference " << worst);
  // The comparison means something: half the receivers are lit (those facing down see no floor), and with Alg. 6 some lose light to the block.
  CHECK(lit > 30);
  if constexpr (V == rsm_visibility::alg6) CHECK(occluded_somewhere > 5);
  // The receivers the pattern skips get nothing, as from gather_rsm.
  CHECK(batch[58] == glm::vec<3, T>(T(0)));
  CHECK(batch[60] == glm::vec<3, T>(T(0)));
  CHECK(batch[61] == glm::vec<3, T>(T(0)));
}

}  // namespace

namespace {

// check_batch_equals_scalar for both instantiations (batch_isa.hpp) where the CPU runs AVX2, the
// portable one alone elsewhere.
template <typename T, rsm_visibility V>
void check_every_isa_equals_scalar() {
  for (const batch_isa isa : {batch_isa::portable, batch_isa::avx2}) {
    if (!batch_isa_supported(isa)) {
      MESSAGE("this CPU or build has no AVX2: only the portable batch gather is compared");
      continue;
    }
    CAPTURE(static_cast<int>(isa));
    check_batch_equals_scalar<T, V>(isa);
  }
}

}  // namespace

TEST_CASE("gather_rsm_batch equals gather_rsm for every receiver of a batch") {
  SUBCASE("float, Alg. 6") { check_every_isa_equals_scalar<float, rsm_visibility::alg6>(); }
  SUBCASE("float, no visibility") { check_every_isa_equals_scalar<float, rsm_visibility::none>(); }
  SUBCASE("double, Alg. 6") { check_every_isa_equals_scalar<double, rsm_visibility::alg6>(); }
}

namespace {

template <typename T, rsm_visibility V>
void check_avx2_equals_portable() {
  const batch_fixture<T> f;
  const std::vector<glm::vec<3, T>> portable = f.template batch<V>(batch_isa::portable);
  const std::vector<glm::vec<3, T>> avx2 = f.template batch<V>(batch_isa::avx2);
  int nonzero = 0;
  for (std::size_t i = 0; i < portable.size(); ++i) {
    CAPTURE(i);
    // Bit for bit: the same source and operations (AVX2 has no FMA, -ffp-contract=off), only
    // more lanes per instruction; a difference means one path computes something else.
    for (int c = 0; c < 3; ++c) CHECK(std::memcmp(&portable[i][c], &avx2[i][c], sizeof(T)) == 0);
    nonzero += portable[i].x > T(0) ? 1 : 0;
  }
  CHECK(nonzero > 30);  // the receivers are lit: the comparison is of gathered light, not zeros
}

}  // namespace

TEST_CASE("gather_rsm_batch's AVX2 path equals its portable path bit for bit") {
  if (!batch_isa_supported(batch_isa::avx2)) {
    MESSAGE("this CPU or build has no AVX2: nothing to compare (the portable path is compared with gather_rsm above)");
    return;
  }
  CHECK(best_batch_isa() == batch_isa::avx2);
  SUBCASE("float, Alg. 6") { check_avx2_equals_portable<float, rsm_visibility::alg6>(); }
  SUBCASE("float, no visibility") { check_avx2_equals_portable<float, rsm_visibility::none>(); }
  SUBCASE("double, Alg. 6") { check_avx2_equals_portable<double, rsm_visibility::alg6>(); }
  SUBCASE("double, no visibility") { check_avx2_equals_portable<double, rsm_visibility::none>(); }
}
