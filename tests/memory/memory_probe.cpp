// Memory and time bounds of the inputs that used to exhaust them (issue 26), measured in a process
// of their own: the probe makes its input in a scratch folder at run time (a 1 GiB sparse file, a
// 256 MiB index buffer, a 2^21-triangle OBJ), runs vplkit on it in-process through the command
// line, and compares its own peak resident set (getrusage) and wall time with the bound that
// docs/hardening.md states. One case per run:
//   vplkit_memory_probe <case> <scratch folder>
// Cases: gltf-external-budget, gltf-byte-indices, obj-2m-triangles, obj-2m-faceted,
// gltf-one-image-four-times, png-inflate-bomb.
// Exit 0 within the bounds, 1 outside them (with the numbers), 2 for a bad command line.
#include <sys/resource.h>

#include <turbojpeg.h>
#include <zlib.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "frontend/cli/cli.hpp"

namespace fs = std::filesystem;

namespace {

double peak_mebibytes() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;  // ru_maxrss is in KiB on Linux
}

double seconds_since(std::chrono::steady_clock::time_point start) { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); }

struct outcome {
  int status;
  std::string out, err;
};

outcome run_vplkit(const std::vector<std::string>& arguments) {
  std::vector<const char*> argv{"vplkit"};
  for (const std::string& argument : arguments) argv.push_back(argument.c_str());
  std::ostringstream out, err;
  const int status = vplkit::run_command_line(static_cast<int>(argv.size()), argv.data(), out, err);
  return {status, out.str(), err.str()};
}

int failures = 0;

void expect(bool condition, const std::string& what) {
  std::cout << (condition ? "ok     " : "FAILED ") << what << "\n";
  if (!condition) ++failures;
}

// A triangle glTF whose buffers are `buffers` (JSON objects) and whose index accessor is `indices`.
std::string gltf(const std::string& buffers, const std::string& views, const std::string& accessors, bool indexed) {
  return R"({"asset": {"version": "2.0"}, "nodes": [{"mesh": 0}], "meshes": [{"primitives": [{"attributes": {"POSITION": 0})" +
         std::string(indexed ? R"(, "indices": 1)" : "") + R"(}]}], "accessors": )" + accessors + R"(, "bufferViews": )" + views +
         R"(, "buffers": )" + buffers + "}";
}

const std::string triangle_positions(36, '\0');

// A 600-byte glTF listing one sparse 1 GiB file four times: one budget for all external data,
// so the second is refused before it is read (before: 5.2 GB and minutes).
void gltf_external_budget(const fs::path& folder) {
  const fs::path big = folder / "big.bin";
  {
    std::ofstream out(big, std::ios::binary);
    out << triangle_positions;
  }
  fs::resize_file(big, std::uintmax_t{1} << 30);  // sparse: nothing on disk
  const std::string buffer = R"({"byteLength": 1073741824, "uri": "big.bin"})";
  std::ofstream(folder / "four.gltf") << gltf("[" + buffer + "," + buffer + "," + buffer + "," + buffer + "]", R"([{"buffer": 0, "byteLength": 36}])",
                                              R"([{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"}])", false);
  const auto start = std::chrono::steady_clock::now();
  const outcome result = run_vplkit({"render", "--scene", (folder / "four.gltf").string(), "--size", "16", "--out", (folder / "four.png").string()});
  const double seconds = seconds_since(start), peak = peak_mebibytes();
  std::cout << "exit " << result.status << ": " << result.err << "peak " << peak << " MiB, " << seconds << " s\n";
  expect(result.status == 1 && result.err.find("would bring its external data to 2147483648 bytes, more than the 1 GiB") != std::string::npos,
         "refused with the budget named");
  expect(peak <= 1024 + 256, "peak <= 1.25 GiB (the budget, 1 GiB, plus the process)");
  expect(!fs::exists(folder / "four.png"), "nothing written");
}

// 256 MiB of one-byte indices (89 million triangles): refused by the triangle limit before they
// are read or widened (before: 3.4 GB and 26 s).
void gltf_byte_indices(const fs::path& folder) {
  const std::size_t count = (std::size_t{256} << 20) / 3 * 3;
  {
    std::ofstream out(folder / "indices.bin", std::ios::binary);
    out << triangle_positions;
    const std::string corners("\x00\x01\x02", 3);
    std::string block;
    for (int i = 0; i < 1 << 16; ++i) block += corners;
    for (std::size_t written = 0; written < count; written += block.size()) out.write(block.data(), static_cast<std::streamsize>(std::min(block.size(), count - written)));
  }
  std::ofstream(folder / "indices.gltf") << gltf(R"([{"byteLength": )" + std::to_string(36 + count) + R"(, "uri": "indices.bin"}])",
                                                 R"([{"buffer": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": )" + std::to_string(count) + "}]",
                                                 R"([{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"}, {"bufferView": 1, "componentType": 5121, "count": )" +
                                                     std::to_string(count) + R"(, "type": "SCALAR"}])",
                                                 true);
  const auto start = std::chrono::steady_clock::now();
  const outcome result = run_vplkit({"render", "--scene", (folder / "indices.gltf").string(), "--size", "16", "--out", (folder / "indices.png").string()});
  const double seconds = seconds_since(start), peak = peak_mebibytes();
  std::cout << "exit " << result.status << ": " << result.err << "peak " << peak << " MiB, " << seconds << " s\n";
  expect(result.status == 1 && result.err.find("more than 16777216 triangles") != std::string::npos, "refused by the triangle limit");
  expect(peak <= 256 + 160, "peak <= the file (256 MiB) + 160 MiB");
}

// An n x n grid of quads as an OBJ without normals. Smooth: the quads share their corners, as a
// scanned or modelled surface does. Faceted: every triangle has three `v` lines of its own (a
// triangle soup, as STL conversions and flat-shaded exports write), so nothing is shared and the
// mesh has three vertices a triangle.
void write_grid(const fs::path& path, int n, bool faceted) {
  std::ofstream out(path);
  char line[128];
  const auto height = [](double x, double z) { return 0.1 * std::sin(6 * x) * std::cos(5 * z); };
  const auto corner = [&](int i, int j) {
    const double x = 2.0 * i / n - 1.0, z = 2.0 * j / n - 1.0;
    std::snprintf(line, sizeof line, "v %.6f %.6f %.6f\n", x, height(x, z), z);
    out << line;
  };
  if (!faceted) {
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i) corner(i, j);
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const int a = j * (n + 1) + i + 1, b = a + 1, c = a + n + 1, d = c + 1;
        std::snprintf(line, sizeof line, "f %d %d %d\nf %d %d %d\n", a, c, b, b, c, d);
        out << line;
      }
    return;
  }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      corner(i, j), corner(i, j + 1), corner(i + 1, j);
      corner(i + 1, j), corner(i, j + 1), corner(i + 1, j + 1);
      out << "f -6 -5 -4\nf -3 -2 -1\n";
    }
}

// A 2^21-triangle OBJ (a 1024 x 1024 grid of quads, no normals) rendered within `bound` MiB and
// `per_triangle_bound` bytes a triangle beyond the process's own memory.
void obj_grid(const fs::path& folder, bool faceted, double bound, double per_triangle_bound) {
  write_grid(folder / "small.obj", 8, faceted);
  write_grid(folder / "grid.obj", 1024, faceted);
  // The process's own memory (GL context, shaders, render targets) first, with a 128-triangle grid.
  const outcome small = run_vplkit({"render", "--scene", (folder / "small.obj").string(), "--size", "512", "--out", (folder / "small.png").string()});
  const double base = peak_mebibytes();
  const auto start = std::chrono::steady_clock::now();
  const outcome result = run_vplkit({"render", "--scene", (folder / "grid.obj").string(), "--size", "512", "--out", (folder / "grid.png").string()});
  const double seconds = seconds_since(start), peak = peak_mebibytes();
  const double triangles = 2.0 * 1024 * 1024;
  const double per_triangle = (peak - base) * 1024.0 * 1024.0 / triangles;
  std::cout << "exit " << small.status << " and " << result.status << ": " << result.err << "peak " << peak << " MiB (" << base
            << " MiB with 128 triangles), " << per_triangle << " bytes per triangle, " << seconds << " s\n";
  expect(small.status == 0 && result.status == 0 && fs::exists(folder / "grid.png"), "both render");
  expect(peak <= bound, "peak <= " + std::to_string(static_cast<int>(bound)) + " MiB");
  expect(per_triangle <= per_triangle_bound, "<= " + std::to_string(static_cast<int>(per_triangle_bound)) + " bytes per triangle at peak beyond the process's own");
}

// The smooth grid: the mesh stays indexed through loading, the GL buffers and the pipeline
// (before: 1.48 GB here, 1.9 GB in the issue). The issue's target is 780 MiB (measured 700-755 MiB
// in seven runs); the bound leaves room for the run-to-run variation. The target per triangle is
// 300 bytes; the peak varies by about 30 bytes a triangle between runs (273-300 in six runs after
// the texture coordinates joined the vertex), so the bound leaves that room.
void obj_2m_triangles(const fs::path& folder) { obj_grid(folder, false, 820, 330); }

// The faceted grid, a triangle soup: three vertices a triangle, six times the smooth grid's. It
// peaked at 1695 MiB (the pipeline and its visibility baseline each kept a copy of the mesh and
// uploaded their own), then 815-827 MiB: the framing's floor quad, pushed onto a vector read to its
// size, doubled its capacity for the whole run. Grown by exactly the quad, and with the GPU copy
// holding only the attributes that vary, 735 MiB alone and 806 MiB beside the slow tier's other
// tests, the peak in the OBJ reader: a vertex index written for every position (120 MiB) beside
// the mesh being built, and the floor reallocating the vertex array (old and new at once). The
// reader now indexes only positions two corners share, and leaves room for the floor: the load
// peaks at 624 MiB. The render then peaked at 705-745 MiB: the CPU mesh, its GPU copy, and
// llvmpipe's binned triangles (90-180 MiB, more on a busy machine); mesh_buffers now draws such a
// mesh in chunks with at most two in flight: 634-643 MiB in three runs. The bound is the issue's
// target.
void obj_2m_faceted(const fs::path& folder) { obj_grid(folder, true, 780, 380); }

// A progressive 8192 x 8192 JPEG of a few hundred KB named by four glTF images (the issue's case:
// 37 s and 5.2 GB, four decodes): one decode, one texture with its mipmaps (341 MiB), within the
// budget of 1 GiB for a scene's textures; then four different such files: the fourth is refused
// by the budget from its header, before it is decoded.
void gltf_one_image_four_times(const fs::path& folder) {
  const int side = 8192;
  const auto write_jpeg = [&](const fs::path& path, int seed) {
    std::vector<unsigned char> rgb(static_cast<std::size_t>(side) * side * 3);
    for (int y = 0; y < side; ++y)
      for (int x = 0; x < side; ++x) {
        unsigned char* p = &rgb[(static_cast<std::size_t>(y) * side + static_cast<std::size_t>(x)) * 3];
        p[0] = static_cast<unsigned char>((x / 256 + seed) * 40), p[1] = static_cast<unsigned char>(y / 256 * 30), p[2] = static_cast<unsigned char>(seed * 60);
      }
    tjhandle encoder = tjInitCompress();
    unsigned char* jpeg = nullptr;
    unsigned long size = 0;
    const int failed = tjCompress2(encoder, rgb.data(), side, 0, side, TJPF_RGB, &jpeg, &size, TJSAMP_420, 50, TJFLAG_PROGRESSIVE);
    if (failed == 0) std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(jpeg), static_cast<std::streamsize>(size));
    tjFree(jpeg);
    tjDestroy(encoder);
    return failed == 0 ? size : 0ul;
  };
  const unsigned long bytes = write_jpeg(folder / "big.jpg", 0);
  for (int k = 1; k < 4; ++k) write_jpeg(folder / ("big-" + std::to_string(k) + ".jpg"), k);
  {
    const float uv_bin[15] = {-1, 0, -1, 1, 0, -1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
    std::ofstream(folder / "uv.bin", std::ios::binary).write(reinterpret_cast<const char*>(uv_bin), sizeof uv_bin);
  }
  const auto textured = [](const std::vector<std::string>& uris) {
    std::string primitives, materials, textures, images;
    for (std::size_t i = 0; i < uris.size(); ++i) {
      const std::string n = std::to_string(i), comma = i == 0 ? "" : ",";
      primitives += comma + R"({"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "material": )" + n + "}";
      materials += comma + R"({"pbrMetallicRoughness": {"baseColorTexture": {"index": )" + n + "}}}";
      textures += comma + R"({"source": )" + n + "}";
      images += comma + R"({"uri": ")" + uris[i] + R"("})";
    }
    return R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}], "meshes": [{"primitives": [)" + primitives +
           R"(]}], "materials": [)" + materials + R"(], "textures": [)" + textures + R"(], "images": [)" + images +
           R"(], "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [-1, 0, -1], "max": [1, 0, 1]},)"
           R"( {"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC2"}], "bufferViews": [{"buffer": 0, "byteLength": 36},)"
           R"( {"buffer": 0, "byteOffset": 36, "byteLength": 24}], "buffers": [{"byteLength": 60, "uri": "uv.bin"}]})";
  };
  std::ofstream(folder / "four.gltf") << textured({"big.jpg", "big.jpg", "big.jpg", "big.jpg"});
  std::ofstream(folder / "distinct.gltf") << textured({"big.jpg", "big-1.jpg", "big-2.jpg", "big-3.jpg"});
  std::cout << "big.jpg: " << bytes << " bytes, progressive, " << side << "x" << side << "\n";
  auto start = std::chrono::steady_clock::now();
  const outcome four = run_vplkit({"render", "--scene", (folder / "four.gltf").string(), "--size", "64", "--out", (folder / "four.png").string()});
  const double seconds = seconds_since(start), peak = peak_mebibytes();
  std::cout << "exit " << four.status << ": " << four.err << "peak " << peak << " MiB, " << seconds << " s\n";
  expect(bytes > 0 && four.status == 0 && fs::exists(folder / "four.png"), "one file named by four images renders");
  // One texture of 8192^2 with mipmaps is 341 MiB, the GL driver holds a copy, and the decoder's
  // 256 MiB output becomes level 0 (moved, not copied): measured 1042 MiB and 27 s.
  expect(peak <= 1280, "peak <= 1.25 GiB (was 5.2 GB with four decodes)");
  start = std::chrono::steady_clock::now();
  const outcome distinct = run_vplkit({"render", "--scene", (folder / "distinct.gltf").string(), "--size", "64", "--out", (folder / "distinct.png").string()});
  std::cout << "exit " << distinct.status << ": " << distinct.err << seconds_since(start) << " s\n";
  expect(distinct.status == 1 && distinct.err.find("image 3 (big-3.jpg): its 8192x8192 texels with mipmaps (357913940 bytes) would bring the scene's decoded "
                                                   "textures to 1431655760 bytes, more than the 1 GiB budget") != std::string::npos,
         "four different 8192^2 files: the fourth is refused, naming the file and the budget");
  expect(!fs::exists(folder / "distinct.png"), "nothing written");
}

// A 1 MiB PNG whose IDAT inflates to 1 GiB behind a 1 x 1 image: refused before inflating
// (before: 1.1 GB, 22 s, and accepted).
void png_inflate_bomb(const fs::path& folder) {
  const auto chunk = [](const std::string& type, const std::string& data) {
    std::string out;
    const auto put32 = [&](std::uint32_t v) {
      for (int shift = 24; shift >= 0; shift -= 8) out += static_cast<char>((v >> shift) & 0xff);
    };
    put32(static_cast<std::uint32_t>(data.size()));
    out += type + data;
    const std::string crc_input = type + data;
    put32(static_cast<std::uint32_t>(crc32(0, reinterpret_cast<const Bytef*>(crc_input.data()), static_cast<uInt>(crc_input.size()))));
    return out;
  };
  z_stream stream{};
  deflateInit(&stream, 9);
  std::string compressed;
  std::vector<unsigned char> zeros(std::size_t{1} << 20, 0), buffer(std::size_t{1} << 16);
  const unsigned char row[4] = {0, 16, 32, 48};
  const auto feed = [&](const unsigned char* data, std::size_t size, int flush) {
    stream.next_in = const_cast<unsigned char*>(data);
    stream.avail_in = static_cast<uInt>(size);
    do {
      stream.next_out = buffer.data();
      stream.avail_out = static_cast<uInt>(buffer.size());
      deflate(&stream, flush);
      compressed.append(reinterpret_cast<const char*>(buffer.data()), buffer.size() - stream.avail_out);
    } while (stream.avail_out == 0);
  };
  feed(row, sizeof row, Z_NO_FLUSH);
  for (int i = 0; i < 1024; ++i) feed(zeros.data(), zeros.size(), Z_NO_FLUSH);
  feed(nullptr, 0, Z_FINISH);
  deflateEnd(&stream);
  const std::string header("\0\0\0\x01\0\0\0\x01\x08\x02\0\0\0", 13);
  std::ofstream(folder / "bomb.png", std::ios::binary) << std::string("\x89PNG\r\n\x1a\n", 8) + chunk("IHDR", header) + chunk("IDAT", compressed) + chunk("IEND", "");
  std::cout << "bomb.png: " << fs::file_size(folder / "bomb.png") << " bytes, inflating to 1 GiB\n";
  const double before = peak_mebibytes();
  const auto start = std::chrono::steady_clock::now();
  const outcome result = run_vplkit({"compare", (folder / "bomb.png").string(), (folder / "bomb.png").string()});
  const double seconds = seconds_since(start), peak = peak_mebibytes();
  std::cout << "exit " << result.status << ": " << result.err << "peak " << peak << " MiB (" << before << " before), " << seconds << " s\n";
  expect(result.status == 1 && result.err.find("an inflate bomb?") != std::string::npos, "refused as an inflate bomb");
  // A guard against a hang (inflating without the bound), not a timing: 3 s on a loaded 2-core
  // machine; the peak below is what shows the bomb was refused before it was inflated.
  expect(seconds < 60.0, "within 60 s");
  expect(peak <= before + 64, "peak within 64 MiB of the probe's own");
}

}  // namespace

int main(int argc, char** argv) {
  const std::vector<std::pair<std::string, std::function<void(const fs::path&)>>> cases = {
      {"gltf-external-budget", gltf_external_budget}, {"gltf-byte-indices", gltf_byte_indices}, {"obj-2m-triangles", obj_2m_triangles}, {"obj-2m-faceted", obj_2m_faceted},
      {"gltf-one-image-four-times", gltf_one_image_four_times},
      {"png-inflate-bomb", png_inflate_bomb}};
  if (argc != 3) {
    std::cerr << "usage: vplkit_memory_probe <case> <scratch folder>\n";
    return 2;
  }
  for (const auto& [name, probe] : cases)
    if (name == argv[1]) {
      const fs::path folder = argv[2];
      fs::remove_all(folder);
      fs::create_directories(folder);
      probe(folder);
      fs::remove_all(folder);
      return failures == 0 ? 0 : 1;
    }
  std::cerr << "vplkit_memory_probe: unknown case '" << argv[1] << "'\n";
  return 2;
}
