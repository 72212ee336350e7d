"""Meshes as numpy arrays, read and measured without trimesh where the format allows.

A binary STL is an 84-byte header and 50-byte records, an ASCII STL a list of ``vertex``
lines: both are read here straight into the vertex and face arrays that ``trimesh.load(...,
process=True)`` builds of them (vertices merged to 1e-8 as trimesh merges them, the first of
equal ones kept, in order of first use). A COLLADA file gives trimesh's triangles through
:func:`.collada.read_collada` (lxml), and a plain OBJ (vertices, texture coordinates, normals,
triangles) is read directly. Their corners are merged by position as an STL's are, where
trimesh keeps apart corners whose normal or texture coordinate differs: such a seam is no
hole, and a closed mesh with seams is watertight here (trimesh calls it open). What the rules
need of a mesh is then measured the way trimesh measures it (bounds, watertightness, volume,
centre of mass and inertia of a closed mesh, the convex hull of an open one), so that checking
a robot imports neither trimesh nor pycollada; tests compare every measure with trimesh's on
the public corpus.

:func:`read` returns None for anything it is not sure to read as trimesh would (another
format, several solids, text that is not UTF-8, non-finite coordinates, a length that does not
match the header, no triangles, OBJ materials or polygons): trimesh then reads the file and
says what is wrong with it. numpy, scipy and lxml are imported inside the functions.
"""

from __future__ import annotations

import functools
import math
from pathlib import Path

from urdftool.description.inputs import MAX_TRIANGLES
from urdftool.numbers import power

_HEADER = 84  # [bytes]: 80 of text, the triangle count
_RECORD = 50  # [bytes]: normal, three vertices (12 float32) and a 2-byte attribute
MERGE_DIGITS = 8  # trimesh merges vertices equal to 1e-8 (tol.merge)


def read(path: Path, data: bytes, max_triangles: int = MAX_TRIANGLES):
    """(vertices (n, 3) float64, faces (m, 3) int64) of an STL, COLLADA or plain OBJ file:
    trimesh's triangles, corners merged by position (see the module docstring), or None when
    trimesh should read it. ``data``: the file's bytes (read by the caller, under the mesh
    size limit). Raises :class:`.collada.ColladaProblem` for a COLLADA file that is malformed
    (``not_well_formed`` when its XML is) or holds over ``max_triangles`` triangles."""
    found = read_unmerged(path, data, max_triangles)
    return None if found is None else merged(*found)


def read_unmerged(path: Path, data: bytes, max_triangles: int = MAX_TRIANGLES):
    """What :func:`read` gives before :func:`merged`: the triangles' corners as the file
    holds them (every vertex used by a face), or None; raises as :func:`read` does. The faces
    of an STL and an OBJ are None: each three corners in order are a triangle (an array of
    them would be ``np.arange(len(corners)).reshape(-1, 3)``, a third of the corners' bytes
    allocated, filled and gathered through for nothing)."""
    suffix = path.suffix.lower()
    if suffix == ".dae":
        return _collada(data, max_triangles)
    if suffix == ".obj":
        try:
            return _obj(data, max_triangles)
        except (ValueError, IndexError):  # trimesh reads it and says what is wrong
            return None
    if suffix != ".stl":
        return None
    raw = _stl_binary(data)
    if raw is None and not binary_stl(data):
        raw = _stl_ascii(data)  # trimesh's order: binary when the length fits, else ASCII
    if raw is None:
        return None
    import numpy as np

    if not np.isfinite(raw).all():
        return None  # trimesh drops the faces of such vertices: let it
    return raw, None


def _count(data: bytes) -> int:
    return int.from_bytes(data[80:84], "little") if len(data) >= _HEADER else -1


def binary_stl(data: bytes) -> bool:
    """Whether an STL file's ``data`` is read as binary, as trimesh decides: its header's
    triangle count fits its length (else it is read as ASCII)."""
    return len(data) >= _HEADER and len(data) == _HEADER + _RECORD * _count(data)


def _stl_binary(data: bytes):
    import numpy as np

    if _count(data) <= 0 or not binary_stl(data):
        return None
    # the corners are read in one copy, straight to float64 (the normals and attributes are
    # skipped by the record's layout); the (count, 3, 3) array is contiguous, so it is
    # reshaped without another copy
    return np.frombuffer(data, dtype=_STL_RECORD, offset=_HEADER)["vertices"].astype(
        np.float64).reshape(-1, 3)


_STL_RECORD = [("normal", "<f4", 3), ("vertices", "<f4", (3, 3)), ("attribute", "<u2")]


def _stl_ascii(data: bytes):
    """The vertices of an ASCII STL of one solid, split and parsed as trimesh does; None when
    a word is no number (trimesh then says what is wrong with it)."""
    import warnings

    import numpy as np

    try:
        text = data.decode("utf-8").strip().lower()
    except UnicodeDecodeError:
        return None
    start, end = text.find("solid"), text.find("endsolid")
    if start < 0 or end < 0 or start > end or text.find("solid", end + 8) >= 0:
        return None  # none, or several solids: trimesh's scene of them
    pieces = text[start:end].split("vertex")[1:]
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # fromstring warns, or raises, and stops at a word
        try:
            vertices = np.fromstring(" ".join(line[:line.find("\n")] for line in pieces),
                                     sep=" ", dtype=np.float64) if pieces else np.zeros(0)
        except (ValueError, DeprecationWarning):
            return None
    if len(vertices) < 9 or len(vertices) % 9:
        return None
    return vertices.reshape(-1, 3)


def _collada(data: bytes, max_triangles: int):
    """A COLLADA document's triangles as :func:`.collada.read_collada` reads them (trimesh's
    triangles, in the file's unit). None when it holds no triangles;
    :class:`.collada.ColladaProblem` when it is malformed or too large."""
    from urdftool.description.collada import read_collada

    vertices, faces = read_collada(data, max_triangles=max_triangles)
    return (vertices, faces) if len(faces) else None


# ASCII white space as ``str.split()`` and the ``\\s`` of a regular expression know it
_WHITE = b" \t\n\r\x0b\x0c\x1c\x1d\x1e\x1f"
_OBJ_KINDS = (b"v ", b"vt ", b"vn ", b"f ", b"o ", b"s ")  # the statements of a plain OBJ
_OBJ_ITEMS = {b"v ": 3, b"vt ": 2, b"vn ": 3, b"f ": 3}  # the words each row holds


def _obj(data: bytes, max_triangles: int = MAX_TRIANGLES):
    """A plain OBJ's triangles as trimesh loads them: ``v`` (3 numbers), ``vt`` (2), ``vn``
    (3) and triangular ``f`` lines of one corner form (``v``, ``v/t``, ``v//n``, ``v/t/n``,
    positive indices), at most ``o`` and ``s`` besides, and comments; corners merged by position
    (trimesh keeps apart those whose texture coordinate or normal differs: a seam, no hole).
    None for anything else (materials, groups, polygons, colours, negative indices, a word
    that is no number, text other than ASCII outside comments, ``o`` and ``s``...), and for
    indices out of range and coordinates that are not finite, and for over ``max_triangles``
    triangles (trimesh's reading counts them first, and refuses).

    Read over whole columns (numpy over the bytes), not line by line: each line's kind from
    its first bytes, its words from where white space ends, and the numbers of each kind of row
    parsed in one go: one slice of the text, statement words blanked, where that kind's lines
    follow one another (as exporters write them), else its rows gathered."""
    import numpy as np

    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError:
        return None
    text = text.strip()  # each rewrite below only where its character is (memchr's pace)
    if "\r" in text:
        text = text.replace("\r\n", "\n")
    text = "\n{}\n".format(text)
    if "\\" in text:
        text = text.replace("\\\n", "")
    raw = text.encode("utf-8") + (b"" if text.endswith("\n") else b"\n")  # after a last "\\"
    chars = np.frombuffer(raw + b"\n\n", dtype=np.uint8)  # two more: any line's first three
    if _signed_exponent(chars):
        return None  # trimesh rewrites "+e" and "-e" before parsing
    breaks = np.flatnonzero(chars[:len(raw)] == 10)  # the text starts and ends with one
    starts, ends = breaks[:-1] + 1, breaks[1:]
    kinds = _obj_kinds(chars, starts)
    counts = _words_per_line(chars, breaks)
    beyond = np.zeros(0, dtype=np.int64) if text.isascii() else np.flatnonzero(chars >= 128)
    if (kinds[(counts > 0) & (kinds < 0)]).size or \
            (kinds[np.searchsorted(breaks, beyond) - 1] < 4).any():
        return None  # materials, groups, lines, indented or unknown statements;
        # text other than ASCII outside comments, o and s
    lines = {}
    for kind, head in enumerate(_OBJ_KINDS[:4]):
        lines[head] = np.flatnonzero(kinds == kind)
        if (counts[lines[head]] != _OBJ_ITEMS[head] + 1).any():
            return None  # colours, 3D texture coordinates, polygons...
    if not len(lines[b"v "]) or not 0 < len(lines[b"f "]) <= max_triangles:
        return None
    texts, blanked = {}, None  # blanked: the text with each row's statement word blanked
    for head, found in lines.items():
        if len(found) and found[-1] - found[0] + 1 == len(found):  # one run of lines
            if blanked is None:
                blanked = chars.copy()
            for at in range(len(head) - 1):
                blanked[starts[found] + at] = 32
            texts[head] = blanked[starts[found[0]]:ends[found[-1]] + 1].tobytes()
        else:
            texts[head] = _row_text(chars, starts[found] + len(head), ends[found])
    corners = _obj_corners(texts[b"f "])
    if corners is None:
        return None
    index, form = corners
    arrays = {}
    for head in (b"v ", b"vt ", b"vn "):
        numbers = _row_floats(texts[head])
        if numbers is None:
            return None
        arrays[head] = numbers.reshape(-1, _OBJ_ITEMS[head]) if len(numbers) else None
    index = index.reshape(-1, (1, 2, 2, 3)[form]) - 1
    if (index < 0).any():
        return None  # index 0 does not exist; trimesh reads what it makes of it
    columns = [(b"v ", 0)] + {0: [], 1: [(b"vt ", 1)], 2: [(b"vn ", 1)],
                              3: [(b"vt ", 1), (b"vn ", 2)]}[form]
    for head, column in columns:
        if arrays[head] is None or index[:, column].max() >= len(arrays[head]) or \
                not np.isfinite(arrays[head]).all():
            return None
    # each three corners a triangle; np.take copies each row whole (indexing the first axis
    # copies element by element: five times the instructions)
    return np.take(arrays[b"v "], index[:, 0], axis=0), None


def _signed_exponent(chars) -> bool:
    """Whether ``chars`` (uint8, starting with a newline) holds "+e" or "-e": an "e" looked
    for at numpy's pace (rare outside comments), then the byte before each."""
    import numpy as np

    before = chars[np.flatnonzero(chars == ord("e")) - 1]
    return bool(((before == ord("+")) | (before == ord("-"))).any())


def _obj_kinds(chars, starts):
    """Each line's index in :data:`_OBJ_KINDS` (6 a comment, -1 another line) from its first
    three bytes (``chars`` holds two bytes after the last line)."""
    import numpy as np

    first, second = chars[starts], chars[starts + 1]
    third = chars[starts + 2]
    pair = first.astype(np.uint16) | second.astype(np.uint16) << 8
    kinds = np.full(len(starts), -1, dtype=np.int8)
    for kind, head in enumerate(_OBJ_KINDS):
        found = pair == head[0] | head[1] << 8
        if len(head) == 3:
            found &= third == head[2]
        kinds[found] = kind
    kinds[first == ord("#")] = len(_OBJ_KINDS)
    return kinds


def _words_per_line(chars, breaks):
    """How many words each line of ``chars`` (uint8) holds, the lines between ``breaks`` (its
    newlines but the two it ends with): the word starts counted up to each newline. Where the
    only control character is the newline, white space is every byte up to the space (one
    comparison, not each byte looked up in :data:`_NOT_WHITE`)."""
    import numpy as np

    plain = np.count_nonzero(chars < 32) == len(breaks) + 2
    return np.diff(np.cumsum(_word_starts(chars, chars > 32 if plain else None))[breaks])


def _row_text(chars, starts, ends) -> bytes:
    """The bytes of rows ``starts[i]:ends[i]`` of ``chars``, each followed by its newline."""
    import numpy as np

    lengths = ends + 1 - starts
    if not len(lengths):
        return b""
    offsets = np.repeat(starts - (np.cumsum(lengths) - lengths), lengths)
    offsets += np.arange(len(offsets))
    return chars[offsets].tobytes()


def _row_floats(text: bytes):
    """The numbers of rows ``text`` (ASCII), every word read whole as ``np.fromstring`` reads
    it; None when a word is no number."""
    import warnings

    import numpy as np

    text = text.decode("ascii")
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # fromstring warns, and stops, at a word
        try:
            return np.fromstring(text, sep=" ", dtype=np.float64) if text and \
                not text.isspace() else np.zeros(0)
        except (ValueError, DeprecationWarning):
            return None


def _obj_corners(text: bytes):
    """(the indices of ``f`` rows ``text``, one corner form) or None: every corner in the
    form of the first (``v``, ``v/t``, ``v//n``, ``v/t/n``: digits, one or two slashes
    between them), three a row (counted by the caller)."""
    import numpy as np

    if text.translate(None, b"0123456789/ \t\n\r\x0b\x0c"):
        return None  # signs (relative indices), letters, rare separators...
    sample = text.split(maxsplit=1)[0]
    form = {0: 0, 1: 1, 2: 2 if b"//" in sample else 3}.get(sample.count(b"/"))
    if form is None or (form == 0 and b"/" in text):
        return None
    if form:
        codes = np.frombuffer(text, dtype=np.uint8)
        slashes = np.flatnonzero(codes == ord("/"))
        words = np.flatnonzero(_word_starts(codes))
        per_word = np.bincount(np.searchsorted(words, slashes, side="right") - 1,
                               minlength=len(words))
        if (per_word != (0, 1, 2, 2)[form]).any():
            return None
        if form == 2:
            if (slashes[1::2] != slashes[0::2] + 1).any():
                return None  # a "//" in every corner
            slashes = np.column_stack([slashes[0::2], slashes[1::2]])
        digit = np.zeros(len(codes) + 1, dtype=bool)  # and False before the first, after the last
        digit[:-1] = (codes >= ord("0")) & (codes <= ord("9"))
        if not (digit[slashes.reshape(len(slashes), -1)[:, 0] - 1].all() and
                digit[slashes.reshape(len(slashes), -1)[:, -1] + 1].all()):
            return None  # digits on both sides of every slash (or pair of slashes)
    return np.fromstring(text.replace(b"/", b" "), sep=" ", dtype=np.int64), form


_NOT_WHITE = bytes(0 if byte in _WHITE else 1 for byte in range(256))  # a translation table


def _word_starts(codes, word=None):
    """Whether each byte of ``codes`` (uint8) starts a word: is not :data:`_WHITE` and
    follows a byte that is (or starts the text). ``word``: whether each byte is not white
    space, when the caller knows."""
    import numpy as np

    if word is None:
        word = np.frombuffer(codes.tobytes().translate(_NOT_WHITE), dtype=bool)
    starts = word.copy()
    starts[1:] &= ~word[:-1]
    return starts


def merged(vertices, faces):
    """(vertices, faces) with the vertices equal to 1e-8 merged as trimesh's merge_vertices
    merges an STL's: the first of equal ones kept, in order of first appearance. Normals and
    texture coordinates play no part: a seam, where a COLLADA or OBJ file keeps corners apart
    because their normals or texture coordinates differ, is no hole, so watertightness is
    judged on these. ``faces`` None: each three corners in order are a triangle
    (:func:`read_unmerged`)."""
    first, inverse = _unique_rows(_merge_keys(vertices))
    return vertices[first], inverse.reshape(-1, 3) if faces is None else inverse[faces]


def _merge_keys(vertices):
    """The keys by which the (n, 3) vertices merge, coordinate-major (3, n) int64: their
    coordinates in units of 1e-8. The hashing and comparing of :func:`_unique_rows` walk
    each coordinate of every vertex: along contiguous memory, at a third of the cost."""
    import numpy as np

    scaled = vertices * 10 ** MERGE_DIGITS
    np.rint(scaled, out=scaled)  # what round() does with no decimals
    return scaled.T.astype(np.int64, order="C")  # (transposed as it is cast: one pass)


def merged_bounds(vertices, unmerged):
    """``bounds(*merged(unmerged, faces))`` as tuples of floats (min corner, max corner), with
    every vertex moved as ``vertices`` moves it
    (``vertices`` is ``unmerged`` scaled, or itself), without merging: a mesh's least and
    greatest coordinate are a merged vertex's when the first vertex to have it is the first
    of those that merge with it (the one merging keeps). Every vertex must be used by a face.
    None when that does not decide it (the first to have it merges into an earlier one, the
    coordinate is a zero found with either sign, or a coordinate is too large for a merge
    key): merge then."""
    import numpy as np

    # coordinate by coordinate, each copied into one contiguous buffer (argmin along rows of
    # three copies the array for each call); the buffers are reused for every axis: a
    # transposed copy of the whole array, and of the scaled one, was the most memory a mesh
    # that only has to fit in a box took (pages the process faulted in for nothing)
    count = len(vertices)
    column = np.empty(count)
    plain = column if unmerged is vertices else np.empty(count)
    scratch = np.empty(count, dtype=bool)
    lows, highs = [], []
    for axis in range(3):
        np.copyto(column, vertices[:, axis])
        low, high = int(column.argmin()), int(column.argmax())
        if plain is not column:
            np.copyto(plain, unmerged[:, axis])
        ends = (low, high) if plain is column else (int(plain.argmin()), int(plain.argmax()))
        if not (abs(plain[ends[0]]) < KEY_RANGE and abs(plain[ends[1]]) < KEY_RANGE):
            return None
        for row in (low, high):
            if column[row] == 0:  # which zero min() and max() return depends on order
                zeros = np.signbit(column[column == 0])
                if zeros.any() != zeros.all():
                    return None
            # the row's coordinate as read is the least (or greatest) as read, but for
            # rounding when scaled: the vertices that may merge with it lie above it (below)
            least = row == low if plain is column else \
                plain[row] - plain[ends[0]] <= plain[ends[1]] - plain[row]
            if row and _merges_earlier(unmerged, plain, row, least, scratch):
                return None
        lows.append(float(column[low]))
        highs.append(float(column[high]))
    return tuple(lows), tuple(highs)


KEY_RANGE = 2.0 ** 62 / 10 ** MERGE_DIGITS  # [m]: beyond, merge keys overflow int64


def _merges_earlier(vertices, column, row: int, least: bool, scratch) -> bool:
    """Whether a vertex before ``row`` merges with it: only those within 1e-8 of it along
    ``column`` (one coordinate of every vertex) can (the margin covers rounding), and their
    keys are compared whole. ``least``: whether the row's coordinate is (about) the least
    of the column, else the greatest: the others are then found with one comparison, those
    not above it (below it) by more than the margin (which holds all within the margin
    whatever ``least`` says: it only spares comparing the keys of more vertices).
    ``scratch``: an array of at least ``row`` booleans to work in."""
    import numpy as np

    value = column[row]
    margin = 1e-7 + 1e-12 * abs(value)
    if least:
        near = np.less_equal(column[:row], value + margin, out=scratch[:row])
    else:
        near = np.greater_equal(column[:row], value - margin, out=scratch[:row])
    near = np.flatnonzero(near)
    if not len(near):
        return False
    return bool((_merge_keys(vertices[near]) == _merge_keys(vertices[row:row + 1])).all(
        axis=0).any())


def _unique_rows(columns):
    """(index of the first of each distinct row, ascending; row -> its place in that list) of
    a table of n rows of int64 given by its (k, n) columns (coordinate-major: every step walks
    contiguous memory). Rows are hashed to one integer whose top bits, above the row's
    index, are sorted in one pass (the first row of each group comes first); the grouping is
    then checked against the rows themselves (on a collision, rows are compared whole)."""
    import numpy as np

    count = columns.shape[1]
    if not count:
        return np.zeros(0, dtype=np.int64), np.zeros(0, dtype=np.int64)
    bits = max(int(count - 1).bit_length(), 1)
    low = np.uint64((1 << bits) - 1)  # the row's index; the hash's top bits above it
    packed = _row_hash(columns)
    packed &= ~low
    packed |= np.arange(count, dtype=np.uint64)
    packed.sort()
    index = (packed & low).view(np.int64)  # below 2 ** 63: the same numbers
    packed >>= np.uint64(bits)
    new = np.empty(count, dtype=bool)
    new[0] = True
    np.not_equal(packed[1:], packed[:-1], out=new[1:])
    same = ~new[1:]  # rows that must equal the one before them (sorted: a group's rows are
    for column in columns:  # neighbours), checked a column at a time
        gathered = column[index]  # (np.take copies an element at a time: twice the cost)
        same &= gathered[1:] == gathered[:-1]
    if not (same | new[1:]).all():  # two rows share a hash
        rows = np.ascontiguousarray(columns.T)
        whole = rows.view(np.dtype((np.void, 8 * rows.shape[1]))).ravel()
        _, starts, inverse = np.unique(whole, return_index=True, return_inverse=True)
        order = np.argsort(starts)
        rank = np.empty(len(order), dtype=np.int64)
        rank[order] = np.arange(len(order))
        return starts[order], rank[inverse.ravel()]
    starts = index[new]  # the first row of each group (sorted by index within it)
    first = np.zeros(count, dtype=bool)
    first[starts] = True
    rank = np.cumsum(first) - 1  # a first row's place among the first rows
    inverse = np.empty(count, dtype=np.int64)  # each group's rank, repeated over its rows
    inverse[index] = np.repeat(rank[starts], np.diff(np.flatnonzero(np.append(new, True))))
    return np.flatnonzero(first), inverse


def _row_hash(columns):
    """One uint64 per row of a table given by its (k, n) int64 columns (splitmix64's mixing,
    column by column)."""
    import numpy as np

    words = columns.view(np.uint64)
    hashed = np.zeros(columns.shape[1], dtype=np.uint64)
    shifted = np.empty_like(hashed)
    factors = (0x9E3779B97F4A7C15, 0xBF58476D1CE4E5B9, 0x94D049BB133111EB)
    with np.errstate(over="ignore"):
        for column in range(len(columns)):
            hashed += words[column]
            hashed *= np.uint64(factors[column % 3])
            np.right_shift(hashed, np.uint64(31), out=shifted)
            hashed ^= shifted
    return hashed


def scaled(vertices, faces, scale):
    """(vertices, faces) after trimesh's ``apply_scale(scale)``: nothing for a scale within
    1e-8 of one, and faces turned over when the scale mirrors (so the volume stays positive)."""
    import numpy as np

    matrix = np.eye(4)
    matrix[:3, :3] *= np.asarray(scale, dtype=np.float64)
    return _transformed(vertices, faces, matrix)


def _transformed(vertices, faces, matrix):
    """(vertices, faces) after trimesh's ``apply_transform(matrix)`` (4 x 4)."""
    import numpy as np

    if np.abs(matrix - np.eye(4)).max() < 1e-8:
        return vertices, faces
    factors = matrix.diagonal()[:3]
    if np.array_equal(matrix, np.diag([*factors, 1.0])) and np.isfinite(vertices).all():
        # a scale: what the product below gives, to the bit, each coordinate times its factor
        # plus zeros (+0.0 for a zero of either sign), without BLAS, whose threads spin on,
        # burning CPU, after a large product
        moved = vertices * factors + 0.0
    else:
        stacked = np.column_stack((vertices, np.ones(len(vertices))))
        moved = np.dot(matrix, stacked.T).T[:, :3]
    turned = faces is not None and np.abs(matrix[:3, :3] - np.eye(3)).max() >= 1e-6 and \
        np.linalg.det(matrix[:3, :3]) < 0.0
    return moved, (np.ascontiguousarray(np.fliplr(faces)) if turned else faces)


def bounds(vertices, faces):
    """(min corner, max corner) of the vertices the faces use, or None."""
    import numpy as np

    used = np.zeros(len(vertices), dtype=bool)
    used[faces] = True
    inside = vertices if used.all() else vertices[used]
    if not len(inside):
        return None
    return inside.min(axis=0), inside.max(axis=0)


def is_watertight(faces) -> bool:
    """trimesh's test: every edge (sorted pair of vertices) is shared by exactly two faces.
    An edge is one integer, its lesser vertex times the vertex count plus its greater: uint32
    while that fits (meshes of up to 65,536 vertices: half the bytes to sort, twice the
    numbers to a vector instruction)."""
    import numpy as np

    if not len(faces):
        return False
    size = int(faces.max()) + 1
    corners = faces.astype(np.uint32 if size * size <= 1 << 32 else np.int64, copy=False)
    starts = corners.ravel()
    ends = np.empty_like(starts)  # each corner's edge runs to the next corner: the next
    ends[:-1] = starts[1:]  # corner in the array (one copy), but the third's, to the first
    ends[2::3] = starts[0::3]
    keys = np.minimum(starts, ends)
    keys *= keys.dtype.type(size)
    keys += np.maximum(starts, ends)
    keys.sort()
    pairs, seconds = keys[0::2], keys[1::2]
    # sorted, every value exactly twice: equal pairs, each pair below the next
    return len(keys) % 2 == 0 and bool((pairs == seconds).all()) and \
        bool((seconds[:-1] < pairs[1:]).all())


def _winding_consistent(faces) -> bool:
    """trimesh's test: every edge that exactly two faces share is walked in opposite
    directions by them (the second starts where the first ends)."""
    import numpy as np

    edges = faces[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2)
    size = np.int64(int(faces.max()) + 1)
    undirected = np.sort(edges, axis=1)
    order = np.argsort(undirected[:, 0] * size + undirected[:, 1], kind="stable")
    keys = (undirected[:, 0] * size + undirected[:, 1])[order]
    starts = np.flatnonzero(np.r_[True, keys[1:] != keys[:-1]])
    pairs = starts[np.diff(np.r_[starts, len(keys)]) == 2]
    return bool((edges[order[pairs], 1] == edges[order[pairs + 1], 0]).all())


def convex_hull(vertices):
    """(vertices, faces, mass properties) of the convex hull of ``vertices`` as
    ``trimesh.convex.convex_hull`` builds and measures it (qhull with "QbB Pp Qt", again with
    "QJ" on failure; faces of no area dropped and turned outward; vertices merged to 1e-8),
    without trimesh; a closed hull inside out is turned over. None when trimesh would repair
    its winding (faces not consistently wound), for trimesh to build.
    Raises qhull's error (a RuntimeError) when even a joggled hull fails: a flat mesh."""
    import numpy as np
    from scipy.spatial import ConvexHull, QhullError

    points = np.asarray(vertices, dtype=np.float64)
    try:
        hull = ConvexHull(points, qhull_options="QbB Pp Qt")
    except QhullError:
        hull = ConvexHull(points, qhull_options="QJ")
    used = np.sort(hull.vertices)
    index = np.zeros(len(hull.points), dtype=np.int64)
    index[used] = np.arange(len(used))
    faces, points = index[hull.simplices].copy(), hull.points[used].copy()
    corners = points[faces]
    vectors = corners[:, 1:, :] - corners[:, :2, :]
    crosses = np.cross(vectors[:, 0], vectors[:, 1])
    norms = np.sqrt(np.dot(crosses * crosses, [1.0, 1.0, 1.0]))
    valid = norms > float(np.finfo(np.float64).resolution * 100)
    faces, crosses, norms = faces[valid], crosses[valid], norms[valid]
    centers = points[faces].mean(axis=1)
    areas = np.sqrt((power(crosses, 2)).sum(axis=1)) / 2.0
    try:
        centroid = np.average(centers, weights=areas, axis=0)
    except ZeroDivisionError:
        centroid = points.mean(axis=0) if len(points) else np.zeros(3)
    backwards = ((crosses / norms.reshape(-1, 1)) * (centers - centroid)).sum(axis=1) < 0.0
    faces[backwards] = np.fliplr(faces[backwards])
    points, faces = merged(points, faces)
    if not len(faces) or not _winding_consistent(faces):
        return None  # trimesh turns faces over along its face graph
    properties = mass_properties(points, faces)
    if properties["volume"] < 0.0 and is_watertight(faces):  # inside out: turned over
        faces = np.ascontiguousarray(np.fliplr(faces))
        properties = mass_properties(points, faces)
    return points, faces, properties


def extreme_points(vertices, all_below: int = 64):
    """The vertices of the convex hull of ``vertices`` (qhull), in their order, or all of them
    when there are fewer than ``all_below`` or qhull cannot build a hull (a flat mesh; scipy
    absent). Exact for the support in any direction and the farthest point from any point:
    both are reached at a vertex of the hull. A mesh of 100,000 vertices keeps a few
    thousand. A caller asking few questions of the points passes a larger ``all_below``: below
    it, asking them all costs less than qhull and scipy's import (0.2 s)."""
    import numpy as np

    vertices = np.asarray(vertices, dtype=float)
    if len(vertices) < all_below:
        return vertices
    try:
        from scipy.spatial import ConvexHull

        return vertices[np.sort(ConvexHull(vertices, qhull_options="Qt").vertices)]
    except Exception:  # qhull's error for a flat or degenerate mesh, or no scipy
        return vertices


# The 13 directions of a cube's faces, edges and corners (both signs: 26), and the cube's
# surface cut into 48 triangles of neighbouring directions (each face: its centre, an edge's
# middle, a corner), as indices into the 26: the +i direction is i, the -i direction 13 + i.
_CUBE = tuple(d for d in ((x, y, z) for x in (1, 0, -1) for y in (1, 0, -1) for z in (1, 0, -1))
              if d > (0, 0, 0))


def _cube_triangles() -> tuple:
    index = {d: i for i, d in enumerate(_CUBE)}
    index.update({tuple(-v for v in d): i + len(_CUBE) for i, d in enumerate(_CUBE)})
    ring = ((1, 0), (1, 1), (0, 1), (-1, 1), (-1, 0), (-1, -1), (0, -1), (1, -1))
    found = []
    for axis in range(3):
        u, v = (i for i in range(3) if i != axis)
        for sign in (1, -1):
            def direction(a, b):
                d = [0, 0, 0]
                d[axis], d[u], d[v] = sign, a, b
                return index[tuple(d)]
            for k in range(8):
                found.append((direction(0, 0), direction(*ring[k]), direction(*ring[(k + 1) % 8])))
    return tuple(found)


CUBE_TRIANGLES = _cube_triangles()


def cube_extremes(points):
    """Indices of the points largest along each of the 26 directions of a cube's faces, edges
    and corners (:data:`_CUBE`, then their opposites; the first of equals): points of the
    convex hull of ``points`` whose own hull lies inside it. Their heights are the matrix
    product's (:func:`_cube_heights`)."""
    import numpy as np

    heights = _cube_heights(np.asarray(points, dtype=np.float64))
    # one row per direction: each row's largest and least found along contiguous memory
    return np.concatenate([heights.argmax(axis=1), heights.argmin(axis=1)])


# Coordinates [m] within which no sum of three overflows (nor warns, as the product would)
_CUBE_SUMMED = 1e307


def _cube_heights(points):
    """``_cube_columns().T @ points.T`` (13, n), the same numbers to the bit (a zero's sign
    aside: equal zeros, the same extremes), as sums and differences of the coordinates: each entry of the product is x dx + y dy + z dz
    accumulated x first, each term added with one rounding (OpenBLAS's fused multiply-adds),
    and each d is 1, 0 or -1: it is (x +- y) +- z, the zeros' terms left out. OpenBLAS
    zeroes the product before adding to it (13 memsets as long as the points), which cost
    more instructions than the product: on the corpus (663,000 corners and vertices) the
    sums save 82 M instructions of 7.2 G. Coordinates not all within
    :data:`_CUBE_SUMMED` (nan, an infinity: 0 * inf is nan, which leaving out a term does
    not give) take the product itself."""
    import numpy as np

    if not (len(points) and points.max() < _CUBE_SUMMED and points.min() > -_CUBE_SUMMED):
        return _cube_columns().T @ points.T
    heights = np.empty((len(_CUBE), len(points)))
    heights[[4, 10, 12]] = points.T  # (1, 0, 0), (0, 1, 0), (0, 0, 1)
    x, y, z = heights[4], heights[10], heights[12]
    # _CUBE's order: (1, 1, 1), (1, 1, 0), (1, 1, -1), (1, 0, 1), (1, 0, 0), (1, 0, -1),
    # (1, -1, 1), (1, -1, 0), (1, -1, -1), (0, 1, 1), (0, 1, 0), (0, 1, -1), (0, 0, 1)
    np.add(x, y, out=heights[1])
    np.add(heights[1], z, out=heights[0])
    np.subtract(heights[1], z, out=heights[2])
    np.add(x, z, out=heights[3])
    np.subtract(x, z, out=heights[5])
    np.subtract(x, y, out=heights[7])
    np.add(heights[7], z, out=heights[6])
    np.subtract(heights[7], z, out=heights[8])
    np.add(y, z, out=heights[9])
    np.subtract(y, z, out=heights[11])
    return heights


@functools.cache
def _cube_columns():
    """:data:`_CUBE` as the columns of a numpy array (3, 13), made once."""
    import numpy as np

    return np.array(_CUBE, dtype=np.float64).T


def inner_volume(vertices) -> float:
    """A lower bound of the volume of the convex hull of ``vertices`` [m^3] (0 when flat),
    without qhull: the volume of the hull of their :func:`cube_extremes` (at most 26 points,
    which lie in it), built point by point (:func:`_small_hull_volume`); shaved by 1e-9 for
    rounding (qhull's joggled hull too), so that it stays below the volume
    :func:`convex_hull` measures."""
    return _shaved(_small_hull_volume, vertices)


def inner_tetrahedron_volume(vertices) -> float:
    """A lower bound of the volume of the convex hull of ``vertices`` [m^3] (0 when flat)
    cheaper than :func:`inner_volume`: the first tetrahedron :func:`_small_hull_volume` grows
    its hull from (four of the :func:`cube_extremes`, far apart: inside the hull), shaved as
    that one is. On the corpus it alone shows 111 of the 115 open meshes the density rule asks of light
    enough, for a twentieth of the small hull's Python."""
    return _shaved(_first_tetrahedron_volume, vertices)


def _shaved(volume_of, vertices) -> float:
    """``volume_of`` (a list of points -> a volume inside their hull [m^3]) of the
    :func:`cube_extremes` of ``vertices``, shaved by 1e-9 for rounding; 0 when not finite,
    not positive, or for fewer than four or non-finite vertices."""
    import numpy as np

    vertices = np.asarray(vertices, dtype=np.float64)
    if len(vertices) < 4 or not np.isfinite(vertices).all():
        return 0.0
    chosen = vertices[sorted(set(cube_extremes(vertices).tolist()))]  # (np.unique: numpy.ma)
    volume = volume_of([tuple(p) for p in chosen.tolist()])
    return volume * (1 - 1e-9) if math.isfinite(volume) and volume > 0 else 0.0


def _minus(u, v):
    return u[0] - v[0], u[1] - v[1], u[2] - v[2]


def _cross(u, v):
    return u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]


def _dot(u, v):
    return u[0] * v[0] + u[1] * v[1] + u[2] * v[2]


def _first_tetrahedron(points: list):
    """(a, b, c, d, six times the signed volume of their tetrahedron, the margin of a
    height) of the first tetrahedron of :func:`_small_hull_volume` (indices into ``points``:
    a the first, b the farthest from it, c the farthest from their line, d from their
    plane), or None when the points are fewer than four or all one point."""
    if len(points) < 4:
        return None
    size = max(max(abs(v) for v in _minus(p, points[0])) for p in points)
    if not size > 0:
        return None
    margin = 1e-9 * power(size, 3)  # of a height: an area (size^2) times a length
    a = 0
    b = max(range(len(points)), key=lambda i: _dot(_minus(points[i], points[a]),
                                                   _minus(points[i], points[a])))
    line = _minus(points[b], points[a])
    c = max(range(len(points)), key=lambda i: _dot(*(_cross(line, _minus(points[i],
                                                                         points[a])),) * 2))
    normal = _cross(_minus(points[b], points[a]), _minus(points[c], points[a]))
    d = max(range(len(points)), key=lambda i: abs(_dot(normal, _minus(points[i], points[a]))))
    return a, b, c, d, _dot(normal, _minus(points[d], points[a])), margin


def _first_tetrahedron_volume(points: list) -> float:
    """The volume of :func:`_first_tetrahedron` [m^3]: 0 when it is flat (within its
    margin), as :func:`_small_hull_volume` says of such points."""
    found = _first_tetrahedron(points)
    if found is None or not abs(found[4]) > found[5]:
        return 0.0
    return abs(found[4]) / 6.0


def _small_hull_volume(points: list) -> float:
    """The volume of the convex hull of a few points, or less: the hull grown a point at a time
    (beneath-beyond), each point beyond some faces adding a tetrahedron on each (they tile
    what it adds). A face is seen from a point only when it is beyond its plane by a margin
    (1e-9 of the points' size, cubed): one nearer is taken as coplanar, which may leave the
    hull grown short of convex by slivers under that margin; their volume, at most a margin
    per point and face, is taken off, so that the volume stays a lower bound."""
    minus, cross, dot = _minus, _cross, _dot

    def face(i, j, k):  # its corners and its normal (not unit: twice its area)
        a = points[i]
        return i, j, k, a, cross(minus(points[j], a), minus(points[k], a))

    def height(face, q):  # six times the signed volume of the tetrahedron (face, q)
        return dot(face[4], minus(q, face[3]))

    found = _first_tetrahedron(points)
    if found is None:
        return 0.0
    a, b, c, d, first, margin = found
    if not abs(first) > margin:
        return 0.0
    corners = [(a, c, b), (a, b, d), (b, c, d), (c, a, d)] if first > 0 else \
        [(a, b, c), (a, d, b), (b, d, c), (c, d, a)]  # each turned outward
    faces = [face(*turned) for turned in corners]
    volume = abs(first) / 6.0
    for q in range(len(points)):
        if q in (a, b, c, d):
            continue
        heights = [height(f, points[q]) for f in faces]
        seen = [f for f, h in zip(faces, heights) if h > margin]
        if not seen:
            continue  # inside, or too near the hull to tell
        volume += sum(h for h in heights if h > margin) / 6.0
        edges = {(u, v) for f in seen for u, v in ((f[0], f[1]), (f[1], f[2]), (f[2], f[0]))}
        faces = [f for f, h in zip(faces, heights) if h <= margin] + \
            [face(u, v, q) for u, v in edges if (v, u) not in edges]
    return volume - len(points) * len(faces) * margin


def mass_properties(vertices, faces) -> dict:
    """Volume, centre of mass and inertia about it (density 1) of a closed triangle mesh, by
    trimesh's integration (Eberly, "Polyhedral Mass Properties"), term for term, so the numbers
    are trimesh's: keys ``mass`` (= volume), ``volume``, ``center_mass``, ``inertia``."""
    import numpy as np

    # coordinate-major (3, m) arrays: each product below is the one trimesh takes, elementwise
    columns = np.ascontiguousarray(np.asarray(vertices, dtype=np.float64).T)
    t0, t1, t2 = (np.take(columns, faces[:, corner], axis=1) for corner in range(3))
    # cubes per vertex, not per corner: the same numbers, a quarter of the (slow) pow calls;
    # squares per corner (t * t is t ** 2 to the bit, and costs less than gathering)
    cubes = power(columns, 3)
    c0, c1 = (np.take(cubes, faces[:, corner], axis=1) for corner in (0, 1))
    s0, s1 = t0 * t0, t1 * t1
    a, b = t1 - t0, t2 - t1
    crosses = np.empty_like(t0)  # numpy's cross of a and b, product for product
    crosses[0] = a[1] * b[2] - a[2] * b[1]
    crosses[1] = a[2] * b[0] - a[0] * b[2]
    crosses[2] = a[0] * b[1] - a[1] * b[0]
    # each sum and product below is trimesh's, in its order, written into arrays made once
    # (a large mesh's temporaries cost more to allocate than to fill)
    f1 = t0 + t1
    f1 += t2  # t0 + t1 + t2
    work = t0 * t1
    f2 = s0 + s1
    f2 += work
    f2 += np.multiply(t2, f1, out=work)  # s0 + s1 + t0 * t1 + t2 * f1
    f3 = s0 * t1
    f3 += c0
    f3 += np.multiply(t0, s1, out=work)
    f3 += c1
    f3 += np.multiply(t2, f2, out=work)  # c0 + s0 * t1 + t0 * s1 + c1 + t2 * f2
    g0, g1, g2 = (np.add(t, f1, out=s) for t, s in ((t0, s0), (t1, s1), (t2, c0)))
    for g, t in ((g0, t0), (g1, t1), (g2, t2)):
        g *= t
        g += f2  # f2 + (t + f1) * t
    integral = np.empty((10, t0.shape[1]))
    np.multiply(crosses[0], f1[0], out=integral[0])
    np.multiply(crosses, f2, out=integral[1:4])
    np.multiply(crosses, f3, out=integral[4:7])
    row, term = c1[0], work[0]  # spare rows
    for i in range(3):
        j = (i + 1) % 3
        np.multiply(t0[j], g0[i], out=row)
        row += np.multiply(t1[j], g1[i], out=term)
        row += np.multiply(t2[j], g2[i], out=term)
        np.multiply(crosses[i], row, out=integral[i + 7])
    integrated = integral.sum(axis=1) / np.array([6, 24, 24, 24, 60, 60, 60, 120, 120, 120],
                                                 dtype=np.float64)
    volume = integrated[0]
    with np.errstate(divide="ignore", invalid="ignore"):
        center = integrated[1:4] / volume
    inertia = np.zeros((3, 3))
    inertia[0, 0] = integrated[5] + integrated[6] - volume * (power(center[[1, 2]], 2)).sum()
    inertia[1, 1] = integrated[4] + integrated[6] - volume * (power(center[[0, 2]], 2)).sum()
    inertia[2, 2] = integrated[4] + integrated[5] - volume * (power(center[[0, 1]], 2)).sum()
    inertia[0, 1] = -(integrated[7] - volume * np.prod(center[[0, 1]]))
    inertia[1, 2] = -(integrated[8] - volume * np.prod(center[[1, 2]]))
    inertia[0, 2] = -(integrated[9] - volume * np.prod(center[[0, 2]]))
    inertia[2, 0], inertia[2, 1], inertia[1, 0] = inertia[0, 2], inertia[1, 2], inertia[0, 1]
    return {"mass": volume, "volume": volume, "center_mass": center, "inertia": inertia}
