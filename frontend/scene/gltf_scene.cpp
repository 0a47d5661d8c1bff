// Loading a glTF file with tinygltf under vplkit's file policy (external files only from the
// glTF's folder tree, within one budget; the JSON's depth measured first; glTF 1.0 named), then
// reading the model into a scene (gltf_reader.hpp). The writer is gltf_writer.cpp.
#include "frontend/scene/gltf_scene.hpp"

#include <cstring>
#include <limits>
#include <map>
#include <sstream>
#include <string_view>
#include <vector>

#include <tiny_gltf.h>

#include "frontend/core/error.hpp"
#include "frontend/core/files.hpp"
#include "frontend/scene/draco.hpp"
#include "frontend/scene/gltf_reader.hpp"

namespace fs = std::filesystem;

namespace vplkit {
namespace {

using gltf_detail::image_bytes;

std::string size_text(std::uintmax_t bytes) {
  if (bytes >= (std::uintmax_t{1} << 30) && bytes % (std::uintmax_t{1} << 30) == 0) return std::to_string(bytes >> 30) + " GiB";
  if (bytes >= (std::uintmax_t{1} << 20) && bytes % (std::uintmax_t{1} << 20) == 0) return std::to_string(bytes >> 20) + " MiB";
  return std::to_string(bytes) + " bytes";
}

// tinygltf's file access, bounded: only regular files in the glTF's folder tree, named by a
// relative path without "..", all of them together at most max_bytes; nothing written. Without a
// folder (parse_gltf from memory) nothing is read. tinygltf has percent-decoded the URI once and
// joined it to the folder; it then also tries the current folder, which is never ours.
struct file_access {
  std::string base_dir;            ///< as tinygltf joins it
  std::uintmax_t max_bytes = 0;    ///< the budget of all external files
  std::uintmax_t used_bytes = 0;
  std::string refusal;             ///< why a file was refused: the message, not tinygltf's
};

std::string folder_prefix(const std::string& base) { return base.empty() || base.back() == '/' ? base : base + "/"; }

bool file_exists(const std::string& path, void* user) {
  const auto* access = static_cast<const file_access*>(user);
  if (access->base_dir.empty()) return true;  // read_whole_file then says why it is refused
  // Only the candidate in the glTF's folder; read_whole_file decides whether it may be read.
  return path.compare(0, folder_prefix(access->base_dir).size(), folder_prefix(access->base_dir)) == 0;
}

std::string expand_file_path(const std::string& path, void*) { return path; }

// Why a URI (percent-decoded, relative to the glTF's folder) may not be read; empty when it may.
std::string refused_path(const std::string& relative) {
  if (relative.empty()) return "it is empty";
  if (relative.find('\0') != std::string::npos) return "it contains a NUL character";
  if (relative.front() == '/') return "it is an absolute path";
  for (std::size_t begin = 0; begin <= relative.size();) {
    std::size_t end = relative.find('/', begin);
    if (end == std::string::npos) end = relative.size();
    if (relative.compare(begin, end - begin, "..") == 0) return "it has a '..' component";
    begin = end + 1;
  }
  return {};
}

bool read_whole_file(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* user) {
  auto* access = static_cast<file_access*>(user);
  const auto refuse = [&](const std::string& why) {
    access->refusal = why;
    if (err) *err += why;
    return false;
  };
  if (access->base_dir.empty()) return refuse("external file '" + excerpt_path(path) + "' refused: the glTF was given from memory");
  const std::string relative = path.substr(folder_prefix(access->base_dir).size());
  if (const std::string why = refused_path(relative); !why.empty())
    return refuse("external file '" + excerpt_path(relative) + "' refused: " + why + " (a glTF reads files in its own folder tree only)");
  try {
    std::error_code code;
    const std::uintmax_t bytes = fs::is_regular_file(path, code) ? fs::file_size(path, code) : 0;
    if (!code && access->used_bytes + bytes > access->max_bytes)
      return refuse("external file '" + excerpt_path(relative) + "' (" + std::to_string(bytes) + " bytes) would bring its external data to " +
                    std::to_string(access->used_bytes + bytes) + " bytes, more than the " + size_text(access->max_bytes) +
                    " vplkit reads for one glTF (all buffers and images together)");
    read_file_into(path, access->max_bytes - access->used_bytes, "glTF external file", *out);
    access->used_bytes += out->size();
    return true;
  } catch (const error& failure) {
    return refuse(failure.what());
  }
}

bool write_whole_file(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
  if (err) *err += "vplkit does not write files while reading a glTF";
  return false;
}

bool keep_image_bytes(tinygltf::Image* image, const int index, std::string*, std::string*, int, int, const unsigned char* bytes, int size, void* user) {
  if (image->bufferView >= 0 || size <= 0) return true;
  (*static_cast<image_bytes*>(user))[index].assign(reinterpret_cast<const char*>(bytes), static_cast<std::size_t>(size));
  return true;
}


// glTF 1.0 (a different schema: objects keyed by id where 2.0 has arrays, techniques and
// shaders) is refused by its declared version rather than read as a 2.0 file without meshes.
void refuse_gltf_1(const std::string& version, const std::string& how, const std::string& name) {
  if (version == "1" || version.rfind("1.", 0) == 0)
    throw error(name + ": a glTF 1.0 file (" + how + "); vplkit reads glTF 2.0 only (glTF 1.0 is not read: convert it, e.g. with gltf-pipeline or Blender)");
}

// The deepest nesting of arrays and objects in JSON text (strings skipped, escapes too), checked
// before tinygltf parses it: its conversion to tinygltf::Value recurses once per level, and a
// 40 KB file nested 20,000 deep overflows the stack.
void check_json_depth(std::string_view json, const std::string& name, int max_depth) {
  int depth = 0;
  bool in_string = false;
  for (std::size_t at = 0; at < json.size(); ++at) {
    const char c = json[at];
    if (in_string) {
      if (c == '\\') ++at;
      else if (c == '"') in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > max_depth)
        throw error(name + ": its JSON nests arrays and objects more than " + std::to_string(max_depth) + " deep (at byte " + std::to_string(at) +
                    "); vplkit reads at most " + std::to_string(max_depth) + " levels");
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
}

// The JSON chunk of a GLB, when its header and first chunk are well formed (tinygltf reports
// the rest).
std::string_view glb_json(const std::string& bytes) {
  const auto word = [&](std::size_t at) {
    std::uint32_t value = 0;
    std::memcpy(&value, bytes.data() + at, 4);
    return value;  // GLB is little-endian, as is every machine vplkit builds on
  };
  if (bytes.size() < 20 || word(16) != 0x4E4F534Au) return {};  // "JSON"
  const std::uint32_t length = word(12);
  if (length > bytes.size() - 20) return {};
  return std::string_view(bytes).substr(20, length);
}

}  // namespace

scene parse_gltf(const std::string& original, bool binary, const std::string& name, const fs::path& base_dir, const gltf_limits& limits) {
  if (original.size() > std::numeric_limits<unsigned int>::max()) throw error(name + ": larger than 4 GiB");
  const std::string_view json = binary ? glb_json(original) : std::string_view(original);
  check_json_depth(json, name, limits.max_json_depth);
  if (binary && original.size() >= 8 && original.compare(4, 4, std::string("\1\0\0\0", 4)) == 0) refuse_gltf_1("1", "GLB container version 1", name);
  // KHR_draco_mesh_compression: the compressed primitives' indices out of tinygltf's sight.
  std::string edited = without_draco_indices(json);
  if (!edited.empty() && binary) {
    // The same GLB with the edited JSON chunk (padded with spaces to 4 bytes, as GLB asks).
    while (edited.size() % 4 != 0) edited += ' ';
    const std::size_t after_json = 20 + json.size();
    std::string glb = original.substr(0, 12);
    const auto put_word = [&](std::uint32_t value) { glb.append(reinterpret_cast<const char*>(&value), 4); };
    put_word(static_cast<std::uint32_t>(edited.size()));
    put_word(0x4E4F534Au);  // "JSON"
    glb += edited;
    glb.append(original, after_json, std::string::npos);
    const auto total = static_cast<std::uint32_t>(glb.size());
    std::memcpy(glb.data() + 8, &total, 4);
    edited = std::move(glb);
  }
  const std::string& bytes = edited.empty() ? original : edited;
  file_access access;
  access.base_dir = base_dir.empty() ? std::string() : base_dir.string();
  access.max_bytes = limits.max_external_bytes;
  tinygltf::TinyGLTF loader;
  loader.SetFsCallbacks({&file_exists, &expand_file_path, &read_whole_file, &write_whole_file, &access});
  image_bytes images;
  loader.SetImageLoader(&keep_image_bytes, &images);
  tinygltf::Model model;
  std::string err, warn;
  bool loaded = false;
  try {
    loaded = binary ? loader.LoadBinaryFromMemory(&model, &err, &warn, reinterpret_cast<const unsigned char*>(bytes.data()),
                                                  static_cast<unsigned int>(bytes.size()), access.base_dir)
                    : loader.LoadASCIIFromString(&model, &err, &warn, bytes.data(), static_cast<unsigned int>(bytes.size()), access.base_dir);
  } catch (const std::exception& failure) {
    // tinygltf indexes an empty decoded data URI with at(0).
    err += failure.what();
  }
  if (!access.refusal.empty()) {
    // A refused external file: our reason, not tinygltf's wrapping of it. (An image tinygltf
    // could not read is only a warning to it, and a refused one must still fail the load.)
    throw error(name + ": " + access.refusal);
  }
  if (!loaded) {
    // tinygltf's messages echo the input (a 16 MiB data URI, a long path): each line cut short.
    std::string reason;
    std::istringstream lines(err);
    for (std::string line; std::getline(lines, line);)
      if (!line.empty()) reason += (reason.empty() ? "" : "; ") + excerpt(line);
    // A glTF 1.0 file fails here or below (its schema is not 2.0's); named as such.
    const std::string declared = declared_gltf_version(json);
    refuse_gltf_1(declared, "asset.version " + excerpt(declared), name);
    throw error(name + ": not a readable glTF 2.0 file (" + (reason.empty() ? std::string("no reason given") : excerpt(reason, 4 * max_echoed_characters)) + ")");
  }
  if (model.asset.version.empty() || model.asset.version[0] != '2') {
    const std::string declared = declared_gltf_version(json);
    refuse_gltf_1(declared, "asset.version " + excerpt(declared), name);
  }
  return gltf_detail::reader(model, name, limits, images).read();
}

scene load_gltf(const fs::path& path, const gltf_limits& limits) {
  const std::string extension = path.extension().string();
  if (extension != ".gltf" && extension != ".glb") throw error(excerpt_path(path.string()) + ": a glTF file ends in .gltf or .glb");
  const std::string bytes = read_file(path, limits.max_file_bytes, "glTF file");
  fs::path folder = path.parent_path();
  if (folder.empty()) folder = ".";
  return parse_gltf(bytes, extension == ".glb", excerpt_path(path.string()), folder, limits);
}

}  // namespace vplkit
