#include "block_meshes.hpp"

#include <cmath>
#include <numbers>

namespace ide {

namespace {

// A box of half-sizes h centred at c, with flat faces.
void addBox(std::vector<MeshVertex>& out, const float h[3], float cz) {
  // For each axis and sign: the face's two in-plane axes, in an order that keeps it front-facing.
  for (int axis = 0; axis < 3; ++axis)
    for (int sign = -1; sign <= 1; sign += 2) {
      const int u = (axis + (sign > 0 ? 1 : 2)) % 3, v = (axis + (sign > 0 ? 2 : 1)) % 3;
      const float corners[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
      const int order[6] = {0, 1, 2, 0, 2, 3};
      for (int k : order) {
        MeshVertex vert{};
        vert.position[axis] = float(sign) * h[axis];
        vert.position[u] = corners[k][0] * h[u];
        vert.position[v] = corners[k][1] * h[v];
        vert.position[2] += cz;
        vert.normal[axis] = float(sign);
        out.push_back(vert);
      }
    }
}

void addCylinder(std::vector<MeshVertex>& out, float radius, float halfLength, int segments) {
  const float pi2 = 2.0f * std::numbers::pi_v<float>;
  for (int i = 0; i < segments; ++i) {
    const float a0 = pi2 * float(i) / float(segments), a1 = pi2 * float(i + 1) / float(segments);
    const float x0 = std::cos(a0), z0 = std::sin(a0), x1 = std::cos(a1), z1 = std::sin(a1);
    auto side = [&](float x, float z, float y) {
      out.push_back(MeshVertex{{x * radius, y, z * radius}, {x, 0, z}});
    };
    side(x0, z0, -halfLength), side(x1, z1, halfLength), side(x1, z1, -halfLength);
    side(x0, z0, -halfLength), side(x0, z0, halfLength), side(x1, z1, halfLength);
    for (int s = -1; s <= 1; s += 2) {  // the two caps
      const float y = float(s) * halfLength;
      const MeshVertex c{{0, y, 0}, {0, float(s), 0}};
      const MeshVertex p0{{x0 * radius, y, z0 * radius}, {0, float(s), 0}};
      const MeshVertex p1{{x1 * radius, y, z1 * radius}, {0, float(s), 0}};
      out.push_back(c);
      out.push_back(s > 0 ? p1 : p0);  // counter-clockwise seen from outside
      out.push_back(s > 0 ? p0 : p1);
    }
  }
}

void addSphere(std::vector<MeshVertex>& out, float radius, int rings, int segments) {
  const float pi = std::numbers::pi_v<float>;
  auto point = [&](int ring, int seg) {
    const float theta = pi * float(ring) / float(rings), phi = 2.0f * pi * float(seg) / float(segments);
    const float n[3] = {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
    return MeshVertex{{n[0] * radius, n[1] * radius, n[2] * radius}, {n[0], n[1], n[2]}};
  };
  for (int r = 0; r < rings; ++r)
    for (int s = 0; s < segments; ++s) {
      const MeshVertex a = point(r, s), b = point(r + 1, s), c = point(r + 1, s + 1), d = point(r, s + 1);
      out.insert(out.end(), {a, b, c, a, c, d});
    }
}

}  // namespace

std::vector<MeshVertex> blockMesh(BlockShape shape) {
  std::vector<MeshVertex> mesh;
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
      addCylinder(mesh, 0.48f, 0.25f, 32);
      break;
    case BlockShape::Sphere:
      // Catoms 3D are quasi-spherical polyhedra: a coarse sphere shows their facets.
      addSphere(mesh, 0.49f, 8, 12);
      break;
  }
  return mesh;
}

}  // namespace ide
