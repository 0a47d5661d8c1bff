// Memory and time bounds of the inputs that used to exhaust them (issue 26), measured in a process
// of their own: the probe makes its input in a scratch folder at run time (a 1 GiB sparse file, a
// 256 MiB index buffer, a 2^21-triangle OBJ), runs vplkit on it in-process through the command
// line, and compares its own peak resident set (getrusage) and wall time with the bound that
// docs/hardening.md states. One case per run:
//   vplkit_memory_probe <case> <scratch folder>
// Cases: gltf-external-budget, gltf-byte-indices, obj-2m-triangles, png-inflate-bomb.
// Exit 0 within the bounds, 1 outside them (with the numbers), 2 for a bad command line.
#include <sys/resource.h>

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

// A 2^21-triangle OBJ (a 1024 x 1024 grid of quads, no normals) rendered: the mesh stays indexed
// through loading, the GL buffers and the pipeline (before: 1.48 GB here, 1.9 GB in the issue).
void obj_2m_triangles(const fs::path& folder) {
  const auto write_grid = [&](const fs::path& path, int n) {
    std::ofstream out(path);
    char line[96];
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i) {
        const double x = 2.0 * i / n - 1.0, z = 2.0 * j / n - 1.0;
        std::snprintf(line, sizeof line, "v %.6f %.6f %.6f\n", x, 0.1 * std::sin(6 * x) * std::cos(5 * z), z);
        out << line;
      }
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const int a = j * (n + 1) + i + 1, b = a + 1, c = a + n + 1, d = c + 1;
        std::snprintf(line, sizeof line, "f %d %d %d\nf %d %d %d\n", a, c, b, b, c, d);
        out << line;
      }
  };
  write_grid(folder / "small.obj", 8);
  write_grid(folder / "grid.obj", 1024);
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
  // The issue's target is 780 MiB (measured 700-755 MiB in seven runs); the bound leaves room
  // for the same run-to-run variation as the bytes per triangle below.
  expect(peak <= 820, "peak <= 820 MiB");
  // The target is 300 bytes; the peak varies by about 30 bytes a triangle between runs (273-300
  // in six runs after the texture coordinates joined the vertex), so the bound leaves that room.
  expect(per_triangle <= 330, "<= 330 bytes per triangle at peak beyond the process's own");
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
  expect(seconds < 5.0, "within 5 s");
  expect(peak <= before + 64, "peak within 64 MiB of the probe's own");
}

}  // namespace

int main(int argc, char** argv) {
  const std::vector<std::pair<std::string, std::function<void(const fs::path&)>>> cases = {
      {"gltf-external-budget", gltf_external_budget}, {"gltf-byte-indices", gltf_byte_indices}, {"obj-2m-triangles", obj_2m_triangles},
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
