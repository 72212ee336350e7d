"""GLB files of one node whose transform a test chooses (matrix, rotation, scale): for the tests
of how urdftool reads a glTF node's transform (description/meshes, U416)."""

from __future__ import annotations

import json
import struct

import pytest


def glb_with_node(path, **node):
    """A GLB of a 10 cm cube whose one node carries ``node``'s keys (matrix, rotation, scale),
    as trimesh exports it and the key patched into its JSON."""
    def patch(header):
        for entry in header["nodes"]:
            if "mesh" in entry:
                for key in ("matrix", "translation", "rotation", "scale"):
                    entry.pop(key, None)
                entry.update(node)

    _write(path, patch)


def glb_with_chain(path, depth: int):
    """A GLB of a 10 cm cube at the end of ``depth`` nodes, each the child of the one before."""
    def patch(header):
        header["nodes"] = [{"children": [i + 1]} for i in range(depth - 1)] + [{"mesh": 0}]
        header["scenes"], header["scene"] = [{"nodes": [0]}], 0

    _write(path, patch)


def _write(path, patch):
    trimesh = pytest.importorskip("trimesh")
    scene = trimesh.Scene()
    scene.add_geometry(trimesh.creation.box((0.1, 0.1, 0.1)), node_name="n")
    data = scene.export(file_type="glb")
    size = struct.unpack("<I", data[12:16])[0]
    header = json.loads(data[20:20 + size])
    patch(header)
    text = json.dumps(header).encode()
    text += b" " * (-len(text) % 4)
    data = data[:12] + struct.pack("<I", len(text)) + b"JSON" + text + data[20 + size:]
    path.write_bytes(data[:8] + struct.pack("<I", len(data)) + data[12:])


def column_major(*rows):
    return [float(rows[r][c]) for c in range(4) for r in range(4)]  # glTF: column-major
