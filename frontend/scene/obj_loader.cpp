#include "frontend/scene/obj_loader.hpp"

#include <algorithm>
#include <charconv>
#include <cstdlib>
#include <cmath>
#include <map>
#include <memory>
#include <new>
#include <optional>
#include <type_traits>
#include <unordered_map>
#include <vector>

#include "frontend/core/error.hpp"
#include "frontend/core/files.hpp"
#include "frontend/image/texture_decode.hpp"
#include "frontend/scene/polygon.hpp"

namespace vplkit {
namespace fs = std::filesystem;

namespace {

// Splits text into lines (LF or CRLF) and lines into words (spaces and tabs), rejecting every
// other control character: a CR or vertical tab inside a line would make two readers disagree
// about where a statement starts.
class statement_reader {
 public:
  statement_reader(std::string_view text, const std::string& name) : text_(text), name_(name) {}

  // The next line's words (none for an empty or comment line); false at the end of the text.
  bool next(std::vector<std::string_view>& words) {
    if (at_ >= text_.size()) return false;
    ++line_number_;
    std::size_t end = text_.find('\n', at_);
    if (end == std::string_view::npos) end = text_.size();
    std::string_view line = text_.substr(at_, end - at_);
    at_ = end + 1;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    words.clear();
    for (std::size_t i = 0; i < line.size(); ++i) {
      const auto byte = static_cast<unsigned char>(line[i]);
      if ((byte < 0x20 && byte != '\t') || byte == 0x7f) {
        char hex[8];
        std::snprintf(hex, sizeof hex, "0x%02x", byte);
        fail("control character " + std::string(hex) + " in the line (lines end in LF or CRLF; words are separated by spaces or tabs)");
      }
    }
    std::size_t i = 0;
    while (i < line.size()) {
      while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
      if (i >= line.size() || line[i] == '#') break;  // the rest of the line is a comment
      const std::size_t begin = i;
      while (i < line.size() && line[i] != ' ' && line[i] != '\t') ++i;
      words.push_back(line.substr(begin, i - begin));
    }
    return true;
  }

  [[noreturn]] void fail(const std::string& what) const { throw error(name_ + ":" + std::to_string(line_number_) + ": " + what); }

 private:
  std::string_view text_;
  const std::string& name_;
  std::size_t at_ = 0;
  long line_number_ = 0;
};

std::string quoted(std::string_view word) {
  constexpr std::size_t shown = 40;
  // Built with += rather than "'" + string: GCC 12 gives a false -Wrestrict on the latter (bug 105329).
  std::string text = "'";
  text += word.substr(0, shown);
  text += word.size() > shown ? "...'" : "'";
  return text;
}

// A number as the float it is stored in: finite, and within max_mesh_coordinate.
float parse_number(std::string_view word, const statement_reader& reader) {
  std::string_view digits = word;
  if (digits.size() > 1 && digits[0] == '+' && digits[1] != '-') digits.remove_prefix(1);
  float value = 0.0f;
  const auto [end, code] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
  if (code == std::errc::invalid_argument || end != digits.data() + digits.size()) reader.fail(quoted(word) + " is not a number");
  if (code == std::errc::result_out_of_range) reader.fail("number " + quoted(word) + " is outside the float range");
  if (!std::isfinite(value)) reader.fail("number " + quoted(word) + " is not finite");
  if (std::fabs(value) > max_mesh_coordinate)
    reader.fail("number " + quoted(word) + " is larger than " + std::to_string(static_cast<long>(max_mesh_coordinate)) +
                " in magnitude (vplkit works in float; scale the mesh down)");
  return value;
}

glm::vec3 parse_vector(const std::vector<std::string_view>& words, std::size_t min_numbers, std::size_t max_numbers, const statement_reader& reader) {
  const std::size_t count = words.size() - 1;
  if (count < min_numbers || count > max_numbers) {
    const std::string range = min_numbers == max_numbers ? std::to_string(min_numbers) : std::to_string(min_numbers) + " to " + std::to_string(max_numbers);
    reader.fail(quoted(words[0]) + " needs " + range + " numbers, got " + std::to_string(count));
  }
  glm::vec3 result(0.0f);
  for (std::size_t i = 1; i < words.size(); ++i) {
    const float value = parse_number(words[i], reader);
    if (i <= 3) result[static_cast<glm::length_t>(i - 1)] = value;
  }
  return result;
}

struct material {
  std::string name;
  glm::vec3 albedo{0.73f};
  std::string texture_file;  ///< map_Kd's file, relative to the OBJ's folder; empty: none
  glm::vec2 texture_scale{1.0f}, texture_offset{0.0f};  ///< map_Kd's -s and -o (u, v)
  bool clamp = false;                                   ///< map_Kd's -clamp on
};

// map_Kd [-o u [v [w]]] [-s u [v [w]]] [-clamp on|off] [other options] file: the file and the
// options that change where the texture is sampled; the rest (-bm, -mm, -cc, ...) do not apply to
// a base colour and are skipped with their arguments.
void parse_map_kd(const std::vector<std::string_view>& words, material& target, const statement_reader& reader) {
  if (words.size() < 2) reader.fail("'map_Kd' needs a file name");
  const std::size_t last = words.size() - 1;
  const auto is_number = [](std::string_view word) {
    float value = 0.0f;
    const auto [end, code] = std::from_chars(word.data(), word.data() + word.size(), value);
    return code == std::errc() && end == word.data() + word.size();
  };
  for (std::size_t i = 1; i < last;) {
    const std::string_view option = words[i++];
    if (option == "-o" || option == "-s" || option == "-t") {
      glm::vec3 values(option == "-s" ? 1.0f : 0.0f);
      int count = 0;
      while (i < last && count < 3 && is_number(words[i])) values[count++] = parse_number(words[i++], reader);
      if (count == 0) reader.fail("map_Kd " + std::string(option) + " needs 1 to 3 numbers");
      if (option == "-o") target.texture_offset = glm::vec2(values);
      if (option == "-s") target.texture_scale = glm::vec2(values);
    } else if (option == "-clamp") {
      if (i >= last || (words[i] != "on" && words[i] != "off")) reader.fail("map_Kd -clamp needs on or off");
      target.clamp = words[i++] == "on";
    } else if (option == "-blendu" || option == "-blendv" || option == "-cc" || option == "-bm" || option == "-boost" || option == "-texres" ||
               option == "-imfchan") {
      if (i >= last) reader.fail("map_Kd " + std::string(option) + " needs an argument");
      ++i;
    } else if (option == "-mm") {
      if (i + 1 >= last) reader.fail("map_Kd -mm needs two numbers");
      i += 2;
    } else {
      reader.fail("map_Kd option " + quoted(option) + " is not one of -o, -s, -t, -clamp, -blendu, -blendv, -cc, -bm, -boost, -texres, -imfchan, -mm "
                  "(a file name with spaces is not read)");
    }
  }
  target.texture_file = std::string(words[last]);
}

// newmtl, Kd and map_Kd; the other MTL statements (specular, other maps, ...) do not enter a
// diffuse renderer.
void parse_material_library(std::string_view text, const std::string& name, std::map<std::string, material, std::less<>>& materials) {
  statement_reader reader(text, name);
  std::vector<std::string_view> words;
  material* current = nullptr;
  while (reader.next(words)) {
    if (words.empty()) continue;
    if (words[0] == "newmtl") {
      if (words.size() != 2) reader.fail("'newmtl' needs one name");
      current = &materials[std::string(words[1])];
      *current = material{};
      current->name = std::string(words[1]);
    } else if (words[0] == "Kd") {
      if (!current) reader.fail("'Kd' before any 'newmtl'");
      if (words.size() != 2 && words.size() != 4) reader.fail("'Kd' needs 1 or 3 numbers, got " + std::to_string(words.size() - 1));
      glm::vec3 kd(parse_number(words[1], reader));
      if (words.size() == 4) kd = glm::vec3(kd.x, parse_number(words[2], reader), parse_number(words[3], reader));
      current->albedo = glm::clamp(kd, 0.0f, 1.0f);
    } else if (words[0] == "map_Kd") {
      if (!current) reader.fail("'map_Kd' before any 'newmtl'");
      parse_map_kd(words, *current, reader);
    }
  }
}

// One triangle corner: position, texture coordinate and normal indices (-1: none), 0-based.
struct corner {
  std::uint32_t position = 0;
  std::int32_t texture_coordinate = -1;
  std::int32_t normal = -1;
};

// "v", "v/vt", "v//vn" or "v/vt/vn", each index 1..count or negative (counted from the end).
corner parse_corner(std::string_view word, std::size_t positions, std::size_t texture_coordinates, std::size_t normals,
                    const statement_reader& reader) {
  std::string_view parts[3];
  int count = 0;
  for (std::size_t start = 0;;) {
    if (count == 3) reader.fail("face corner " + quoted(word) + " has more than 3 indices (v/vt/vn)");
    const std::size_t slash = word.find('/', start);
    parts[count++] = word.substr(start, slash == std::string_view::npos ? std::string_view::npos : slash - start);
    if (slash == std::string_view::npos) break;
    start = slash + 1;
  }
  // Empty only the texture coordinate between two slashes (v//vn).
  if (parts[0].empty() || (count >= 2 && parts[count - 1].empty()) || (count == 2 && parts[1].empty()))
    reader.fail("face corner " + quoted(word) + " is not v, v/vt, v//vn or v/vt/vn");
  const std::size_t totals[3] = {positions, texture_coordinates, normals};
  const char* names[3] = {"vertex", "texture coordinate", "normal"};
  long resolved[3] = {-1, -1, -1};
  for (int k = 0; k < count; ++k) {
    if (parts[k].empty()) continue;
    long index = 0;
    const auto [end, code] = std::from_chars(parts[k].data(), parts[k].data() + parts[k].size(), index);
    if (code != std::errc() || end != parts[k].data() + parts[k].size()) reader.fail("face corner " + quoted(word) + " is not an index");
    const long total = static_cast<long>(totals[k]);
    const long zero_based = index < 0 ? total + index : index - 1;
    if (index == 0 || zero_based < 0 || zero_based >= total)
      reader.fail("face " + std::string(names[k]) + " index " + std::string(parts[k]) + " is out of range (" + std::to_string(total) + " defined so far)");
    resolved[k] = zero_based;
  }
  return {static_cast<std::uint32_t>(resolved[0]), static_cast<std::int32_t>(resolved[1]), static_cast<std::int32_t>(resolved[2])};
}

// What makes two triangle corners the same mesh vertex: the position, where the normal comes
// from (a `vn` index, or -1 for the smooth normal of the position), the material (the albedo and
// the texture: an index into the materials faces use) and the `vt` index (-1 for none).
struct vertex_key {
  std::uint32_t position = 0;
  std::int32_t normal = -1;
  std::uint32_t material = 0;
  std::int32_t texture_coordinate = -1;
  bool operator==(const vertex_key& other) const {
    return position == other.position && normal == other.normal && material == other.material && texture_coordinate == other.texture_coordinate;
  }
};

struct vertex_key_hash {
  std::size_t operator()(const vertex_key& key) const {
    std::uint64_t h = key.position;
    h = h * 0x9e3779b97f4a7c15ull ^ static_cast<std::uint32_t>(key.normal);
    h = h * 0x9e3779b97f4a7c15ull ^ key.material;
    h = h * 0x9e3779b97f4a7c15ull ^ static_cast<std::uint32_t>(key.texture_coordinate);
    return static_cast<std::size_t>(h ^ (h >> 29));
  }
};

// Mesh vertices by key: the first key of each position in a flat table (the common case, one
// vertex per position), any other key of the position in a hash map. Only a position that more
// than one corner uses can be shared, so only those are ever looked up or written: the table is
// calloc'd, whose pages the kernel backs only when first written, and a triangle soup (every
// position used once: three `v` lines a triangle) never touches it. Before, its 20 bytes a
// position (120 MiB for a faceted 2^21-triangle OBJ) were written up front and held beside the
// mesh being built: the load's peak.
class vertex_index {
 public:
  /// `uses[p]`: how many corners use position p, saturated at 2.
  explicit vertex_index(std::vector<std::uint8_t> uses)
      : uses_(std::move(uses)), first_(uses_.empty() ? nullptr : static_cast<entry*>(std::calloc(uses_.size(), sizeof(entry)))) {
    if (!uses_.empty() && !first_) throw std::bad_alloc();
  }
  static constexpr std::uint32_t none = 0xffffffffu;
  /// Whether a corner at this position can share a vertex with another corner.
  bool may_share(std::uint32_t position) const { return uses_[position] > 1; }
  std::uint32_t find(const vertex_key& key) const {
    const entry& first = first_.get()[key.position];
    if (first.vertex_plus_one != 0 && first.key == key) return first.vertex_plus_one - 1;
    if (others_.empty()) return none;
    const auto found = others_.find(key);
    return found == others_.end() ? none : found->second;
  }
  void insert(const vertex_key& key, std::uint32_t vertex) {
    entry& first = first_.get()[key.position];
    if (first.vertex_plus_one == 0) first = {key, vertex + 1};
    else others_.emplace(key, vertex);
  }

 private:
  /// All zero (calloc's) is an empty entry.
  struct entry {
    vertex_key key;
    std::uint32_t vertex_plus_one;
  };
  static_assert(std::is_trivially_copyable_v<entry> && std::is_trivially_destructible_v<entry>, "entries live in calloc'd memory");
  struct free_deleter {
    void operator()(entry* table) const { std::free(table); }
  };
  std::vector<std::uint8_t> uses_;
  std::unique_ptr<entry, free_deleter> first_;
  std::unordered_map<vertex_key, std::uint32_t, vertex_key_hash> others_;
};

// parse_obj, with the file's text owned by `owned` when it is given: then the text is released as
// soon as its statements are read, before the mesh is built (the text of a triangle soup, three `v`
// lines a triangle, is about 100 bytes a triangle: as much as the mesh being built).
mesh parse_obj_text(std::string_view text, std::string* owned, const std::string& name, const material_library_reader& read_library, const obj_limits& limits,
                    const texture_file_reader& read_texture) {
  statement_reader reader(text, name);
  std::vector<std::string_view> words;
  std::vector<glm::vec3> positions, normals;
  std::vector<glm::vec2> texture_coordinates;  // v flipped: glTF's convention (material.hpp)
  std::map<std::string, material, std::less<>> materials;
  std::vector<std::string> libraries_read;
  std::vector<material> used{material{}};  // the materials faces use, by first use; 0: none given
  std::uint32_t current = 0;
  std::vector<corner> corners;                 // three per triangle
  std::vector<std::uint32_t> triangle_material;  // one per triangle, into `used`
  std::vector<corner> polygon;
  std::vector<glm::vec3> polygon_positions;
  std::vector<std::uint32_t> polygon_triangles;  // three indices into `polygon` per triangle
  polygon_triangulator triangulator;
  while (reader.next(words)) {
    if (words.empty()) continue;
    const std::string_view keyword = words[0];
    if (keyword == "v") {
      positions.push_back(parse_vector(words, 3, 7, reader));
    } else if (keyword == "vn") {
      normals.push_back(parse_vector(words, 3, 3, reader));
    } else if (keyword == "vt") {
      const glm::vec3 uvw = parse_vector(words, 1, 3, reader);
      texture_coordinates.emplace_back(uvw.x, 1.0f - uvw.y);
    } else if (keyword == "f") {
      if (words.size() < 4) reader.fail("a face needs at least 3 corners");
      polygon.clear();
      for (std::size_t i = 1; i < words.size(); ++i)
        polygon.push_back(parse_corner(words[i], positions.size(), texture_coordinates.size(), normals.size(), reader));
      if (triangle_material.size() + (polygon.size() - 2) > limits.max_triangles)
        reader.fail("more than " + std::to_string(limits.max_triangles) + " triangles (the most vplkit loads)");
      polygon_positions.clear();
      for (const corner& at : polygon) polygon_positions.push_back(positions[at.position]);
      polygon_triangles.clear();
      try {
        triangulator.triangulate(polygon_positions, polygon_triangles);
      } catch (const error& failure) {
        reader.fail(failure.what());
      }
      if (triangle_material.size() + polygon_triangles.size() / 3 > limits.max_triangles)
        reader.fail("more than " + std::to_string(limits.max_triangles) + " triangles (the most vplkit loads)");
      for (const std::uint32_t k : polygon_triangles) corners.push_back(polygon[k]);
      triangle_material.insert(triangle_material.end(), polygon_triangles.size() / 3, current);
    } else if (keyword == "mtllib") {
      if (words.size() < 2) reader.fail("'mtllib' needs a file name");
      for (std::size_t i = 1; i < words.size(); ++i) {
        const std::string library(words[i]);
        try {
          parse_material_library(read_library(library), library, materials);
        } catch (const error& failure) {
          reader.fail("mtllib " + library + ": " + failure.what());
        }
        libraries_read.push_back(library);
      }
    } else if (keyword == "usemtl") {
      if (words.size() != 2) reader.fail("'usemtl' needs one material name");
      const auto found = materials.find(words[1]);
      if (found == materials.end()) {
        std::string read;
        for (const std::string& library : libraries_read) read += (read.empty() ? "" : ", ") + library;
        reader.fail("material " + quoted(words[1]) + " is not in the material libraries read so far (" + (read.empty() ? "none" : read) + ")");
      }
      // As the library defines it now (a library read again may redefine a material).
      auto same = std::find_if(used.begin() + 1, used.end(), [&](const material& m) { return m.name == found->second.name && m.texture_file == found->second.texture_file &&
                                                                                            m.albedo == found->second.albedo && m.clamp == found->second.clamp &&
                                                                                            m.texture_scale == found->second.texture_scale &&
                                                                                            m.texture_offset == found->second.texture_offset; });
      if (same == used.end()) same = used.insert(used.end(), found->second);
      current = static_cast<std::uint32_t>(same - used.begin());
    }
    // o, g, s, l, p, vp, curves and surfaces: nothing a triangle renderer uses.
  }
  if (positions.empty() || corners.empty()) throw error(name + ": no faces (an OBJ mesh needs 'v' and 'f' lines)");
  if (owned) std::string().swap(*owned);

  // Where the file has no normals, each corner takes the area-weighted mean of the normals of the
  // faces around its position (smooth shading, as the meshes were scanned or modelled).
  std::vector<glm::vec3> smooth_normals(positions.size(), glm::vec3(0.0f));
  std::vector<std::uint8_t> uses(positions.size(), 0);  // corners per position, saturated at 2
  for (std::size_t face = 0; face < corners.size(); face += 3) {
    const glm::vec3 a = positions[corners[face].position], b = positions[corners[face + 1].position], c = positions[corners[face + 2].position];
    const glm::vec3 area_weighted = glm::cross(b - a, c - a);
    for (std::size_t k = 0; k < 3; ++k) {
      smooth_normals[corners[face + k].position] += area_weighted;
      std::uint8_t& count = uses[corners[face + k].position];
      count = static_cast<std::uint8_t>(std::min(count + 1, 2));
    }
  }
  // The textures of the materials faces use, each file decoded once, and a surface material per
  // textured OBJ material.
  material_library library;
  std::vector<int> surface_of(used.size(), -1);
  std::map<std::string, int> texture_of_file;
  texture_budget budget(limits.textures.max_scene_bytes, "obj_limits::textures.max_scene_bytes");
  for (std::size_t m = 0; m < used.size(); ++m) {
    if (used[m].texture_file.empty()) continue;
    if (std::find(triangle_material.begin(), triangle_material.end(), static_cast<std::uint32_t>(m)) == triangle_material.end()) continue;
    const material& source = used[m];
    auto [at, inserted] = texture_of_file.try_emplace(source.texture_file, static_cast<int>(library.textures.size()));
    if (inserted) {
      const std::string what = name + ": material '" + source.name + "' map_Kd " + source.texture_file;
      if (!read_texture) throw error(what + ": texture files are not read here");
      std::string bytes;
      try {
        bytes = read_texture(source.texture_file);
      } catch (const error& failure) {
        throw error(what + ": " + failure.what());
      }
      budget.decode_into(library, bytes, what, source.texture_file, limits.textures);
    }
    surface_material made;
    made.name = source.name;
    made.texture = at->second;
    made.sampler.wrap_s = made.sampler.wrap_t = source.clamp ? texture_wrap::clamp_to_edge : texture_wrap::repeat;
    // -s and -o act on OBJ's (u, v), v up; in the flipped v' = 1 - v: v'_t = s v' + (1 - s - o).
    made.texture_matrix = glm::mat2(glm::vec2(source.texture_scale.x, 0.0f), glm::vec2(0.0f, source.texture_scale.y));
    made.texture_offset = glm::vec2(source.texture_offset.x, 1.0f - source.texture_scale.y - source.texture_offset.y);
    surface_of[m] = static_cast<int>(library.materials.size());
    library.materials.push_back(std::move(made));
  }

  // The mesh stays indexed: corners with the same position, normal source, material and texture
  // coordinate share a vertex, so that memory follows the mesh (about 50 bytes a triangle for a
  // closed surface), not three copies of every vertex.
  mesh result;
  vertex_index shared(std::move(uses));
  // At most a vertex per corner (a triangle soup, where nothing is shared, has exactly that):
  // reserved, because growing by doubling held the old and the new array at once (185 + 277 MB
  // for a faceted 2^21-triangle mesh). The pages of a closed mesh's unused part are never touched.
  // Both leave room for frame_mesh's floor, which would otherwise reallocate them.
  result.indices.reserve(corners.size() + framing_floor_indices);
  result.vertices.reserve(corners.size() + framing_floor_vertices);
  for (std::size_t face = 0; face < corners.size(); face += 3) {
    const material& face_material = used[triangle_material[face / 3]];
    glm::vec3 corner_position[3];
    for (std::size_t k = 0; k < 3; ++k) corner_position[k] = positions[corners[face + k].position];
    glm::vec3 face_normal = glm::cross(corner_position[1] - corner_position[0], corner_position[2] - corner_position[0]);
    const float area = glm::length(face_normal);
    if (!(area > 0.0f) || !std::isfinite(area)) continue;  // degenerate triangle: nothing to shade
    face_normal /= area;
    for (std::size_t k = 0; k < 3; ++k) {
      const corner& at = corners[face + k];
      // The file's normal where it gives a usable one; else the smooth normal, unless it leans
      // away from the face (a crease folded over itself): then the face's own, for this corner only.
      std::optional<glm::vec3> normal;
      vertex_key key{at.position, -1, triangle_material[face / 3], at.texture_coordinate};
      if (at.normal >= 0) {
        const glm::vec3 given = normals[static_cast<std::size_t>(at.normal)];
        const float given_length = glm::length(given);
        if (given_length > 0.0f && std::isfinite(given_length)) {
          normal = glm::normalize(given);
          key.normal = at.normal;
        }
      }
      if (!normal) {
        const glm::vec3 smooth = smooth_normals[at.position];
        const float smooth_length = glm::length(smooth);
        if (smooth_length > 0.0f && std::isfinite(smooth_length) && glm::dot(smooth, face_normal) > 0.0f) normal = glm::normalize(smooth);
      }
      const bool shareable = normal.has_value();
      const bool indexed = shareable && shared.may_share(at.position);
      if (indexed) {
        if (const std::uint32_t found = shared.find(key); found != vertex_index::none) {
          result.indices.push_back(found);
          continue;
        }
      }
      const std::int32_t uv = at.texture_coordinate;
      const auto added = static_cast<std::uint32_t>(result.vertices.size());
      result.vertices.push_back({corner_position[k], shareable ? *normal : face_normal, face_material.albedo,
                                 uv >= 0 ? texture_coordinates[static_cast<std::size_t>(uv)] : glm::vec2(0.0f)});
      result.indices.push_back(added);
      if (indexed) shared.insert(key, added);
    }
    // A textured face (every corner with a vt) joins its material's range; one without vt is plain.
    const int surface = surface_of[triangle_material[face / 3]];
    const bool textured = surface >= 0 && corners[face].texture_coordinate >= 0 && corners[face + 1].texture_coordinate >= 0 &&
                          corners[face + 2].texture_coordinate >= 0;
    if (textured) {
      const auto first = static_cast<std::uint32_t>(result.indices.size() - 3);
      std::vector<material_range>& ranges = result.material_ranges;
      if (!ranges.empty() && ranges.back().material == static_cast<std::uint32_t>(surface) && ranges.back().first_index + ranges.back().index_count == first)
        ranges.back().index_count += 3;
      else
        ranges.push_back({first, 3, static_cast<std::uint32_t>(surface)});
    }
  }
  if (result.indices.empty()) throw error(name + ": no faces with area (every triangle is degenerate)");
  // The parser's arrays go first, then the vertices are fitted to their count (a copy of what is
  // used: a closed mesh has about one vertex per two triangles).
  for (auto* released : {&positions, &smooth_normals}) std::vector<glm::vec3>().swap(*released);
  std::vector<corner>().swap(corners);
  shared = vertex_index({});
  if (result.vertices.capacity() > result.vertices.size() + result.vertices.size() / 8 + framing_floor_vertices) {
    std::vector<vertex> fitted;
    fitted.reserve(result.vertices.size() + framing_floor_vertices);
    fitted.assign(result.vertices.begin(), result.vertices.end());
    result.vertices.swap(fitted);
  }
  if (!result.material_ranges.empty()) result.materials = std::make_shared<const material_library>(std::move(library));
  return result;
}

}  // namespace

mesh parse_obj(std::string_view text, const std::string& name, const material_library_reader& read_library, const obj_limits& limits,
               const texture_file_reader& read_texture) {
  return parse_obj_text(text, nullptr, name, read_library, limits, read_texture);
}

mesh load_obj(const fs::path& path, const obj_limits& limits) {
  std::string text = read_file(path, limits.max_obj_bytes, "OBJ file");
  const fs::path folder = path.parent_path();
  return parse_obj_text(
      text, &text, path.string(), [&](const std::string& library) { return read_file(folder / library, limits.max_mtl_bytes, "MTL file"); }, limits,
      [&](const std::string& file) {
        // Exporters on Windows write map_Kd paths with backslashes.
        std::string portable = file;
        std::replace(portable.begin(), portable.end(), '\\', '/');
        return read_file(folder / portable, limits.max_texture_file_bytes, "texture file");
      });
}

}  // namespace vplkit
