#include "block_meshes.hpp"

#include <cmath>
#include <numbers>

namespace ide {

namespace {

std::uint16_t add(Mesh& m, const MeshVertex& v) {
  m.vertices.push_back(v);
  return std::uint16_t(m.vertices.size() - 1);
}

void quad(Mesh& m, std::uint16_t a, std::uint16_t b, std::uint16_t c, std::uint16_t d) {
  m.indices.insert(m.indices.end(), {a, b, c, a, c, d});
}

// A box of half-sizes h centred at (0, 0, cz), with flat faces (4 vertices each).
void addBox(Mesh& m, const float h[3], float cz) {
  for (int axis = 0; axis < 3; ++axis)
    for (int sign = -1; sign <= 1; sign += 2) {
      // The face's in-plane axes, in an order that makes (u, v, axis) right-handed for sign > 0.
      const int u = (axis + (sign > 0 ? 1 : 2)) % 3, v = (axis + (sign > 0 ? 2 : 1)) % 3;
      const float corners[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
      std::uint16_t ids[4];
      for (int k = 0; k < 4; ++k) {
        MeshVertex vert{};
        vert.position[axis] = float(sign) * h[axis];
        vert.position[u] = corners[k][0] * h[u];
        vert.position[v] = corners[k][1] * h[v];
        vert.position[2] += cz;
        vert.normal[axis] = float(sign);
        ids[k] = add(m, vert);
      }
      quad(m, ids[0], ids[1], ids[2], ids[3]);
    }
}

void addCylinder(Mesh& m, float radius, float halfLength, int segments) {
  const float pi2 = 2.0f * std::numbers::pi_v<float>;
  const auto base = std::uint16_t(m.vertices.size());
  for (int i = 0; i <= segments; ++i) {  // the side: a ring at each end, smooth normals
    const float a = pi2 * float(i) / float(segments), x = std::cos(a), z = std::sin(a);
    add(m, MeshVertex{{x * radius, -halfLength, z * radius}, {x, 0, z}});
    add(m, MeshVertex{{x * radius, halfLength, z * radius}, {x, 0, z}});
  }
  for (int i = 0; i < segments; ++i) {
    const auto a = std::uint16_t(base + 2 * i);
    quad(m, a, std::uint16_t(a + 1), std::uint16_t(a + 3), std::uint16_t(a + 2));
  }
  for (int s = -1; s <= 1; s += 2) {  // the caps: a fan around the centre
    const float y = float(s) * halfLength;
    const std::uint16_t centre = add(m, MeshVertex{{0, y, 0}, {0, float(s), 0}});
    for (int i = 0; i <= segments; ++i) {
      const float a = pi2 * float(i) / float(segments);
      add(m, MeshVertex{{std::cos(a) * radius, y, std::sin(a) * radius}, {0, float(s), 0}});
    }
    for (int i = 0; i < segments; ++i) {
      const auto p0 = std::uint16_t(centre + 1 + i), p1 = std::uint16_t(centre + 2 + i);
      // Counter-clockwise seen from outside: angles run clockwise seen from +y.
      m.indices.insert(m.indices.end(), {centre, s > 0 ? p1 : p0, s > 0 ? p0 : p1});
    }
  }
}

void addSphere(Mesh& m, float radius, int rings, int segments) {
  const float pi = std::numbers::pi_v<float>;
  const auto base = std::uint16_t(m.vertices.size());
  for (int r = 0; r <= rings; ++r)
    for (int s = 0; s <= segments; ++s) {
      const float theta = pi * float(r) / float(rings), phi = 2.0f * pi * float(s) / float(segments);
      const float n[3] = {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
      add(m, MeshVertex{{n[0] * radius, n[1] * radius, n[2] * radius}, {n[0], n[1], n[2]}});
    }
  const int row = segments + 1;
  for (int r = 0; r < rings; ++r)
    for (int s = 0; s < segments; ++s) {
      const auto a = std::uint16_t(base + r * row + s);
      quad(m, a, std::uint16_t(a + row), std::uint16_t(a + row + 1), std::uint16_t(a + 1));
    }
}

}  // namespace

Mesh blockMesh(BlockShape shape) {
  Mesh mesh;
  // A little smaller than the cell, so that neighbouring blocks stay apart on screen.
  switch (shape) {
    case BlockShape::Cube: {
      const float h[3] = {0.46f, 0.46f, 0.46f};
      addBox(mesh, h, 0);
      break;
    }
    case BlockShape::Tile: {
      const float h[3] = {0.46f, 0.46f, 0.12f};
      addBox(mesh, h, -0.38f);
      break;
    }
    case BlockShape::Cylinder:
      addCylinder(mesh, 0.48f, 0.25f, 24);
      break;
    case BlockShape::Sphere:
      // Catoms 3D are quasi-spherical polyhedra: a coarse sphere shows their facets.
      addSphere(mesh, 0.49f, 8, 12);
      break;
  }
  return mesh;
}

}  // namespace ide
