"""``urdftool collisions`` renderers write to the stream they are given."""

from __future__ import annotations

import io

from urdftool.collision.pose import Contact, PoseReport
from urdftool.report import collisions as render


def _report(srdf=None):
    touching = Contact("a", "b", True, 0.0, 0.002, "Adjacent")
    hit = Contact("a", "c", True, 0.0, 0.01, "")
    apart = Contact("b", "c", False, 0.25, 0.0, "User")
    return PoseReport({"j": 0.5}, [hit, touching], [apart], ["cam"], [], srdf)


def test_pose_text_names_the_srdf_forbidden_pairs_and_visual_only_links():
    stream = io.StringIO()
    render.pose_text("bot", _report("config/bot.srdf"), custom=True, stream=stream)
    text = stream.getvalue()
    assert text.startswith("bot at the given configuration (1 joint), SRDF: config/bot.srdf\n")
    assert "COLLIDING" in text and "1 adjacent pair(s) overlap at their joints (allowed): a/b" \
        in text
    assert "250.00" in text and "disabled (User)" in text
    assert "(they escape every check): cam" in text
    assert text.rstrip().endswith("1 colliding pair(s) not allowed by adjacency or the SRDF")


def test_pose_json_keeps_the_report_fields():
    data = render.pose_json("bot", _report())
    assert data["srdf"] is None and data["q"] == {"j": 0.5}
    assert [c["link2"] for c in data["colliding"]] == ["c", "b"]
    assert data["closest"][0]["allowed"] == "User" and data["visual_only"] == ["cam"]
