#include "simcore/gltf_export.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace simcore {

namespace {

// GLB is little-endian; the writer copies floats, indices and lengths as they are in memory.
static_assert(std::endian::native == std::endian::little, "gltf_export writes little-endian data as is");

// One shape of unit size, centred on the origin, as glTF wants it: positions and normals
// (float x, y, z each) and triangles (counter-clockwise seen from outside).
struct Shape {
  std::vector<float> positions, normals;
  std::vector<std::uint16_t> indices;

  void vertex(double x, double y, double z, double nx, double ny, double nz) {
    positions.insert(positions.end(), {float(x), float(y), float(z)});
    normals.insert(normals.end(), {float(nx), float(ny), float(nz)});
  }
};

Shape cube() {  // side 1: per face four corners, so that each face has its own normal
  Shape s;
  for (int axis = 0; axis < 3; ++axis) {
    for (int sign : {1, -1}) {
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      const auto first = std::uint16_t(s.positions.size() / 3);
      const double corners[4][2] = {{-0.5, -0.5}, {0.5, -0.5}, {0.5, 0.5}, {-0.5, 0.5}};
      for (int k = 0; k < 4; ++k) {
        const auto& c = corners[sign > 0 ? k : 3 - k];  // reversed on the negative side: still outward
        double p[3], n[3] = {0, 0, 0};
        p[axis] = 0.5 * sign;
        p[u] = c[0];
        p[v] = c[1];
        n[axis] = sign;
        s.vertex(p[0], p[1], p[2], n[0], n[1], n[2]);
      }
      s.indices.insert(s.indices.end(), {first, std::uint16_t(first + 1), std::uint16_t(first + 2), first,
                                         std::uint16_t(first + 2), std::uint16_t(first + 3)});
    }
  }
  return s;
}

Shape sphere() {  // diameter 1, 8 stacks of 16 slices
  constexpr int kStacks = 8, kSlices = 16;
  const double pi = std::acos(-1.0);
  Shape s;
  for (int i = 0; i <= kStacks; ++i) {
    const double theta = pi * i / kStacks;
    for (int j = 0; j <= kSlices; ++j) {
      const double phi = 2 * pi * j / kSlices;
      const double x = std::sin(theta) * std::cos(phi), y = std::cos(theta),
                   z = std::sin(theta) * std::sin(phi);
      s.vertex(0.5 * x, 0.5 * y, 0.5 * z, x, y, z);
    }
  }
  for (int i = 0; i < kStacks; ++i)
    for (int j = 0; j < kSlices; ++j) {
      const auto a = std::uint16_t(i * (kSlices + 1) + j), b = std::uint16_t(a + kSlices + 1);
      s.indices.insert(s.indices.end(),
                       {a, std::uint16_t(a + 1), b, std::uint16_t(a + 1), std::uint16_t(b + 1), b});
    }
  return s;
}

std::string number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", std::abs(v) < 5e-7 ? 0.0 : v);
  return text;
}

template <class T>
void append(std::string& bin, const std::vector<T>& values) {
  const std::size_t at = bin.size();
  bin.resize(at + values.size() * sizeof(T));
  std::memcpy(bin.data() + at, values.data(), values.size() * sizeof(T));
  bin.resize((bin.size() + 3) / 4 * 4, '\0');
}

// The buffer views and accessors of the shape (positions 0, normals 1, indices 2), scaled to `size`.
std::string geometry(Shape shape, double size, std::string& bin) {
  float lo[3] = {1e30f, 1e30f, 1e30f}, hi[3] = {-1e30f, -1e30f, -1e30f};
  for (std::size_t i = 0; i < shape.positions.size(); ++i) {
    float& p = shape.positions[i];
    p = float(p * size);
    lo[i % 3] = std::min(lo[i % 3], p);
    hi[i % 3] = std::max(hi[i % 3], p);
  }
  const std::size_t positionsAt = bin.size();
  append(bin, shape.positions);
  const std::size_t normalsAt = bin.size();
  append(bin, shape.normals);
  const std::size_t indicesAt = bin.size();
  append(bin, shape.indices);
  const std::size_t vertices = shape.positions.size() / 3;
  auto view = [](std::size_t offset, std::size_t bytes, int target) {
    return "{\"buffer\":0,\"byteOffset\":" + std::to_string(offset) +
           ",\"byteLength\":" + std::to_string(bytes) + ",\"target\":" + std::to_string(target) + "}";
  };
  return "\"bufferViews\":[" + view(positionsAt, vertices * 12, 34962) + "," +
         view(normalsAt, vertices * 12, 34962) + "," + view(indicesAt, shape.indices.size() * 2, 34963) +
         "],\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":" + std::to_string(vertices) +
         ",\"type\":\"VEC3\",\"min\":[" + number(lo[0]) + "," + number(lo[1]) + "," + number(lo[2]) +
         "],\"max\":[" + number(hi[0]) + "," + number(hi[1]) + "," + number(hi[2]) +
         "]},{\"bufferView\":1,\"componentType\":5126,\"count\":" + std::to_string(vertices) +
         ",\"type\":\"VEC3\"},{\"bufferView\":2,\"componentType\":5123,\"count\":" +
         std::to_string(shape.indices.size()) + ",\"type\":\"SCALAR\"}]";
}

void writeChunk(std::ostream& out, std::uint32_t type, const std::string& bytes) {
  const auto length = std::uint32_t(bytes.size());
  out.write(reinterpret_cast<const char*>(&length), 4);
  out.write(reinterpret_cast<const char*>(&type), 4);
  out.write(bytes.data(), std::streamsize(bytes.size()));
}

// One material, and one mesh using it, per colour (glTF binds materials to a mesh's primitives);
// `meshOf` gets each colour's mesh number.
std::string materialsAndMeshes(std::map<std::uint32_t, std::size_t>& meshOf) {
  std::string materials = "\"materials\":[", meshes = "\"meshes\":[";
  std::size_t next = 0;
  char item[256];
  for (auto& [color, mesh] : meshOf) {
    mesh = next++;
    const char* comma = mesh ? "," : "";
    const auto channel = [c = color](int shift) { return double((c >> shift) & 0xFF) / 255.0; };
    std::snprintf(item, sizeof item,
                  "%s{\"name\":\"#%06X\",\"pbrMetallicRoughness\":{\"baseColorFactor\":[%.4g,%.4g,%.4g,1],"
                  "\"metallicFactor\":0,\"roughnessFactor\":0.6}}",
                  comma, unsigned(color & 0xFFFFFF), channel(16), channel(8), channel(0));
    materials += item;
    std::snprintf(
        item, sizeof item,
        "%s{\"primitives\":[{\"attributes\":{\"POSITION\":0,\"NORMAL\":1},\"indices\":2,\"material\":%zu}]}",
        comma, mesh);
    meshes += item;
  }
  return materials + "]," + meshes + "]";
}

constexpr std::uint32_t kMobileColor = 0xE08020;  // mobiles: orange slabs
constexpr double kMobileThicknessMm = 5;

// A node per block at its position (metres, +Y up), then one per mobile, and the scene of them all.
std::string nodes(const Simulation& sim, double size, const std::map<std::uint32_t, std::size_t>& meshOf) {
  std::string list = "\"nodes\":[", scene = "\"scenes\":[{\"nodes\":[";
  const BlockVector& blocks = sim.world().blocks();
  char item[192];
  for (std::size_t id = 0; id < blocks.size(); ++id) {
    const Vec3 p = sim.position(BlockId(id));
    const char* comma = id ? "," : "";
    std::snprintf(item, sizeof item, "%s{\"name\":\"block %zu\",\"mesh\":%zu,\"translation\":[%s,%s,%s]}",
                  comma, id, meshOf.at(blocks[id].color), number(p.x * size).c_str(),
                  number(p.z * size).c_str(), number(-p.y * size).c_str());
    list += item;
    std::snprintf(item, sizeof item, "%s%zu", comma, id);
    scene += item;
  }
  // Mobiles (Smart Blocks with physics): the block's cube scaled to a thin slab lying on the blocks,
  // turned about the vertical by the mobile's angle.
  if (const Physics* physics = sim.physics())
    for (std::size_t i = 0; i < physics->mobileCount(); ++i) {
      const MobileSpec& m = physics->spec(i);
      const Eigen::Vector2d at = physics->positionMm(i) / 1000.0;
      const double half = physics->angleDeg(i) * M_PI / 360.0, thick = kMobileThicknessMm / 1000.0;
      const std::size_t node = blocks.size() + i;
      std::snprintf(item, sizeof item, ",{\"name\":\"mobile %zu\",\"mesh\":%zu,\"translation\":[%s,%s,%s],",
                    i, meshOf.at(kMobileColor), number(at.x()).c_str(), number(size / 2 + thick / 2).c_str(),
                    number(-at.y()).c_str());
      list += item;
      std::snprintf(item, sizeof item, "\"rotation\":[0,%s,0,%s],\"scale\":[%s,%s,%s]}",
                    number(std::sin(half)).c_str(), number(std::cos(half)).c_str(),
                    number(m.lxMm / 1000.0 / size).c_str(), number(thick / size).c_str(),
                    number(m.lyMm / 1000.0 / size).c_str());
      list += item;
      std::snprintf(item, sizeof item, ",%zu", node);
      scene += item;
    }
  return list + "]," + scene + "]}]";
}

}  // namespace

void exportGltf(const Simulation& sim, std::ostream& out) {
  const TargetSpec& target = sim.target();
  const double size = target.blockSizeMm / 1000.0;
  const bool round = target.shape == BodyShape::Sphere;
  std::string bin;
  std::string json = "{\"asset\":{\"version\":\"2.0\",\"generator\":\"vsim (meld toolchain)\"},\"scene\":0,";
  json += geometry(round ? sphere() : cube(), size, bin);
  json += ",\"buffers\":[{\"byteLength\":" + std::to_string(bin.size()) + "}],";
  std::map<std::uint32_t, std::size_t> meshOf;
  for (const Block& b : sim.world().blocks()) meshOf.emplace(b.color, 0);
  if (sim.physics() && sim.physics()->mobileCount()) meshOf.emplace(kMobileColor, 0);
  json += materialsAndMeshes(meshOf);  // numbers the meshes: before nodes() reads them
  json += ',';
  json += nodes(sim, size, meshOf);
  json += '}';
  json.resize((json.size() + 3) / 4 * 4, ' ');  // chunks are 4-byte aligned: JSON pads with spaces

  const std::uint64_t total = 12 + 8 + json.size() + 8 + bin.size();
  if (total > 0xFFFFFFFFu)  // GLB's lengths are 32-bit
    throw std::runtime_error("the world is too large for one glTF binary file (" +
                             std::to_string(total >> 20) + " MiB; at most 4 GiB)");
  const std::uint32_t header[3] = {0x46546C67u, 2u, std::uint32_t(total)};
  out.write(reinterpret_cast<const char*>(header), sizeof header);
  writeChunk(out, 0x4E4F534Au, json);  // "JSON"
  writeChunk(out, 0x004E4942u, bin);   // "BIN\0"
  if (!out) throw std::runtime_error("cannot write the glTF file");
}

}  // namespace simcore
