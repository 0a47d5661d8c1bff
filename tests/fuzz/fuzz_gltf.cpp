// Fuzz target: the glTF 2.0 reader (frontend/scene/gltf_scene.hpp over tinygltf). Three kinds of
// input, by their first byte:
//   "glTF..."  a .glb as it is;
//   "{..."     a .gltf text as it is (scripts/fuzz.sh gives libFuzzer tests/fuzz/gltf.dict);
//   anything else: the bytes drive a generator (fuzz_input) that writes a glTF with the structure
//              tinygltf accepts and the values and references a hostile file would have: node
//              graphs as chains thousands deep, trees and cycles; buffers, views and accessors with
//              boundary offsets, strides, counts and component types; triangle strips and fans;
//              KHR_draco_mesh_compression primitives over a valid Draco cube (edgebreaker or
//              sequential, made at start by libdraco's encoder), the cube with bytes the input
//              changes or cuts, or the input's own bytes; cameras and lights with
//              extreme numbers; extras nested thousands deep; external URIs with "..", percent
//              escapes and absolute paths. Byte mutations of a generator input are structural ones.
// External files are looked up in a scratch folder holding one 36-byte buffer (in.bin, also in
// sub/) and, beside the folder, a file the reader must never reach (outside.bin).
// A malformed input must end in vplkit::error; a scene that loads must pass check_scene, have
// finite camera rays (or refuse its camera with vplkit::error) and keep the triangle limit.
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include <draco/compression/encode.h>
#include <draco/mesh/triangle_soup_mesh_builder.h>

#include "frontend/core/error.hpp"
#include "frontend/reference/reference.hpp"
#include "frontend/scene/gltf_scene.hpp"
#include "tests/fuzz/fuzz_input.hpp"

namespace fs = std::filesystem;
using vplkit::fuzzing::fuzz_input;

namespace {

void require(bool condition, const char* what) {
  if (!condition) {
    std::fprintf(stderr, "fuzz_gltf: %s\n", what);
    std::abort();
  }
}

// The scratch folder: <tmp>/vplkit-fuzz-gltf-<pid>/scene/{in.bin, sub/in.bin} and ../outside.bin,
// whose positions (777.125, ...) no loaded scene may contain.
const fs::path& scene_folder() {
  static const fs::path folder = [] {
    const fs::path root = fs::temp_directory_path() / ("vplkit-fuzz-gltf-" + std::to_string(::getpid()));
    fs::create_directories(root / "scene" / "sub");
    const float triangle[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    const float secret[9] = {777.125f, -333.0625f, 555.5f, 778.125f, -333.0625f, 555.5f, 777.125f, -332.0625f, 555.5f};
    for (const fs::path& bin : {root / "scene" / "in.bin", root / "scene" / "sub" / "in.bin"})
      std::ofstream(bin, std::ios::binary).write(reinterpret_cast<const char*>(triangle), sizeof triangle);
    std::ofstream(root / "outside.bin", std::ios::binary).write(reinterpret_cast<const char*>(secret), sizeof secret);
    std::atexit([] {
      std::error_code ignored;
      fs::remove_all(fs::temp_directory_path() / ("vplkit-fuzz-gltf-" + std::to_string(::getpid())), ignored);
    });
    return root / "scene";
  }();
  return folder;
}

const char* number(fuzz_input& in) {
  return in.pick({"0", "1", "-1", "2", "3", "0.5", "1e-6", "1e-45", "0.05", "50", "1e7", "1e38", "3.4e38", "1e300", "-1e38", "255", "65535", "4294967295",
                  "4294967296", "2147483647", "-2147483648", "36", "12", "4", "1.5707963267948966", "3.1", "100000", "1e6"});
}

const char* index_value(fuzz_input& in) { return in.pick({"0", "1", "2", "3", "-1", "7", "2147483647", "1.5", "\"0\""}); }

std::string base64(const std::string& bytes) {
  static const char* alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    std::uint32_t group = static_cast<std::uint8_t>(bytes[i]) << 16;
    if (i + 1 < bytes.size()) group |= static_cast<std::uint8_t>(bytes[i + 1]) << 8;
    if (i + 2 < bytes.size()) group |= static_cast<std::uint8_t>(bytes[i + 2]);
    out += alphabet[group >> 18 & 63];
    out += alphabet[group >> 12 & 63];
    out += i + 1 < bytes.size() ? alphabet[group >> 6 & 63] : '=';
    out += i + 2 < bytes.size() ? alphabet[group & 63] : '=';
  }
  return out;
}

// A unit cube as Draco data (12 triangles, POSITION as attribute 0), encoded with edgebreaker or
// the sequential method: a valid starting point the input then damages.
std::string draco_cube(bool sequential) {
  const float corners[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  const int faces[12][3] = {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5}, {0, 5, 4}, {3, 6, 2}, {3, 7, 6}, {0, 4, 7}, {0, 7, 3}, {1, 2, 6}, {1, 6, 5}};
  draco::TriangleSoupMeshBuilder builder;
  builder.Start(12);
  const int position = builder.AddAttribute(draco::GeometryAttribute::POSITION, 3, draco::DT_FLOAT32);
  for (int f = 0; f < 12; ++f)
    builder.SetAttributeValuesForFace(position, draco::FaceIndex(static_cast<std::uint32_t>(f)), corners[faces[f][0]], corners[faces[f][1]], corners[faces[f][2]]);
  const std::unique_ptr<draco::Mesh> mesh = builder.Finalize();
  draco::Encoder encoder;
  encoder.SetAttributeQuantization(draco::GeometryAttribute::POSITION, 11);
  encoder.SetEncodingMethod(sequential ? draco::MESH_SEQUENTIAL_ENCODING : draco::MESH_EDGEBREAKER_ENCODING);
  draco::EncoderBuffer buffer;
  require(mesh && encoder.EncodeMeshToBuffer(*mesh, &buffer).ok(), "libdraco could not encode the cube");
  return std::string(buffer.data(), buffer.size());
}

std::string nested(std::size_t depth) { return std::string(depth, '[') + std::string(depth, ']'); }

// A glTF text whose structure the bytes choose.
std::string generate(fuzz_input& in) {
  std::string json = "{\"asset\":{\"version\":\"" + std::string(in.pick({"2.0", "2.0", "1.0", ""})) + "\"";
  if (in.below(8) == 0) json += ",\"extras\":" + nested(in.flag() ? in.below(80) : in.word() % 30000);
  json += "}";
  // Buffers: data URIs of the input's bytes, or external names a hostile file would use.
  const std::uint32_t buffers = in.below(4);
  json += ",\"buffers\":[";
  for (std::uint32_t b = 0; b < buffers; ++b) {
    std::string uri;
    std::size_t length = 36;
    switch (in.below(7)) {
      case 6: {
        // Draco data: the cube, damaged by the input, or cut short.
        static const std::string cubes[2] = {draco_cube(false), draco_cube(true)};
        std::string bytes = cubes[in.below(2)];
        for (std::uint32_t changes = in.below(4); changes > 0; --changes) bytes[in.below(static_cast<std::uint32_t>(bytes.size()))] = static_cast<char>(in.word());
        if (in.below(4) == 0) bytes.resize(in.below(static_cast<std::uint32_t>(bytes.size()) + 1));
        length = bytes.size();
        uri = "data:application/octet-stream;base64," + base64(bytes);
        break;
      }
      case 0:
      case 1: {
        const std::string bytes = in.take(in.below(2) == 0 ? 36 : in.below(200));
        length = in.flag() ? bytes.size() : in.below(300);
        uri = "data:application/octet-stream;base64," + base64(bytes);
        break;
      }
      case 2: uri = in.pick({"in.bin", "sub/in.bin", "in%2Ebin", "sub%2Fin.bin", "./in.bin", "sub/./in.bin"}); break;
      case 3: uri = in.pick({"../outside.bin", "%2e%2e/outside.bin", "%2E%2E/outside.bin", "sub/../../outside.bin", "..%2Foutside.bin", "%252e%252e/outside.bin"}); break;
      case 4: uri = (fs::absolute(scene_folder()) / (in.flag() ? "in.bin" : "../outside.bin")).string(); break;
      default: uri = in.pick({"", "data:", "data:application/octet-stream;base64,!!", "missing.bin", "in.bin\\u0000x", "sub"}); break;
    }
    if (in.below(4) == 0) length = std::strtoul(number(in), nullptr, 10);
    json += std::string(b ? "," : "") + "{\"byteLength\":" + std::to_string(length) + ",\"uri\":\"" + uri + "\"}";
  }
  json += "]";
  const std::uint32_t views = in.below(6);
  json += ",\"bufferViews\":[";
  for (std::uint32_t v = 0; v < views; ++v) {
    json += std::string(v ? "," : "") + "{\"buffer\":" + index_value(in) + ",\"byteLength\":" + (in.flag() ? "36" : number(in));
    if (in.flag()) json += std::string(",\"byteOffset\":") + number(in);
    if (in.below(4) == 0) json += std::string(",\"byteStride\":") + in.pick({"4", "12", "16", "252", "0", "3", "256"});
    json += "}";
  }
  json += "]";
  const std::uint32_t accessors = in.below(6);
  json += ",\"accessors\":[";
  for (std::uint32_t a = 0; a < accessors; ++a) {
    json += std::string(a ? "," : "") + "{\"bufferView\":" + index_value(in) + ",\"componentType\":" +
            in.pick({"5126", "5126", "5125", "5123", "5121", "5120", "5122", "5124", "5130", "1"}) + ",\"count\":" + (in.flag() ? "3" : number(in)) +
            ",\"type\":\"" + in.pick({"VEC3", "VEC3", "SCALAR", "VEC2", "VEC4", "MAT4", "vec3"}) + "\"";
    if (in.flag()) json += std::string(",\"byteOffset\":") + number(in);
    if (in.below(8) == 0) json += ",\"sparse\":{\"count\":1,\"indices\":{\"bufferView\":0,\"componentType\":5125},\"values\":{\"bufferView\":0}}";
    json += "}";
  }
  json += "]";
  const std::uint32_t meshes = in.below(3);
  json += ",\"meshes\":[";
  for (std::uint32_t m = 0; m < meshes; ++m) {
    json += std::string(m ? "," : "") + "{\"primitives\":[";
    const std::uint32_t primitives = 1 + in.below(3);
    for (std::uint32_t p = 0; p < primitives; ++p) {
      json += std::string(p ? "," : "") + "{\"attributes\":{\"POSITION\":" + index_value(in);
      if (in.flag()) json += std::string(",\"NORMAL\":") + index_value(in);
      json += "}";
      if (in.flag()) json += std::string(",\"indices\":") + index_value(in);
      if (in.below(3) == 0) json += std::string(",\"mode\":") + in.pick({"4", "0", "1", "5", "6", "5", "6", "-1", "99"});
      if (in.below(4) == 0) {
        json += std::string(",\"extensions\":{\"KHR_draco_mesh_compression\":{\"bufferView\":") + index_value(in) + ",\"attributes\":{\"POSITION\":" +
                in.pick({"0", "0", "1", "-1", "7", "\"0\""}) + (in.flag() ? std::string(",\"NORMAL\":") + in.pick({"0", "1", "2"}) : std::string()) + "}}}";
      }
      if (in.below(4) == 0) json += std::string(",\"material\":") + index_value(in);
      json += "}";
    }
    json += "]}";
  }
  json += "]";
  if (in.flag()) {
    json += ",\"materials\":[{\"pbrMetallicRoughness\":{\"baseColorFactor\":[" + std::string(number(in)) + "," + number(in) + "," + number(in) + "," +
            number(in) + "]}}]";
  }
  if (in.flag()) {
    json += ",\"cameras\":[{\"type\":\"" + std::string(in.pick({"perspective", "perspective", "orthographic"})) + "\",\"perspective\":{\"yfov\":" +
            in.pick({"0.8", "3.1", "1e-6", "0"}) + ",\"znear\":" + in.pick({"0.05", "1e-6", "1e-30", "1"}) + ",\"zfar\":" +
            in.pick({"50", "1e7", "1e30", "0.06", "1e38"}) + "}}]";
  }
  bool lights = false;
  if (in.flag()) {
    lights = true;
    json += ",\"extensionsUsed\":[\"KHR_lights_punctual\"],\"extensions\":{\"KHR_lights_punctual\":{\"lights\":[{\"type\":\"" +
            std::string(in.pick({"spot", "directional", "point"})) + "\",\"intensity\":" + number(in) + ",\"color\":[" + number(in) + ",1,1]" +
            ",\"spot\":{\"innerConeAngle\":" + in.pick({"0", "0.3", "1.5"}) + ",\"outerConeAngle\":" + in.pick({"0.6", "1.5707963267948966", "2"}) + "}}]}}";
  }
  // Nodes: a chain (one in eight thousands deep: deep enough to overflow a recursive walk under
  // ASan, and costly enough per input that they are kept rare), or a small graph whose children the
  // bytes choose.
  const bool chain = in.below(4) == 0;
  const std::uint32_t nodes = chain ? 2 + (in.below(8) == 0 ? in.word() % 6000 : in.below(64)) : 1 + in.below(12);
  json += ",\"nodes\":[";
  for (std::uint32_t n = 0; n < nodes; ++n) {
    json += std::string(n ? "," : "") + "{";
    std::string fields;
    if (chain) {
      if (n + 1 < nodes) fields += ",\"children\":[" + std::to_string(n + 1) + "]";
      else fields += ",\"mesh\":0";
    } else {
      const std::uint32_t children = in.below(4);
      if (children > 0) {
        fields += ",\"children\":[";
        for (std::uint32_t c = 0; c < children; ++c) fields += std::string(c ? "," : "") + std::to_string(in.below(nodes + 1));
        fields += "]";
      }
      if (in.flag()) fields += std::string(",\"mesh\":") + index_value(in);
      if (in.below(4) == 0) fields += std::string(",\"camera\":") + index_value(in);
      if (lights && in.below(4) == 0) fields += std::string(",\"extensions\":{\"KHR_lights_punctual\":{\"light\":") + index_value(in) + "}}";
    }
    switch (in.below(6)) {
      case 0: fields += std::string(",\"translation\":[") + number(in) + "," + number(in) + "," + number(in) + "]"; break;
      case 1: fields += std::string(",\"scale\":[") + number(in) + "," + number(in) + "," + number(in) + "]"; break;
      case 2: fields += std::string(",\"rotation\":[") + number(in) + "," + number(in) + "," + number(in) + "," + number(in) + "]"; break;
      case 3: {
        fields += ",\"matrix\":[";
        for (int k = 0; k < 16; ++k) fields += std::string(k ? "," : "") + (k % 5 == 0 && in.flag() ? "1" : number(in));
        fields += "]";
        break;
      }
      default: break;
    }
    json += fields.empty() ? "" : fields.substr(1);
    json += "}";
  }
  json += "]";
  if (in.below(4) != 0) {
    json += ",\"scenes\":[{\"nodes\":[0";
    if (!chain && in.flag()) json += std::string(",") + index_value(in);
    json += "]}],\"scene\":" + std::string(in.pick({"0", "0", "1", "-1"}));
  }
  return json + "}";
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::string bytes(reinterpret_cast<const char*>(data), size);
  const bool binary = bytes.compare(0, 4, "glTF") == 0;
  if (!binary && (size == 0 || data[0] != '{')) {
    fuzz_input in(data, size);
    bytes = generate(in);
  }
  vplkit::gltf_limits limits;
  limits.max_triangles = 1 << 16;       // keeps each run fast; the limit's own check is exercised too
  limits.max_external_bytes = 1 << 10;  // 28 reads of in.bin
  try {
    const vplkit::scene loaded = vplkit::parse_gltf(bytes, binary, "fuzz.gltf", scene_folder(), limits);
    vplkit::check_scene(loaded);
    require(loaded.geometry.triangle_count() <= limits.max_triangles + 2, "more triangles than the limit");  // + frame_mesh's floor
    for (const vplkit::vertex& v : loaded.geometry.vertices)
      require(v.position != glm::vec3(777.125f, -333.0625f, 555.5f) || v.normal != glm::vec3(0, 0, 1), "a vertex of outside.bin was read");
    try {
      const vplkit::camera_rays rays(loaded.view, 64, 48);
      const vplkit::camera_rays::ray centre = rays.at(32, 24);
      require(std::isfinite(centre.direction.x) && std::isfinite(centre.origin.x), "a camera ray is not finite");
    } catch (const vplkit::error&) {
    }
  } catch (const vplkit::error&) {
  }
  return 0;
}
