"""What loading a robot takes besides its file: the companion files the user named and the
limits on its meshes. Kept apart from the loader so that the settings, the runner and the
result cache handle them without importing it (a re-run served from the cache never does)."""

from __future__ import annotations

from pathlib import Path

from urdftool.records import Frozen

MAX_TRIANGLES = 2_000_000
MAX_MESH_BYTES = 128 * 1024 * 1024


class SettingValue(str):
    """A xacro argument's value that a repository's settings file gave (``per-file-args``):
    data for the expansion, never a folder included files may come from (a value given on the
    command line is one, see :func:`urdftool.description.load.load`)."""

    __slots__ = ()


class MeshLimits(Frozen):
    """How many triangles and bytes a mesh may have to be read."""

    max_triangles: int
    max_bytes: int

    __slots__ = ("max_triangles", "max_bytes")

    def __init__(self, max_triangles: int = MAX_TRIANGLES,
                 max_bytes: int = MAX_MESH_BYTES) -> None:
        set_field = object.__setattr__
        set_field(self, "max_triangles", max_triangles)
        set_field(self, "max_bytes", max_bytes)


class CompanionPaths(Frozen):
    """Companion files named by the user (``check --controllers/--srdf/--spec`` or the settings
    file); what is not named is discovered beside the robot (:mod:`.companions`)."""

    controllers: tuple[Path, ...]
    srdf: Path | None
    spec: Path | None

    __slots__ = ("controllers", "srdf", "spec")

    def __init__(self, controllers: tuple[Path, ...] = (), srdf: Path | None = None,
                 spec: Path | None = None) -> None:
        set_field = object.__setattr__
        set_field(self, "controllers", controllers)
        set_field(self, "srdf", srdf)
        set_field(self, "spec", spec)
        self.__post_init__()

    def __post_init__(self):
        object.__setattr__(self, "controllers", tuple(Path(p) for p in self.controllers or ()))
        for kind in ("srdf", "spec"):
            if getattr(self, kind) is not None:
                object.__setattr__(self, kind, Path(getattr(self, kind)))

    def named(self) -> list[Path]:
        """Every file named."""
        return [*self.controllers, *(p for p in (self.srdf, self.spec) if p is not None)]

    def overridden_by(self, other: "CompanionPaths") -> "CompanionPaths":
        """These paths with every one ``other`` names replaced (the command line wins)."""
        return CompanionPaths(other.controllers or self.controllers, other.srdf or self.srdf,
                              other.spec or self.spec)
