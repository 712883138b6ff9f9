"""What frames.png draws of a case's shapes and loads over the particles:
each shaped body's region outline (its reference configuration) and the
surfaces its pressure loads act on, read from case.resolved.toml."""

import math

import numpy as np

RECTANGLE_FACES = ("bottom", "right", "top", "left")


def _turn(points, centre, degrees):
    """Points turned counter-clockwise about `centre` by `degrees`."""
    a = math.radians(degrees)
    c, s = math.cos(a), math.sin(a)
    d = points - centre
    return centre + np.column_stack((c * d[:, 0] - s * d[:, 1], s * d[:, 0] + c * d[:, 1]))


def _ellipse(centre, a, b, degrees=0.0, n=256):
    t = np.linspace(0.0, 2.0 * math.pi, n + 1)
    centre = np.asarray(centre, float)
    return _turn(centre + np.column_stack((a * np.cos(t), b * np.sin(t))), centre, degrees)


def _rectangle_corners(region):
    (x0, x1), (y0, y1) = region["x"], region["y"]
    corners = np.array([[x0, y0], [x1, y0], [x1, y1], [x0, y1]], float)
    centre = np.array([0.5 * (x0 + x1), 0.5 * (y0 + y1)])
    return _turn(corners, centre, region.get("angle", 0.0))


def region_outlines(region):
    """A region's closed outlines (m), as the case writes it: an annulus has two."""
    kind = region.get("shape", "rectangle")
    if kind == "rectangle":
        c = _rectangle_corners(region)
        return [np.vstack((c, c[:1]))]
    if kind == "circle":
        return [_ellipse(region["center"], region["radius"], region["radius"])]
    if kind == "ellipse":
        a, b = region["semi_axes"]
        return [_ellipse(region["center"], a, b, region.get("angle", 0.0))]
    if kind == "annulus":
        inner, outer = region["radii"]
        return [_ellipse(region["center"], outer, outer), _ellipse(region["center"], inner, inner)]
    v = np.asarray(region["vertices"], float)
    return [np.vstack((v, v[:1]))]


def is_shaped(body):
    """A body drawn with its outline: any shape but an unturned rectangle."""
    return (body.get("shape", "rectangle") != "rectangle" or body.get("angle", 0.0) != 0.0
            or bool(body.get("holes")))


def shape_outlines(case):
    """{body name: [outline, ...]} of the case's shaped bodies, holes included
    (none in space: a body there has no plane outline)."""
    out = {}
    if case.get("dimension", 2) == 3:
        return out
    for name, body in case.get("bodies", {}).items():
        if body.get("kind") == "wall" or not is_shaped(body):
            continue
        lines = region_outlines(body)
        for hole in body.get("holes", []):
            lines += region_outlines(hole)
        out[name] = lines
    return out


def _distance_to_segment(points, a, b):
    d = b - a
    t = np.clip(((points - a) @ d) / (d @ d), 0.0, 1.0)
    return np.hypot(*(points - (a + t[:, None] * d)).T)


BOX_FACES = ("bottom", "right", "top", "left", "back", "front")
# A box's face: its axis (0 x, 1 y, 2 z) and whether it is the high side.
_BOX_FACE_PLANES = ((1, 0), (0, 1), (1, 1), (0, 0), (2, 0), (2, 1))


def _section_face_distance(position, section, face):
    """Distance in x-y to a plane shape's named face (a rectangle's name or a
    polygon's edge number): a body's in the plane, an extrusion's section's
    in space."""
    if section.get("shape", "rectangle") == "rectangle":
        k = RECTANGLE_FACES.index(face)
        c = _rectangle_corners(section)
        a, b = c[k], c[(k + 1) % 4]
    else:
        v = np.asarray(section["vertices"], float)
        k = int(face) - 1
        a, b = v[k], v[(k + 1) % len(v)]
    return _distance_to_segment(position[:, :2], a, b)


def _face_distance_in_space(position, body, face):
    """Distance to a 3D body's named face (the names of docs/running.md, "In
    space"), or None for a face this drawing does not know."""
    kind = body.get("shape", "box")
    if kind == "box":
        axis, high = _BOX_FACE_PLANES[BOX_FACES.index(face)]
        return np.abs(position[:, axis] - body["xyz"[axis]][high])
    if kind == "cylinder":
        base, top = np.asarray(body["base"], float), np.asarray(body["top"], float)
        u = (top - base) / np.linalg.norm(top - base)
        along = (position - base) @ u
        if face == "base":
            return np.abs(along)
        if face == "top":
            return np.abs(along - np.linalg.norm(top - base))
        radial = position - base - along[:, None] * u
        return np.abs(np.linalg.norm(radial, axis=1) - body["radius"])
    if kind == "extrusion":
        if face in ("back", "front"):
            return np.abs(position[:, 2] - body["z"][0 if face == "back" else 1])
        return _section_face_distance(position, body["section"], face)
    return None


def loaded_particles(case, body_names, frame, l0):
    """{load name: indices into the frame's particles} of each pressure load:
    the surface particles (the frame's `surface` flag) of its body that lie
    within a lattice spacing of the part of the surface it selects, judged
    at their positions in `frame` (the first, reference, frame), in order of
    their angle round the body's centroid."""
    out = {}
    if "surface" not in frame.fields():
        return out
    position = frame["position"]
    surface = frame["surface"] == 1
    for name, load in case.get("loads", {}).items():
        if load.get("type") != "pressure" or load.get("body") not in body_names:
            continue
        body = case["bodies"][load["body"]]
        chosen = surface & (frame["body"] == body_names.index(load["body"]))
        if "face" in load:
            distance = (_face_distance_in_space(position, body, str(load["face"]))
                        if case.get("dimension", 2) == 3
                        else _section_face_distance(position, body, load["face"]))
            if distance is not None:
                chosen &= distance <= 0.75 * l0
        elif "box" in load:
            for axis, key in enumerate("xyz"[:position.shape[1]]):
                if key in load["box"]:
                    lo, hi = load["box"][key]
                    chosen &= (position[:, axis] >= lo - l0) & (position[:, axis] <= hi + l0)
        elif "half_plane" in load or "half_space" in load:
            side = load.get("half_plane", load.get("half_space"))
            p = np.asarray(side["point"], float)
            n = np.asarray(side["normal"], float)
            chosen &= (position - p) @ n >= -0.75 * l0 * np.linalg.norm(n)
        # In order round the body's centroid, so an even pick spreads along it.
        indices = np.flatnonzero(chosen)
        centre = position[frame["body"] == body_names.index(load["body"])].mean(axis=0)
        d = position[indices] - centre
        indices = indices[np.argsort(np.arctan2(d[:, 1], d[:, 0]), kind="stable")]
        if "face" in load and len(indices):
            # A face's corner particles turn their normals half-way round the
            # corner: the face's own direction is its particles' usual one.
            normal = frame["normal"][indices]
            mean = normal.mean(axis=0)
            indices = indices[normal @ (mean / max(np.linalg.norm(mean), 1e-30)) > 0.9]
        out[name] = indices
    return out


def draw_outlines(ax, outlines, view, colour):
    """Each outline, dashed, in the panel's page coordinates (mm)."""
    for lines in outlines.values():
        for line in lines:
            across, down = view.page(line * 1e3)
            ax.plot(across, down, color=colour, linewidth=0.7, linestyle=(0, (3, 2)), zorder=3)


def draw_pressure_arrows(ax, frame, loaded, view, length_mm, colour, arrows=28):
    """Arrows along the loaded particles' inward normals in `frame` (up to
    `arrows` per load, evenly picked): where a pressure pushes."""
    if "normal" not in frame.fields():
        return
    position, normal = frame["position"] * 1e3, frame["normal"]
    for indices in loaded.values():
        if len(indices) == 0:
            continue
        pick = indices[np.linspace(0, len(indices) - 1, min(arrows, len(indices))).astype(int)]
        tail = position[pick] + normal[pick] * length_mm * 1.1
        head = position[pick] + normal[pick] * length_mm * 0.1
        tail_a, tail_d = view.page(tail)
        head_a, head_d = view.page(head)
        for ta, td, ha, hd in zip(tail_a, tail_d, head_a, head_d):
            ax.annotate("", xy=(ha, hd), xytext=(ta, td), zorder=4,
                        arrowprops=dict(arrowstyle="-|>", color=colour, lw=0.8,
                                        mutation_scale=6, shrinkA=0, shrinkB=0))
