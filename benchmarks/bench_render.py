"""Benchmark: ``urdftool render`` at 600x600 on the humanoid and on a mesh-heavy corpus robot.

Timed after start-up (the robot loaded and its scene built once, as ``render`` does before it
draws): posing the scene through yourdfpy's graph, shading, ordering and filling every
triangle, and encoding the PNG. The reference, timed in the same run on the same triangles,
is the plainest picture Pillow can make of them: ``ImageDraw.polygon`` once per triangle of
the robot, from the already projected corners (an array, as any numpy pipeline has them), in
the given order, in one flat colour, no PNG. The issue's goal (600x600 in
under 1 s for 100,000 triangles) is reported as seconds per 100,000 triangles.
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
CORPUS = ROOT.parent / "shared" / "corpus"
MESH_HEAVY = "example-robot-data/robots/talos_data/robots/talos_reduced.urdf"
TARGET = 1.5  # ours / Pillow's bare fill of the same triangles


def _bench(name: str, path: Path, target: float | None) -> dict:
    from PIL import Image, ImageDraw

    from benchmarks.timing import best_of as _best_of
    from urdftool.description.load import load
    from urdftool.kinematics.scene import scene_model
    from urdftool.report import picture

    start = time.perf_counter()
    robot = load(path)
    model = scene_model(robot)
    setup = time.perf_counter() - start
    options = picture.PictureOptions("iso", (600, 600))

    def ours():
        return picture.png([picture.Layer(model.pose({}))], options)

    scene = model.pose({})
    camera = picture._camera([picture.Layer(scene)], "iso", 600, 600)
    corners = camera.pixels(scene.triangles).reshape(-1, 6)
    filled = len(picture._project(picture.Layer(scene), camera).corners)

    def bare():
        image = Image.new("RGB", (600, 600), "white")
        draw = ImageDraw.Draw(image)
        for polygon in corners.tolist():
            draw.polygon(polygon, fill=(128, 128, 128))

    ours_time, bare_time = _best_of(ours), _best_of(bare)
    triangles = len(scene.triangles)
    per_100k = ours_time / triangles * 100_000
    print(f"render {name}: {triangles} triangles ({filled} filled: faces of closed surfaces "
          f"turned away left out, long ones split), load + scene {setup:.2f} s, picture "
          f"{ours_time:.3f} s ({per_100k:.2f} s per 100k triangles; goal < 1), Pillow's bare "
          f"fill {bare_time:.3f} s, ratio {ours_time / bare_time:.2f}"
          + (f" (target <= {target})" if target else " (no target: fixed costs dominate)"))
    return {"name": f"render_600x600_{name}", "ratio": ours_time / bare_time,
            "target": target, "triangles": triangles, "filled": filled, "render_s": ours_time,
            "pillow_fill_s": bare_time, "s_per_100k_triangles": per_100k,
            "load_and_scene_s": setup}


def main() -> list[dict]:
    # a few thousand triangles: fixed costs (PNG encoding, posing) dominate, no ratio target
    results = [_bench("humanoid", ROOT / "robots" / "humanoid" / "humanoid.urdf.xacro", None)]
    if (CORPUS / MESH_HEAVY).is_file():
        results.append(_bench("talos_meshes", CORPUS / MESH_HEAVY, TARGET))
    else:
        print(f"render: corpus robot {MESH_HEAVY} not found under {CORPUS}; skipped")
    return results


if __name__ == "__main__":
    main()
