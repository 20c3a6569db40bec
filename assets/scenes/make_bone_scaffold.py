#!/usr/bin/env python3
"""Writes bone_scaffold.strata.json: the paper's Fig. 1 scene (Zhao et al. 2011), "Bone, offset
of Bone, and cellular-scaffold".

- cortical shell: the femur (../meshes/femur.off scaled to a 100 mm segment) minus its inward
  offset by CORTEX mm (a true Euclidean offset node, not a scaled copy);
- porous core: that offset (an instance of the offset node, so it is evaluated once) intersected
  with 3 x 3 x 3 tiles of the strut lattice ../meshes/scaffold_cell.obj (14 x 12 x 34 mm, 263
  struts of radius 0.4 mm on a 2 mm pitch), united by a left-deep chain of 26 unions as the
  paper's tree is: depth 29.

The tile (a hidden mesh node) is shared by 27 instances. Run with no arguments from this folder
to rewrite the scene (deterministic output); re-run after changing either mesh, so that the
recorded content hashes match.
"""
import json
import os

HERE = os.path.dirname(os.path.abspath(__file__))
CORTEX = 2.0  # cortical wall thickness, mm
TILE = (14.0, 12.0, 34.0)  # must match make_scaffold_cell.py


def content_hash(path):
    """engine/io/scene_file.cpp hashFile: FNV-1a 64 over the bytes, then Hasher's avalanche."""
    mask = (1 << 64) - 1
    h = 0xCBF29CE484222325
    with open(path, "rb") as f:
        for b in f.read():
            h = ((h ^ b) * 0x100000001B3) & mask
    h ^= h >> 33
    h = (h * 0xFF51AFD7ED558CCD) & mask
    h ^= h >> 33
    h = (h * 0xC4CEB9FE1A85EC53) & mask
    h ^= h >> 33
    return "fnv1a64:%016x" % h


def transform(translate=(0, 0, 0), scale=(1, 1, 1)):
    return {"translate": list(translate), "rotate": [0, 0, 0], "scale": list(scale)}


def mesh(node_id, name, rel_path, scale, color, visible=True):
    node = {
        "id": node_id,
        "name": name,
        "type": "mesh",
        "path": rel_path,
        "hash": content_hash(os.path.join(HERE, rel_path)),
        "transform": transform(scale=(scale,) * 3),
        "color": color,
    }
    if not visible:
        node["visible"] = False
    return node


def operation(node_id, name, kind, children, **members):
    node = {"id": node_id, "name": name, "type": kind}
    node.update(members)
    node["transform"] = transform()
    node["children"] = children
    return node


def main():
    bone = [0.93, 0.88, 0.78]
    lattice = [0.85, 0.6, 0.35]
    femur = mesh(1, "femur", "../meshes/femur.off", 100.0, bone)
    core = operation(2, "femur core", "offset", [{"id": 3, "name": "femur (core)", "type": "instance", "of": 1, "transform": transform()}], distance=-CORTEX)
    cell = mesh(4, "scaffold cell", "../meshes/scaffold_cell.obj", 1.0, lattice, visible=False)

    next_id = 10
    tiles = []
    for k in (-1, 0, 1):
        for j in (-1, 0, 1):
            for i in (-1, 0, 1):
                name = "cell %d%d%d" % (i + 1, j + 1, k + 1)
                at = (i * TILE[0], j * TILE[1], k * TILE[2])
                tiles.append({"id": next_id, "name": name, "type": "instance", "of": 4, "transform": transform(at)})
                next_id += 1
    chain = tiles[0]
    for n, tile in enumerate(tiles[1:], start=2):
        chain = operation(next_id, "scaffold %d" % n, "union", [chain, tile])
        next_id += 1

    core_instance = {"id": next_id, "name": "core", "type": "instance", "of": 2, "transform": transform()}
    next_id += 1
    shell = operation(next_id, "cortical shell", "difference", [femur, core])
    next_id += 1
    porous = operation(next_id, "porous core", "intersection", [core_instance, chain])
    next_id += 1
    root = operation(next_id, "bone scaffold", "union", [shell, porous, cell])
    scene = {
        "format": "strata-scene",
        "version": 2,
        "unit": "millimetre",
        "settings": {"resolution": 512, "margin": 0.05},
        "root": root,
    }
    with open(os.path.join(HERE, "bone_scaffold.strata.json"), "w") as f:
        json.dump(scene, f, indent=1)
        f.write("\n")


if __name__ == "__main__":
    main()
