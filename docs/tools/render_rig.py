#!/usr/bin/env python3
"""Pictures of a FinFlex rig for the documentation (docs/rigs.md).

Draws each mesh from the side and from above in its root body frame, every triangle
coloured by the rig component it belongs to, with each child's frame (origin and x
axis) and a legend; prints what every component selects and its frame.

A documentation tool, not part of the build or the tests. It reads the mesh and the
rig file itself and re-implements in numpy what resolve_rig does with them (rules in
docs/rigs.md and docs/body-frame.md):
  - meshes: OBJ (v and f lines, polygons fan-triangulated, vertices in file order,
    g/o groups) and glTF/GLB (TRIANGLES primitives of the default scene, node
    transforms applied, one group "<mesh name or index>/<primitive index>" each);
  - the root frame: "auto" (find_body_frame), "identity" or explicit;
  - selectors: "all", indices, group, and box / half-space tested on the parent's
    vertices in the parent's local frame (a box includes its faces; a half-space takes
    dot(p - point, normal) > 0);
  - child frames: explicit ones are written in the parent's local frame; "identity"
    is the parent's frame; "auto" puts the origin at the attachment and x towards the
    part's centroid.
So the picture shows what the library selects. With --finflex it also asks the
library (`finflex rig-info --labels`) and fails if any vertex's component differs;
with --finflex and --pose it adds a view of the fish posed by `finflex deform --rig`.

Needs Python 3.8+, numpy and matplotlib (pip install numpy matplotlib). From the
repository root, one --case RIG MESH per row of the picture:

    python3 docs/tools/render_rig.py \\
        --case data/rigs/blub.rig.json data/blub/fish.obj \\
        --case data/rigs/blub_low_resolution.rig.json data/blub/fish_low_resolution.obj \\
        --finflex build/apps/finflex \\
        --pose body_m=0.5 --pose tail_angle=0.8 --pose right_pectoral_angle=0.8 \\
        --pose left_pectoral_angle=0.8 --out docs/images/rig_blub.png

    python3 docs/tools/render_rig.py \\
        --case data/rigs/barramundi.rig.json data/barramundi/BarramundiFish.gltf \\
        --finflex build/apps/finflex \\
        --pose body_m=0.5 --pose tail_angle=0.8 --pose right_pectoral_angle=0.8 \\
        --pose left_pectoral_angle=0.8 --out docs/images/rig_barramundi.png

Without --out it only prints (and, with --finflex, checks) the selections.
"""
import argparse
import base64
import json
import os
import struct
import subprocess
import sys
import tempfile

import numpy as np

# --------------------------------------------------------------------------- meshes


class Mesh:
    def __init__(self, positions, triangles, groups):
        self.positions = positions  # (n, 3) float64, rounded to float32 as the library holds them
        self.triangles = triangles  # (t, 3) int
        self.groups = groups  # [(name, first_triangle, triangle_count)]


def load_obj(path):
    positions, triangles, groups = [], [], []
    g_names, o_names = [], []  # (name, first triangle) at each g / o line
    with open(path) as f:
        for line in f:
            fields = line.split()
            if not fields:
                continue
            if fields[0] == "v":
                positions.append([float(t) for t in fields[1:4]])
            elif fields[0] == "f":
                corners = []
                for token in fields[1:]:
                    index = int(token.split("/")[0])
                    corners.append(index - 1 if index > 0 else len(positions) + index)
                for k in range(1, len(corners) - 1):
                    triangles.append([corners[0], corners[k], corners[k + 1]])
            elif fields[0] in ("g", "o"):
                name = " ".join(fields[1:])
                (g_names if fields[0] == "g" else o_names).append((name, len(triangles)))
    marks = g_names or o_names  # the g lines, or the o lines when there is no g line
    for k, (name, first) in enumerate(marks):
        end = marks[k + 1][1] if k + 1 < len(marks) else len(triangles)
        if end == first:
            continue
        if groups and groups[-1][0] == name and sum(groups[-1][1:]) == first:
            groups[-1] = (name, groups[-1][1], end - groups[-1][1])
        else:
            groups.append((name, first, end - first))
    p = np.array(positions, dtype=np.float32).astype(np.float64)
    return Mesh(p, np.array(triangles, dtype=np.int64).reshape(-1, 3), groups)


_GLTF_TYPES = {5120: np.int8, 5121: np.uint8, 5122: np.int16, 5123: np.uint16, 5125: np.uint32,
               5126: np.float32}
_GLTF_SIZES = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4}


def _quat_matrix(q):
    x, y, z, w = q
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                     [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                     [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])


def _node_matrix(node):
    if "matrix" in node:
        return np.array(node["matrix"], dtype=np.float64).reshape(4, 4).T  # column-major
    m = np.eye(4)
    rs = np.eye(3)
    if "rotation" in node:
        rs = _quat_matrix(node["rotation"])
    if "scale" in node:
        rs = rs @ np.diag(node["scale"])
    m[:3, :3] = rs
    if "translation" in node:
        m[:3, 3] = node["translation"]
    return m


def load_gltf(path):
    with open(path, "rb") as f:
        data = f.read()
    chunk = None
    if data[:4] == b"glTF":  # GLB: header, JSON chunk, optional BIN chunk
        length = struct.unpack_from("<I", data, 12)[0]
        doc = json.loads(data[20:20 + length])
        if len(data) > 20 + length:
            bin_length = struct.unpack_from("<I", data, 20 + length)[0]
            chunk = data[28 + length:28 + length + bin_length]
    else:
        doc = json.loads(data)
    buffers = []
    for buffer in doc.get("buffers", []):
        uri = buffer.get("uri")
        if uri is None:
            buffers.append(chunk)
        elif uri.startswith("data:"):
            buffers.append(base64.b64decode(uri.split(",", 1)[1]))
        else:
            with open(os.path.join(os.path.dirname(path), uri), "rb") as f:
                buffers.append(f.read())

    def accessor(index):
        a = doc["accessors"][index]
        n = _GLTF_SIZES[a["type"]]
        dtype = np.dtype(_GLTF_TYPES[a["componentType"]])
        view = doc["bufferViews"][a["bufferView"]]
        start = view.get("byteOffset", 0) + a.get("byteOffset", 0)
        stride = view.get("byteStride", n * dtype.itemsize)
        raw = np.frombuffer(buffers[view["buffer"]], dtype=np.uint8)
        rows = [raw[start + i * stride:start + i * stride + n * dtype.itemsize]
                for i in range(a["count"])]
        return np.frombuffer(b"".join(r.tobytes() for r in rows), dtype=dtype).reshape(-1, n)

    positions, triangles, groups = [], [], []
    count = 0

    def visit(index, parent):
        nonlocal count
        node = doc["nodes"][index]
        world = parent @ _node_matrix(node)
        if "mesh" in node:
            mesh = doc["meshes"][node["mesh"]]
            linear = world[:3, :3]
            for k, primitive in enumerate(mesh["primitives"]):
                if primitive.get("mode", 4) != 4:
                    continue
                p = accessor(primitive["attributes"]["POSITION"]).astype(np.float64)
                p = (p @ linear.T + world[:3, 3]).astype(np.float32).astype(np.float64)
                if "indices" in primitive:
                    t = accessor(primitive["indices"]).astype(np.int64).reshape(-1, 3)
                else:
                    t = np.arange(len(p)).reshape(-1, 3)
                if np.linalg.det(linear) < 0:
                    t = t[:, [0, 2, 1]]  # a mirroring transform: keep the winding outward
                name = "%s/%d" % (mesh.get("name") or str(node["mesh"]), k)
                groups.append((name, sum(len(x) for x in triangles), len(t)))
                positions.append(p)
                triangles.append(t + count)
                count += len(p)
        for child in node.get("children", []):
            visit(child, world)

    scene = doc["scenes"][doc.get("scene", 0)] if "scenes" in doc else {
        "nodes": list(range(len(doc["nodes"])))}
    for index in scene["nodes"]:
        visit(index, np.eye(4))
    return Mesh(np.concatenate(positions), np.concatenate(triangles), groups)


def load_mesh(path):
    extension = os.path.splitext(path)[1].lower()
    if extension == ".obj":
        return load_obj(path)
    if extension in (".gltf", ".glb"):
        return load_gltf(path)
    sys.exit("%s: only .obj, .gltf and .glb are read by this tool" % path)


# --------------------------------------------------------------------------- frames


class Frame:
    """origin, rows of R = (e_x, e_y, e_z), length s_x: p_local = R (p - origin) / s_x."""

    def __init__(self, origin, x, y, length):
        self.origin = np.asarray(origin, dtype=np.float64)
        self.R = np.array([x, y, np.cross(x, y)], dtype=np.float64)
        self.length = float(length)

    def to_local(self, p):
        return (np.asarray(p) - self.origin) @ self.R.T / self.length

    def to_mesh(self, p):
        return self.origin + self.length * (np.asarray(p) @ self.R)

    def vector_to_mesh(self, v):
        return np.asarray(v) @ self.R


def find_body_frame(mesh):
    """finflex::find_body_frame without options (docs/body-frame.md)."""
    p, t = mesh.positions, mesh.triangles
    a, b, c = p[t[:, 0]], p[t[:, 1]], p[t[:, 2]]
    doubled = np.cross(b - a, c - a)
    area = 0.5 * np.linalg.norm(doubled, axis=1)
    mu = (area[:, None] * (a + b + c) / 3).sum(0) / area.sum()
    d = [a - mu, b - mu, c - mu]
    d.append(d[0] + d[1] + d[2])
    cov = sum(np.einsum("t,ti,tj->ij", area / 12, e, e) for e in d) / area.sum()
    values, vectors = np.linalg.eigh(cov)
    order = np.argsort(-values)
    ex, u, v = (vectors[:, k] for k in order)

    def facing(axis):
        ok = area > 0
        cosine = doubled[ok] @ axis / (2 * area[ok])
        return (area[ok] * cosine ** 2).sum() / area[ok].sum()

    def moments(axis):
        s = [e @ axis for e in d[:3]]
        total = s[0] + s[1] + s[2]
        squares = s[0] ** 2 + s[1] ** 2 + s[2] ** 2
        cubes = s[0] ** 3 + s[1] ** 3 + s[2] ** 3
        return area / 12 * (squares + total ** 2), area / 60 * (total ** 3 + 3 * total * squares
                                                                + 2 * cubes)

    ey = v if facing(u) >= facing(v) else u
    lateral = np.cross(ex, ey)
    lateral /= np.linalg.norm(lateral)
    x = (p - mu) @ ex
    lo, hi = x.min(), x.max()
    third = (hi - lo) / 3
    cx = ((a + b + c) / 3 - mu) @ ex
    second = moments(lateral)[0]

    def rms(low, high):
        m = (cx >= low) & (cx <= high)
        return np.sqrt(second[m].sum() / area[m].sum()) if area[m].sum() > 0 else 0.0

    if rms(lo, lo + third) > rms(hi - third, hi):
        ex = -ex
    if moments(ey)[1].sum() < 0:
        ey = -ey
    return Frame(mu, ex, ey, hi - lo)


def _extent(mesh, vertices, origin, x):
    s = (mesh.positions[vertices] - origin) @ x
    return s.max() - s.min()


def _explicit_axes(spec, where):
    x = np.array(spec["x"], dtype=np.float64)
    y = np.array(spec["y"], dtype=np.float64)
    if not np.linalg.norm(x) > 0:
        sys.exit("%s.x is zero" % where)
    x /= np.linalg.norm(x)
    y = y - (y @ x) * x
    if not np.linalg.norm(y) > 1e-6:
        sys.exit("%s.y is zero or parallel to x" % where)
    return x, y / np.linalg.norm(y)


def root_frame(mesh, spec):
    spec = spec or {"mode": "auto"}
    mode = spec.get("mode", "explicit")
    if mode == "auto":
        return find_body_frame(mesh)
    if mode == "identity":
        return Frame([0, 0, 0], [1, 0, 0], [0, 1, 0], 1.0)
    x, y = _explicit_axes(spec, "frame")
    origin = np.array(spec["origin"], dtype=np.float64)
    everything = np.arange(len(mesh.positions))
    length = spec.get("length") or _extent(mesh, everything, origin, x)
    return Frame(origin, x, y, length)


def child_frame(mesh, spec, subtree, parent, where):
    """A child's frame in mesh coordinates; an explicit spec is in the parent's local frame."""
    mode = spec.get("mode", "explicit") if spec else "auto"
    if mode == "identity":
        return parent
    if mode == "auto":
        inside = np.zeros(len(mesh.positions), dtype=bool)
        inside[subtree] = True
        count = inside[mesh.triangles].sum(1)
        mixed = mesh.triangles[(count > 0) & (count < 3)].ravel()
        attachment = np.unique(mixed[inside[mixed]])
        if len(attachment):
            origin = mesh.positions[attachment].mean(0)
        else:  # a separate piece: its vertex closest to the parent's origin
            distance = np.linalg.norm(mesh.positions[subtree] - parent.origin, axis=1)
            origin = mesh.positions[subtree[np.argmin(distance)]]
        x = mesh.positions[subtree].mean(0) - origin
        x /= np.linalg.norm(x)
        y = parent.R[1] - (parent.R[1] @ x) * x
        if np.linalg.norm(y) < 0.1:
            y = parent.R[2] - (parent.R[2] @ x) * x
        y /= np.linalg.norm(y)
        return Frame(origin, x, y, _extent(mesh, subtree, origin, x))
    x, y = _explicit_axes(spec, where)
    x = parent.vector_to_mesh(x)
    x /= np.linalg.norm(x)
    y = parent.vector_to_mesh(y)
    y = y - (y @ x) * x
    y /= np.linalg.norm(y)
    origin = parent.to_mesh(np.array(spec["origin"], dtype=np.float64))
    length = spec["length"] * parent.length if "length" in spec else _extent(mesh, subtree,
                                                                               origin, x)
    return Frame(origin, x, y, length)


# ----------------------------------------------------------------------------- rigs


def select(mesh, spec, parent_vertices, parent_frame, where):
    if spec == "all":
        return parent_vertices
    (kind, body), = spec.items()
    if kind == "indices":
        chosen = np.unique(np.array(body, dtype=np.int64))
        if not np.isin(chosen, parent_vertices).all():
            sys.exit("%s.select.indices: a vertex outside the parent" % where)
    elif kind == "group":
        if body not in [name for name, _, _ in mesh.groups]:
            sys.exit("%s.select.group: '%s' is not a face group of the mesh" % (where, body))
        chosen = np.unique(np.concatenate(
            [mesh.triangles[first:first + count].ravel()
             for name, first, count in mesh.groups if name == body] or [np.zeros(0, np.int64)]))
        if not np.isin(chosen, parent_vertices).all():
            sys.exit("%s.select.group: a vertex outside the parent" % where)
    else:
        local = parent_frame.to_local(mesh.positions[parent_vertices])
        if kind == "box":
            inside = np.all((local >= body["min"]) & (local <= body["max"]), axis=1)
        else:
            inside = (local - body["point"]) @ np.array(body["normal"], dtype=np.float64) > 0
        chosen = parent_vertices[inside]
    if len(chosen) == 0:
        sys.exit("%s.select selects no vertex of the parent" % where)
    return chosen


class Component:
    def __init__(self, spec, index):
        self.spec = spec
        self.name = spec["name"]
        self.where = "components[%d] '%s'" % (index, self.name)
        self.parent = None
        self.children = []
        self.subtree = None  # its vertices and its descendants'
        self.own = None
        self.frame = None


def resolve(rig, mesh):
    """The components in depth-first order, with their vertices and frames."""
    components = [Component(spec, i) for i, spec in enumerate(rig["components"])]
    by_name = {c.name: c for c in components}
    roots = [c for c in components if "parent" not in c.spec]
    if len(roots) != 1:
        sys.exit("a rig has exactly one root (found %d)" % len(roots))
    for c in components:
        if "parent" in c.spec:
            if c.spec["parent"] not in by_name:
                sys.exit("%s.parent: '%s' is not a component" % (c.where, c.spec["parent"]))
            c.parent = by_name[c.spec["parent"]]
            c.parent.children.append(c)
    root = roots[0]
    root.subtree = np.arange(len(mesh.positions))
    root.frame = root_frame(mesh, rig.get("frame"))
    order = []

    def visit(c):
        order.append(c)
        taken = np.full(len(mesh.positions), -1)
        for child in c.children:
            child.subtree = select(mesh, child.spec["select"], c.subtree, c.frame, child.where)
            clash = taken[child.subtree] >= 0
            if clash.any():
                sys.exit("%s.select takes vertex %d, which its sibling '%s' also takes" % (
                    child.where, child.subtree[clash][0],
                    c.children[taken[child.subtree[clash][0]]].name))
            taken[child.subtree] = c.children.index(child)
            child.frame = child_frame(mesh, child.spec.get("frame"), child.subtree, c.frame,
                                      child.where + ".frame")
        c.own = c.subtree[taken[c.subtree] < 0]
        for child in c.children:
            visit(child)

    visit(root)
    if len(order) != len(components):
        sys.exit("the parent links loop: some components never reach the root")
    return order


def describe(order):
    for c in order:
        f = c.frame
        print("  %-20s %6d own vertices, %6d with its descendants%s" % (
            c.name, len(c.own), len(c.subtree), ", parent " + c.parent.name if c.parent else ""))
        print("      frame: origin %s, x %s, y %s, length %.4f" % tuple(
            ["(%s)" % ", ".join("%.4f" % t for t in v) for v in (f.origin, f.R[0], f.R[1])]
            + [f.length]))


# ------------------------------------------------------------------ finflex itself


def finflex_labels(finflex, rig_path, mesh_path):
    """`finflex rig-info --labels`: each vertex's component and root-frame position."""
    with tempfile.TemporaryDirectory() as scratch:
        path = os.path.join(scratch, "labels.txt")
        subprocess.run([finflex, "rig-info", "--in", mesh_path, "--rig", rig_path,
                        "--labels", path], check=True, stdout=subprocess.DEVNULL)
        with open(path) as f:
            rows = [line.split() for line in f if not line.startswith("#")]
    return [r[0] for r in rows], np.array([[float(t) for t in r[1:4]] for r in rows])


def check_with_finflex(finflex, rig_path, mesh_path, mesh, order):
    names, local = finflex_labels(finflex, rig_path, mesh_path)
    mine = np.empty(len(mesh.positions), dtype=object)
    for c in order:
        mine[c.own] = c.name
    differ = np.flatnonzero(mine != np.array(names, dtype=object))
    offset = np.abs(order[0].frame.to_local(mesh.positions) - local).max()
    if len(names) != len(mesh.positions) or len(differ):
        sys.exit("finflex rig-info disagrees on %d vertices (first: %s)" % (
            len(differ), differ[:5]))
    print("  finflex rig-info agrees: every vertex in the same component; root-frame "
          "positions within %.1e" % offset)


def finflex_pose(finflex, rig_path, mesh_path, pose):
    """Positions of the mesh posed by `finflex deform --rig` (the file keeps the order)."""
    with tempfile.TemporaryDirectory() as scratch:
        path = os.path.join(scratch, "posed.obj")
        sets = [a for p in pose for a in ("--set", p)]
        subprocess.run([finflex, "deform", "--in", mesh_path, "--rig", rig_path, *sets,
                        "--normals", "jacobian", "--out", path], check=True,
                       stdout=subprocess.DEVNULL)
        return load_obj(path).positions


# -------------------------------------------------------------------------- picture

COLOURS = ["#8c8c8c", "#e6550d", "#3182bd", "#31a354", "#756bb1", "#d6616b", "#bcbd22",
           "#17becf", "#843c39", "#e377c2"]


def draw(ax, mesh, order, view, title, positions=None):
    """view: (horizontal, vertical, depth axis, flip vertical) in the root frame.
    positions: the mesh posed (drawn in the rest root frame, without the child frames)."""
    from matplotlib.collections import PolyCollection
    import matplotlib.colors as mcolors

    h, v, depth, flip = view
    root = order[0].frame
    local = root.to_local(mesh.positions if positions is None else positions)
    label = np.empty(len(local), dtype=np.int64)
    for k, c in enumerate(order):
        label[c.own] = k
    tri = mesh.triangles
    # A triangle takes the component of the majority of its corners (of its first
    # corner when all three differ).
    l0, l1, l2 = label[tri[:, 0]], label[tri[:, 1]], label[tri[:, 2]]
    owner = np.where(l1 == l2, l1, l0)
    corners = local[tri]
    normal = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    norm = np.linalg.norm(normal, axis=1)
    normal /= np.where(norm > 0, norm, 1)[:, None]
    light = 0.45 + 0.55 * np.abs(normal[:, depth])  # two-sided light from the viewer
    base = np.array([mcolors.to_rgb(COLOURS[k % len(COLOURS)]) for k in range(len(order))])
    face = np.clip(base[owner] * light[:, None], 0, 1)
    towards_viewer = -1 if flip else 1
    back_to_front = np.argsort(towards_viewer * corners[:, :, depth].mean(1))
    ax.add_collection(PolyCollection(corners[back_to_front][:, :, [h, v]],
                                     facecolors=face[back_to_front],
                                     edgecolors=face[back_to_front], linewidths=0.15))
    if positions is None:
        for k, c in enumerate(order[1:], start=1):  # child frames: origin and x axis
            o = root.to_local(c.frame.origin)
            tip = root.to_local(c.frame.to_mesh([1.0, 0.0, 0.0]))
            ax.annotate("", xy=(tip[h], tip[v]), xytext=(o[h], o[v]), zorder=5,
                        annotation_clip=False,
                        arrowprops=dict(arrowstyle="-|>", color="black", lw=0.9,
                                        mutation_scale=7))
            ax.plot(o[h], o[v], "o", color=COLOURS[k % len(COLOURS)], mec="black", ms=4,
                    zorder=6)
    ax.plot(0, 0, "+", color="black", ms=7, zorder=6)
    lo, hi = local.min(0), local.max(0)
    ax.set_xlim(lo[h] - 0.03, hi[h] + 0.03)
    ax.set_ylim(lo[v] - 0.03, hi[v] + 0.03)
    if flip:
        ax.invert_yaxis()
    ax.set_aspect("equal")
    ax.set_xlabel("x (head +)", fontsize=7)
    ax.set_ylabel("z (the fish's right +, downwards)" if flip else "y (dorsal +)", fontsize=7)
    ax.tick_params(labelsize=6)
    ax.grid(True, linewidth=0.3, alpha=0.6)
    ax.set_title(title, fontsize=8)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--case", nargs=2, action="append", required=True,
                        metavar=("RIG", "MESH"), help="a rig file and the mesh it is for")
    parser.add_argument("--finflex", help="the finflex tool: check its selection, pose")
    parser.add_argument("--pose", action="append", default=[], metavar="NAME=VALUE",
                        help="with --finflex: add a view posed with these parameters")
    parser.add_argument("--out", help="PNG to write")
    parser.add_argument("--dpi", type=int, default=80)
    args = parser.parse_args()
    if args.pose and not args.finflex:
        parser.error("--pose needs --finflex (the pose is finflex deform's)")

    cases = []
    for rig_path, mesh_path in args.case:
        with open(rig_path) as f:
            rig = json.load(f)
        mesh = load_mesh(mesh_path)
        order = resolve(rig, mesh)
        print("%s on %s (%d vertices):" % (rig_path, mesh_path, len(mesh.positions)))
        describe(order)
        posed = None
        if args.finflex:
            check_with_finflex(args.finflex, rig_path, mesh_path, mesh, order)
            if args.pose:
                posed = finflex_pose(args.finflex, rig_path, mesh_path, args.pose)
        cases.append((rig_path, mesh_path, mesh, order, posed))
    if not args.out:
        return

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.patches import Patch

    columns = 3 if args.pose else 2
    fig, axes = plt.subplots(len(cases), columns, figsize=(5.2 * columns + 1.6, 3.0 * len(cases)),
                             squeeze=False)
    for row, (rig_path, mesh_path, mesh, order, posed) in enumerate(cases):
        name = os.path.basename(mesh_path)
        draw(axes[row, 0], mesh, order, (0, 1, 2, False), name + ": side (from +z)")
        draw(axes[row, 1], mesh, order, (0, 2, 1, True), name + ": top (from +y)")
        if posed is not None:
            draw(axes[row, 2], mesh, order, (0, 2, 1, True), "posed: " + ", ".join(args.pose),
                 positions=posed)
            axes[row, 2].title.set_fontsize(6.5)
        handles = [Patch(color=COLOURS[k % len(COLOURS)],
                         label="%s (%d)" % (c.name, len(c.own))) for k, c in enumerate(order)]
        axes[row, -1].legend(handles=handles, fontsize=6.5, loc="center left",
                             bbox_to_anchor=(1.02, 0.5), title=os.path.basename(rig_path),
                             title_fontsize=6.5, frameon=False)
    fig.text(0.005, 0.005, "In the root body frame (lengths / s_x); +: the pivot; dot and "
             "arrow: a child's frame origin and x axis, one frame length long; legend: own "
             "vertices.", fontsize=6.5)
    fig.tight_layout(rect=(0, 0.025, 1, 1))
    fig.savefig(args.out, dpi=args.dpi)
    print("wrote", args.out)


if __name__ == "__main__":
    main()
