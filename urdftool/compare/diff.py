"""``diff``: the structural changes between two robots and their effects, as one result."""

from __future__ import annotations

from dataclasses import dataclass, field

from urdftool.compare.effect import Effects
from urdftool.compare.structure import Change, NotCompared, Renames


@dataclass(frozen=True)
class DiffOptions:
    """tolerance: numbers closer than this are equal (in their own unit: m, rad, kg, ...)
    samples: configurations drawn within the common limits (plus the zero one)
    seed: the random stream of the samples
    chains: (base, tip) link pairs (new names) whose reach is compared
    collisions: compare self-collisions over the samples (FCL)
    companions: compare the SRDF and controller YAML each side has (as ``check`` finds them)
    """

    tolerance: float = 1e-9
    samples: int = 200
    seed: int = 0
    chains: tuple[tuple[str, str], ...] = ()
    collisions: bool = True
    companions: bool = True


@dataclass
class Diff:
    """Two robots compared: their changes, renames, effects, companions' changes, the
    companion files not compared (a side could not read or parse one), warnings."""

    old: str
    new: str
    changes: list[Change]
    renames: Renames
    effects: Effects | None
    companions: list[Change] = field(default_factory=list)
    not_compared: list[NotCompared] = field(default_factory=list)
    warnings: list[str] = field(default_factory=list)

    @property
    def equivalent(self) -> bool:
        """No change in structure or companions, and every file compared: the two describe
        the same robot."""
        return not self.changes and not self.companions and not self.not_compared


def diff(old, new, options: DiffOptions = DiffOptions()) -> Diff:
    """Compare robot ``old`` with robot ``new`` (urdftool Robot objects); the effects only when
    something other than appearance changed. When a side cannot
    be built into a kinematic model, the effects are left out with a warning saying why;
    UnknownLink for a ``chains`` link that a side does not have."""
    from urdftool.compare.effect import effects
    from urdftool.compare.structure import structure

    changes, found = structure(old, new, options.tolerance)
    _known_chains(old, new, found, options.chains)
    result = Diff(old.display, new.display, changes, found, None)
    if any(_physical(change) for change in changes):
        from urdftool.errors import FKError, ModelBuildError

        try:
            result.effects = effects(old, new, found, options.samples, options.seed,
                                     list(options.chains), options.tolerance, options.collisions)
        except (FKError, ModelBuildError) as error:  # the structure is still worth reporting
            result.warnings.append(f"effects not computed: {error}")
    if options.companions:
        from urdftool.compare.companions import compare

        result.companions, result.not_compared = compare(old, new, found)
    return result


def chain_ends(text: str, links) -> tuple[str, str]:
    """(base, tip) of a ``BASE:TIP`` chain named on the command line, split at the ':' that
    names two of ``links`` (a link name may hold ':': ``arm:base:arm:tool0``); with no such ':'
    at the first one with a link on one side, else at the first one, so that the unknown end
    is the one reported (``arm:base:arm:hnd``: 'arm:hnd', not 'arm'). UsageError when
    there is no ':', an end is empty, or two ':' name existing links (``a:b:c`` with links
    ``a``, ``b:c``, ``a:b`` and ``c``), or the chain is one link at both ends (its reach is 0
    on both sides: compared as "equal", where ik and workspace refuse a limb no joint moves)."""
    from urdftool.errors import UsageError

    ends = _split_chain(text, links)
    if ends[0] == ends[1]:
        raise UsageError(f"--chain '{text}' names link '{ends[0]}' at both ends: a chain runs "
                         "between two links")
    return ends


def _split_chain(text: str, links) -> tuple[str, str]:
    from urdftool.errors import UsageError

    splits = [(text[:at], text[at + 1:]) for at, char in enumerate(text) if char == ":"]
    splits = [(base, tip) for base, tip in splits if base and tip]
    if not splits:
        raise UsageError(f"--chain must be BASE:TIP, got '{text}'")
    known = [ends for ends in splits if ends[0] in links and ends[1] in links]
    if len(known) > 1:
        raise UsageError(f"--chain '{text}' names more than one chain: "
                         + ", ".join(f"'{base}' -> '{tip}'" for base, tip in known))
    if known:
        return known[0]
    return next((ends for ends in splits if ends[0] in links or ends[1] in links), splits[0])


def _known_chains(old, new, found, chains) -> None:
    """UnknownLink for a ``chains`` link ``new`` does not have, or ``old`` under its old name,
    whether or not the effects are computed."""
    from urdftool.errors import UnknownLink
    from urdftool.kinematics.tree import beside_the_tree, posed_links

    back = {new_name: old_name for old_name, new_name in found.links.items()}
    for ends in chains:  # (a link beside the tree is in no model: no reach to compare)
        UnknownLink.unless_among(ends, posed_links(new), beside_the_tree(new))
        UnknownLink.unless_among([back.get(name, name) for name in ends], posed_links(old),
                                 beside_the_tree(old))


def _physical(change: Change) -> bool:
    """Whether a change can move a frame, the mass or a collision (a visual or a material
    cannot: the effects are not computed for them)."""
    if change.element == "material":
        return False
    return not (change.element == "link" and change.kind == "changed"
                and change.field.startswith("visual["))
