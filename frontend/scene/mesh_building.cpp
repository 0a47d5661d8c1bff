// Building and editing meshes: the quad, box, sphere and cylinder the built-in scenes are made of,
// and the two refinements (longest-edge bisection to a triangle count, subdivision to an edge
// length) that the teapot scenes and the references use.
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <optional>
#include <queue>
#include <tuple>

#include "frontend/scene/scene.hpp"

namespace vplkit {

void add_quad(mesh& target, glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d, glm::vec3 normal, glm::vec3 albedo) {
  const auto base = static_cast<std::uint32_t>(target.vertices.size());
  for (const glm::vec3& corner : {a, b, c, d}) target.vertices.push_back({corner, normal, albedo});
  for (std::uint32_t index : {0u, 1u, 2u, 0u, 2u, 3u}) target.indices.push_back(base + index);
}

void add_box(mesh& target, glm::vec3 centre, glm::vec3 size, float yaw_degrees, glm::vec3 albedo) {
  const float yaw = glm::radians(yaw_degrees);
  const glm::vec3 axis_x(std::cos(yaw), 0.0f, -std::sin(yaw));
  const glm::vec3 axis_y(0.0f, 1.0f, 0.0f);
  const glm::vec3 axis_z(std::sin(yaw), 0.0f, std::cos(yaw));
  const glm::vec3 hx = axis_x * (0.5f * size.x), hy = axis_y * (0.5f * size.y), hz = axis_z * (0.5f * size.z);
  auto corner = [&](float sx, float sy, float sz) { return centre + sx * hx + sy * hy + sz * hz; };
  add_quad(target, corner(-1, -1, 1), corner(1, -1, 1), corner(1, 1, 1), corner(-1, 1, 1), axis_z, albedo);      // front
  add_quad(target, corner(1, -1, -1), corner(-1, -1, -1), corner(-1, 1, -1), corner(1, 1, -1), -axis_z, albedo);  // back
  add_quad(target, corner(1, -1, 1), corner(1, -1, -1), corner(1, 1, -1), corner(1, 1, 1), axis_x, albedo);      // right
  add_quad(target, corner(-1, -1, -1), corner(-1, -1, 1), corner(-1, 1, 1), corner(-1, 1, -1), -axis_x, albedo);  // left
  add_quad(target, corner(-1, 1, 1), corner(1, 1, 1), corner(1, 1, -1), corner(-1, 1, -1), axis_y, albedo);      // top
  add_quad(target, corner(-1, -1, -1), corner(1, -1, -1), corner(1, -1, 1), corner(-1, -1, 1), -axis_y, albedo);  // bottom
}

void add_sphere(mesh& target, glm::vec3 centre, float radius, int stacks, int slices, glm::vec3 albedo) {
  const auto base = static_cast<std::uint32_t>(target.vertices.size());
  const float pi = 3.14159265358979f;
  for (int i = 0; i <= stacks; ++i) {
    const float polar = pi * static_cast<float>(i) / static_cast<float>(stacks);
    for (int j = 0; j <= slices; ++j) {
      const float azimuth = 2.0f * pi * static_cast<float>(j) / static_cast<float>(slices);
      const glm::vec3 normal(std::sin(polar) * std::cos(azimuth), std::cos(polar), -std::sin(polar) * std::sin(azimuth));
      target.vertices.push_back({centre + radius * normal, normal, albedo});
    }
  }
  const auto row = static_cast<std::uint32_t>(slices + 1);
  for (std::uint32_t i = 0; i < static_cast<std::uint32_t>(stacks); ++i) {
    for (std::uint32_t j = 0; j < static_cast<std::uint32_t>(slices); ++j) {
      const std::uint32_t a = base + i * row + j, b = a + row, c = b + 1, d = a + 1;
      for (std::uint32_t index : {a, b, c, a, c, d}) target.indices.push_back(index);
    }
  }
}

void add_cylinder(mesh& target, glm::vec3 base, float radius, float height, int segments, int stacks, glm::vec3 albedo) {
  const auto first = static_cast<std::uint32_t>(target.vertices.size());
  const float pi = 3.14159265358979f;
  for (int i = 0; i <= stacks; ++i)
    for (int j = 0; j <= segments; ++j) {
      const float angle = 2.0f * pi * static_cast<float>(j) / static_cast<float>(segments);
      const glm::vec3 normal(std::cos(angle), 0.0f, -std::sin(angle));
      target.vertices.push_back({base + radius * normal + glm::vec3(0.0f, height * static_cast<float>(i) / static_cast<float>(stacks), 0.0f), normal, albedo});
    }
  const auto row = static_cast<std::uint32_t>(segments + 1);
  for (std::uint32_t i = 0; i < static_cast<std::uint32_t>(stacks); ++i)
    for (std::uint32_t j = 0; j < static_cast<std::uint32_t>(segments); ++j) {
      const std::uint32_t a = first + i * row + j, b = a + 1, c = b + row, d = a + row;
      for (std::uint32_t index : {a, b, c, a, c, d}) target.indices.push_back(index);
    }
}

mesh refine_longest_edges(const mesh& source, std::size_t target_triangles) {
  // Weld: one vertex per distinct position.
  mesh welded;
  std::map<std::tuple<float, float, float>, std::uint32_t> index_of;
  std::vector<glm::vec3> normal_sums;
  for (std::size_t corner = 0; corner < source.indices.size(); ++corner) {
    const vertex& v = source.vertices[source.indices[corner]];
    const auto key = std::make_tuple(v.position.x, v.position.y, v.position.z);
    auto [found, inserted] = index_of.emplace(key, static_cast<std::uint32_t>(welded.vertices.size()));
    if (inserted) {
      welded.vertices.push_back(v);
      normal_sums.push_back(glm::vec3(0.0f));
    }
    normal_sums[found->second] += v.normal;
    welded.indices.push_back(found->second);
  }
  for (std::size_t i = 0; i < welded.vertices.size(); ++i)
    if (glm::length(normal_sums[i]) > 0.0f) welded.vertices[i].normal = glm::normalize(normal_sums[i]);

  // Triangles as index triples; edges (low, high) -> the triangles that have them.
  std::vector<std::array<std::uint32_t, 3>> triangles;
  for (std::size_t t = 0; t + 2 < welded.indices.size(); t += 3)
    triangles.push_back({welded.indices[t], welded.indices[t + 1], welded.indices[t + 2]});
  using edge = std::pair<std::uint32_t, std::uint32_t>;
  const auto key_of = [](std::uint32_t a, std::uint32_t b) { return a < b ? edge(a, b) : edge(b, a); };
  std::map<edge, std::vector<std::size_t>> edges;
  const auto length_of = [&](const edge& e) { return glm::length(welded.vertices[e.first].position - welded.vertices[e.second].position); };
  std::priority_queue<std::pair<float, edge>> longest;
  const auto add_triangle_edges = [&](std::size_t t) {
    for (int k = 0; k < 3; ++k) {
      const edge e = key_of(triangles[t][static_cast<std::size_t>(k)], triangles[t][static_cast<std::size_t>((k + 1) % 3)]);
      edges[e].push_back(t);
      longest.emplace(length_of(e), e);
    }
  };
  for (std::size_t t = 0; t < triangles.size(); ++t) add_triangle_edges(t);
  const auto remove_triangle_edges = [&](std::size_t t) {
    for (int k = 0; k < 3; ++k) {
      auto& list = edges[key_of(triangles[t][static_cast<std::size_t>(k)], triangles[t][static_cast<std::size_t>((k + 1) % 3)])];
      list.erase(std::remove(list.begin(), list.end(), t), list.end());
    }
  };
  while (triangles.size() < target_triangles && !longest.empty()) {
    const edge e = longest.top().second;
    longest.pop();
    const auto found = edges.find(e);
    if (found == edges.end() || found->second.empty()) continue;  // split already
    const std::vector<std::size_t> sharing = found->second;
    const vertex& a = welded.vertices[e.first];
    const vertex& b = welded.vertices[e.second];
    const glm::vec3 normal_sum = a.normal + b.normal;
    const vertex middle{0.5f * (a.position + b.position), glm::length(normal_sum) > 0.0f ? glm::normalize(normal_sum) : a.normal,
                        0.5f * (a.albedo + b.albedo), 0.5f * (a.texcoord + b.texcoord)};
    const auto m = static_cast<std::uint32_t>(welded.vertices.size());
    welded.vertices.push_back(middle);
    for (std::size_t t : sharing) {
      remove_triangle_edges(t);
      std::array<std::uint32_t, 3> tri = triangles[t];
      // Rotate so that the split edge is (tri[0], tri[1]), keeping the winding.
      while (key_of(tri[0], tri[1]) != e) tri = {tri[1], tri[2], tri[0]};
      triangles[t] = {tri[0], m, tri[2]};
      triangles.push_back({m, tri[1], tri[2]});
      add_triangle_edges(t);
      add_triangle_edges(triangles.size() - 1);
    }
    edges.erase(e);
  }
  mesh refined;
  refined.vertices = std::move(welded.vertices);
  for (const auto& tri : triangles) refined.indices.insert(refined.indices.end(), tri.begin(), tri.end());
  return refined;
}

std::optional<mesh> subdivide_long_edges(const mesh& source, float max_edge, std::size_t max_triangles) {
  using triangle = std::array<vertex, 3>;
  const auto longest_edge = [](const triangle& t, float& length) {
    int edge = 0;
    length = -1.0f;
    for (int k = 0; k < 3; ++k) {
      const float candidate = glm::length(t[static_cast<std::size_t>(k)].position - t[static_cast<std::size_t>((k + 1) % 3)].position);
      if (candidate > length) length = candidate, edge = k;
    }
    return static_cast<std::size_t>(edge);
  };
  // One source triangle at a time, so that the output keeps the source's order (a renderer's
  // early depth test depends on it: a floor's underside drawn first would be shaded in full).
  // A split replaces a triangle by two: the count grows by one per split.
  const std::size_t source_triangles = source.indices.size() / 3;
  if (source_triangles > max_triangles) return std::nullopt;
  std::vector<triangle> pending, done;
  for (std::size_t first = 0; first < source_triangles; ++first) {
    pending.push_back({source.vertices[source.indices[3 * first]], source.vertices[source.indices[3 * first + 1]],
                       source.vertices[source.indices[3 * first + 2]]});
    while (!pending.empty()) {
      const triangle t = pending.back();
      pending.pop_back();
      float length = 0.0f;
      const std::size_t a = longest_edge(t, length), b = (a + 1) % 3, c = (a + 2) % 3;
      if (!(length > max_edge)) {
        done.push_back(t);
        continue;
      }
      if (done.size() + pending.size() + 2 + (source_triangles - first - 1) > max_triangles) return std::nullopt;
      vertex middle;
      middle.position = 0.5f * (t[a].position + t[b].position);  // + commutes: both triangles of the edge get the same bits
      // Equal ends keep their normal and albedo bit for bit (a flat face stays one face).
      const glm::vec3 normal = t[a].normal + t[b].normal;
      middle.normal = t[a].normal == t[b].normal || !(glm::length(normal) > 0.0f) ? t[a].normal : glm::normalize(normal);
      middle.albedo = t[a].albedo == t[b].albedo ? t[a].albedo : 0.5f * (t[a].albedo + t[b].albedo);
      pending.push_back({middle, t[b], t[c]});
      pending.push_back({t[a], middle, t[c]});
    }
  }
  mesh out;
  std::map<std::array<float, 9>, std::uint32_t> index_of;
  for (const triangle& t : done)
    for (const vertex& v : t) {
      const std::array<float, 9> key = {v.position.x, v.position.y, v.position.z, v.normal.x, v.normal.y, v.normal.z, v.albedo.x, v.albedo.y, v.albedo.z};
      const auto [found, inserted] = index_of.emplace(key, static_cast<std::uint32_t>(out.vertices.size()));
      if (inserted) out.vertices.push_back(v);
      out.indices.push_back(found->second);
    }
  return out;
}

}  // namespace vplkit
