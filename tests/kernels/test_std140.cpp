// vplkit/std140.hpp: the std140 sizes and offsets of the settings structs, derived here by hand
// from the rules (GL 4.6 core, 7.6.2.2) and checked at compile time; the byte writer checked by
// reading every value back at its offset; the GLSL block text. The offsets against a GL driver's
// are tests/frontend/gl/test_std140_gl.cpp.
#include <doctest/doctest.h>

#include <cstring>
#include <set>

#include <vplkit/std140.hpp>

using namespace vplkit;

// std::array's == is constexpr only from C++20; the kernels' headers are C++17.
template <std::size_t N>
constexpr bool equal(const std::array<std::size_t, N>& a, const std::array<std::size_t, N>& b) {
  for (std::size_t i = 0; i < N; ++i)
    if (a[i] != b[i]) return false;
  return true;
}

// Hand-derived layouts (a vec3 is 16-aligned but 12 long, so a float may follow in its last 4
// bytes; an array's stride is 16; a nested struct starts and ends on 16).
static_assert(std140_size<irradiance_settings<float>> == 16);
static_assert(equal(std140_offsets<spot_light<float>>, std::array<std::size_t, 5>{0, 16, 32, 44, 48}));  // cos_inner in intensity's last word
static_assert(equal(std140_offsets<point_light<float>>, std::array<std::size_t, 2>{0, 16}));
static_assert(std140_size<spot_light<float>> == 64);
static_assert(equal(std140_offsets<directional_light<float>>, std::array<std::size_t, 2>{0, 16}));
static_assert(std140_size<directional_light<float>> == 32);
static_assert(equal(std140_offsets<lightwave_layout_settings<float>>, std::array<std::size_t, 5>{0, 16, 28, 32, 36}));
static_assert(std140_size<lightwave_layout_settings<float>> == 48);
// An int in the last 4 bytes of the vec3, then an int and a float: 24 bytes, rounded up to 32.
static_assert(equal(std140_offsets<lightwave_cone_settings<float>>, std::array<std::size_t, 4>{0, 12, 16, 20}));
static_assert(std140_size<lightwave_cone_settings<float>> == 32);
static_assert(equal(std140_offsets<rsm_unprojection<float>>, std::array<std::size_t, 3>{0, 8, 16}));
static_assert(std140_size<rsm_unprojection<float>> == 32);
static_assert(equal(std140_offsets<disk_pattern_settings<float>>, std::array<std::size_t, 5>{0, 4, 8, 12, 16}));  // bools are 4-byte words
static_assert(std140_size<disk_pattern_settings<float>> == 32);
static_assert(std140_offset(&radial_pattern_constants<float>::seed) == 36);
static_assert(std140_size<radial_pattern_constants<float>> == 48);
// float[15] at 16 with stride 16: 16 + 15 * 16 = 256, not 4 + 15 * 4 = 64 as a C++ struct has it.
static_assert(equal(std140_offsets<elevation_slots<float>>, std::array<std::size_t, 2>{0, 16}));
static_assert(std140_size<elevation_slots<float>> == 256);
// irradiance 16, radial 48 at 16, disk 32 at 64, slots 256 at 96, then ivec2 at 352 and 3 ints.
static_assert(equal(std140_offsets<rsm_gather_settings<float>>, std::array<std::size_t, 8>{0, 16, 64, 96, 352, 360, 364, 368}));
static_assert(std140_size<rsm_gather_settings<float>> == 384);
static_assert(std140_offset(&rsm_gather_settings<float>::perspective) == 368);
static_assert(std140_alignment<rsm_gather_settings<float>> == 16);

// A struct whose description leaves a member out, for std140_offset's refusal.
struct partly_described {
  float listed = 0.0f;
  float unlisted = 0.0f;
};
namespace vplkit {
template <>
struct settings_description<partly_described> {
  static constexpr const char* name = "partly_described";
  static constexpr bool glsl_twin = false;
  static constexpr auto fields() { return std::make_tuple(schema::field(&partly_described::listed, "listed", schema::any_finite(), "", "the one listed")); }
  static setting_problem rules(const partly_described& settings) { return schema::no_rules(settings); }
};
}  // namespace vplkit

namespace {

// Gives every number of `value` its own value, counting up in layout order (a bool: odd or not).
template <typename Value>
void fill(Value& value, int& counter) {
  if constexpr (is_described_v<Value>) {
    for_each_field(value, [&](const field_description&, auto& part) { fill(part, counter); });
  } else if constexpr (std::is_array_v<Value>) {
    for (auto& element : value) fill(element, counter);
  } else if constexpr (std::is_same_v<Value, bool>) {
    value = counter++ % 2 == 1;
  } else if constexpr (std::is_arithmetic_v<Value>) {
    value = static_cast<Value>(counter++);
  } else {
    for (glm::length_t c = 0; c < Value::length(); ++c) fill(value[c], counter);
  }
}

template <typename Word>
Word read_at(const std::byte* bytes, std::size_t offset) {
  Word word;
  std::memcpy(&word, bytes + offset, sizeof word);
  return word;
}

// Reads back what fill() put in, at the offsets std140_fields lists, and checks that the fields
// lie inside the struct without overlapping and that every other byte is 0.
template <typename Settings>
void check_round_trip() {
  Settings settings{};
  int counter = 1;
  fill(settings, counter);
  const auto bytes = std140_bytes(settings);
  REQUIRE(bytes.size() == std140_size<Settings>);
  std::vector<bool> covered(bytes.size(), false);
  int expected = 1;
  for (const std140_field& field : std140_fields<Settings>()) {
    CAPTURE(field.path);
    const std::string& type = field.glsl_type;
    const char last = type.back();
    const std::size_t components = (last >= '2' && last <= '4') ? static_cast<std::size_t>(last - '0') : 1;
    const std::size_t elements = field.array_size == 0 ? 1 : field.array_size;
    for (std::size_t e = 0; e < elements; ++e) {
      for (std::size_t c = 0; c < components; ++c) {
        const std::size_t at = field.offset + e * field.array_stride + c * 4;
        REQUIRE(at + 4 <= bytes.size());
        for (std::size_t b = at; b < at + 4; ++b) {
          CHECK_FALSE(covered[b]);
          covered[b] = true;
        }
        if (type == "bool") CHECK(read_at<std::uint32_t>(bytes.data(), at) == static_cast<std::uint32_t>(expected % 2));
        else if (type == "float" || type.rfind("vec", 0) == 0) CHECK(read_at<float>(bytes.data(), at) == static_cast<float>(expected));
        else if (type == "int" || type.rfind("ivec", 0) == 0) CHECK(read_at<std::int32_t>(bytes.data(), at) == expected);
        else if (type == "uint") CHECK(read_at<std::uint32_t>(bytes.data(), at) == static_cast<std::uint32_t>(expected));
        else FAIL("a GLSL type the test does not read: " << type);
        ++expected;
      }
    }
  }
  CHECK(expected == counter);  // every number fill() set was read back
  for (std::size_t b = 0; b < bytes.size(); ++b)
    if (!covered[b]) CHECK_MESSAGE(bytes[b] == std::byte{0}, "padding byte " << b << " is not 0");
}

}  // namespace

TEST_CASE("std140_bytes puts every field of every settings struct at its std140 offset, padding zeroed") {
  for_each_glsl_twin_type([](const auto& settings) {
    using settings_type = std::decay_t<decltype(settings)>;
    const std::string name = settings_description<settings_type>::name;
    CAPTURE(name);
    check_round_trip<settings_type>();
  });
}

TEST_CASE("std140_bytes of rsm_gather_settings read at hand-derived offsets") {
  rsm_gather_settings<float> settings;
  settings.irradiance.min_distance = 0.25f;
  settings.radial.seed = 0xdeadbeefu;
  settings.radial.max_radius = 48.0f;
  settings.disk.printed_weights = true;
  settings.disk.per_pixel_shift = false;
  settings.slots = make_elevation_slots<float>(9);
  settings.rsm_size = glm::ivec2(640, 480);
  settings.coverage_blocks = 12;
  settings.perspective = 0;
  const auto bytes = std140_bytes(settings);
  CHECK(read_at<float>(bytes.data(), 0) == 0.25f);
  CHECK(read_at<std::uint32_t>(bytes.data(), 16 + 36) == 0xdeadbeefu);
  CHECK(read_at<float>(bytes.data(), 16 + 40) == 48.0f);
  CHECK(read_at<std::uint32_t>(bytes.data(), 64 + 12) == 1u);
  CHECK(read_at<std::uint32_t>(bytes.data(), 64 + 16) == 0u);
  CHECK(read_at<std::int32_t>(bytes.data(), 96) == 9);
  for (int k = 0; k < micro_linear_buffer_max_slots - 1; ++k) {
    CAPTURE(k);
    CHECK(read_at<float>(bytes.data(), 96 + 16 + 16 * static_cast<std::size_t>(k)) == settings.slots.boundary_tangent[k]);
  }
  CHECK(read_at<std::int32_t>(bytes.data(), 352) == 640);
  CHECK(read_at<std::int32_t>(bytes.data(), 356) == 480);
  CHECK(read_at<std::int32_t>(bytes.data(), 360) == 12);
  CHECK(read_at<std::int32_t>(bytes.data(), 368) == 0);
}

TEST_CASE("write_std140 writes a struct where it is told and nothing past it") {
  std::vector<std::byte> buffer(16 + std140_size<spot_light<float>> + 16, std::byte{0xab});
  spot_light<float> light;
  light.cos_outer = 0.5f;
  write_std140(light, buffer.data() + 16);
  CHECK(read_at<float>(buffer.data(), 16 + 48) == 0.5f);
  for (std::size_t b = 0; b < 16; ++b) CHECK(buffer[b] == std::byte{0xab});
  // spot_light's last 12 bytes are padding: write_std140 leaves them as they were.
  for (std::size_t b = 16 + 52; b < buffer.size(); ++b) CHECK(buffer[b] == std::byte{0xab});
}

TEST_CASE("std140_fields flattens nested structs and names arrays with their stride") {
  const std::vector<std140_field> fields = std140_fields<rsm_gather_settings<float>>();
  std::set<std::string> paths;
  for (const std140_field& field : fields) CHECK(paths.insert(field.path).second);
  const auto find = [&](const std::string& path) {
    for (const std140_field& field : fields)
      if (field.path == path) return field;
    FAIL("no field " << path);
    return std140_field{};
  };
  CHECK(find("radial.seed").offset == 52);
  CHECK(find("radial.seed").glsl_type == "uint");
  CHECK(find("disk.per_pixel_shift").glsl_type == "bool");
  const std140_field tangents = find("slots.boundary_tangent");
  CHECK(tangents.offset == 112);
  CHECK(tangents.array_size == 15u);
  CHECK(tangents.array_stride == 16u);
  CHECK(find("rsm_size").glsl_type == "ivec2");
  CHECK(fields.size() == 1u + 11u + 5u + 2u + 4u);
}

TEST_CASE("std140_block: the GLSL block of one member, with the size and every offset") {
  CHECK(std140_block<irradiance_settings<float>>("irradiance_block", "irradiance") ==
        "// irradiance_settings in std140: 16 bytes (vplkit/std140.hpp: std140_bytes)\n"
        "//   offset 0: float irradiance.min_distance\n"
        "layout(std140) uniform irradiance_block {\n"
        "  irradiance_settings irradiance;\n"
        "};\n");
  const std::string slots = std140_block<elevation_slots<float>>("slots_block", "slots");
  CHECK(slots.find("//   offset 16: float slots.boundary_tangent[15], stride 16\n") != std::string::npos);
  CHECK(slots.find("256 bytes") != std::string::npos);
}

TEST_CASE("std140_offset refuses a member the description does not list") {
  CHECK(std140_offset(&partly_described::listed) == 0u);
  CHECK_THROWS_AS(static_cast<void>(std140_offset(&partly_described::unlisted)), std::invalid_argument);
}
