#!/usr/bin/env python3
"""Reads a .glb written by vsim --export-gltf as a glTF 2.0 reader would, checks its structure
(header, chunks, buffer views and accessors inside the buffer, node and mesh references) and
prints "nodes N materials M meshes K shape S" (S: the vertex count of the shape), then a line
"#rrggbb COUNT" per material with the number of nodes drawn in it, by decreasing count."""
import json
import struct
import sys

data = open(sys.argv[1], "rb").read()
magic, version, length = struct.unpack_from("<III", data, 0)
assert magic == 0x46546C67, "not a glTF binary (magic)"
assert version == 2, f"glTF version {version}"
assert length == len(data), f"header length {length} != file size {len(data)}"
json_length, json_type = struct.unpack_from("<II", data, 12)
assert json_type == 0x4E4F534A and json_length % 4 == 0, "first chunk is not 4-aligned JSON"
doc = json.loads(data[20:20 + json_length])
bin_at = 20 + json_length
bin_length, bin_type = struct.unpack_from("<II", data, bin_at)
assert bin_type == 0x004E4942, "second chunk is not BIN"
assert bin_at + 8 + bin_length == len(data), "BIN chunk does not end the file"
assert doc["asset"]["version"] == "2.0"
assert doc["buffers"][0]["byteLength"] <= bin_length
for view in doc["bufferViews"]:
    assert view["byteOffset"] + view["byteLength"] <= doc["buffers"][0]["byteLength"], "view outside buffer"
sizes = {5126: 4, 5123: 2}
counts = {"VEC3": 3, "SCALAR": 1}
for acc in doc["accessors"]:
    view = doc["bufferViews"][acc["bufferView"]]
    assert acc["count"] * sizes[acc["componentType"]] * counts[acc["type"]] <= view["byteLength"]
position = doc["accessors"][0]
assert "min" in position and "max" in position, "POSITION accessor without bounds"
vertices = position["count"]
index_view = doc["bufferViews"][doc["accessors"][2]["bufferView"]]
offset = index_view["byteOffset"]
indices = struct.unpack_from(f"<{doc['accessors'][2]['count']}H", data, bin_at + 8 + offset)
assert max(indices) < vertices and len(indices) % 3 == 0, "bad triangle indices"
for mesh in doc["meshes"]:
    for prim in mesh["primitives"]:
        assert prim["material"] < len(doc["materials"])
for node in doc["nodes"]:
    assert node["mesh"] < len(doc["meshes"]) and len(node["translation"]) == 3
assert sorted(doc["scenes"][doc["scene"]]["nodes"]) == list(range(len(doc["nodes"])))
print(f"nodes {len(doc['nodes'])} materials {len(doc['materials'])} meshes {len(doc['meshes'])} shape {vertices}")
uses = {}
for node in doc["nodes"]:
    for prim in doc["meshes"][node["mesh"]]["primitives"]:
        name = doc["materials"][prim["material"]]["name"].lower()
        uses[name] = uses.get(name, 0) + 1
for name, count in sorted(uses.items(), key=lambda item: (-item[1], item[0])):
    print(name, count)
