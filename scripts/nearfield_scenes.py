#!/usr/bin/python3
"""Writes the near-field and furnace test scenes, radiosity/scenes/*.json.

Each scene is built here from rooms, blocks, boards and flush emitters so that its construction
can be read (radiosity/scenes/README.md says what each one tests). The output is the same
byte for byte on every run; the committed JSON files are the scenes, this script how they
were made.

Conventions: y is up; a room [0,X] x [0,Y] x [0,Z] has inward normals; every patch is a
parallelogram {origin, edge_u, edge_v} whose normal edge_u x edge_v points along the side it
faces. A "two-sided" board is two coincident patches facing away from each other (twins).

Usage: /usr/bin/python3 scripts/nearfield_scenes.py [--out DIR]
"""
import argparse
import json
import os

WHITE = [0.72, 0.7, 0.66]
CEILING = [0.8, 0.8, 0.78]
FLOOR = [0.45, 0.4, 0.35]
WARM = [0.75, 0.6, 0.45]
COOL = [0.45, 0.55, 0.75]
WOOD = [0.55, 0.4, 0.25]
GREY = [0.5, 0.5, 0.5]
DARK = [0.1, 0.1, 0.12]
BLACK = [0.0, 0.0, 0.0]


def add(a, b):
    return [x + y for x, y in zip(a, b)]


def scale(s, a):
    return [s * x for x in a]


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def dot(a, b):
    return sum(x * y for x, y in zip(a, b))


def clean(v):
    """Coordinates rounded to 12 decimals (1e-12 m), so the JSON reads cleanly."""
    return [round(x, 12) + 0.0 for x in v]


class Scene:
    def __init__(self):
        self.patches = []
        self.camera = None

    def patch(self, name, origin, u, v, facing, reflectance, emission=None):
        """A parallelogram whose normal points along `facing` (u and v swapped if needed)."""
        if dot(cross(u, v), facing) < 0:
            u, v = v, u
        assert dot(cross(u, v), facing) > 0, name
        item = {"name": name, "origin": clean(origin), "edge_u": clean(u), "edge_v": clean(v),
                "reflectance": list(reflectance)}
        if emission is not None:
            item["emission"] = list(emission)
        self.patches.append(item)

    def twin(self, name, origin, u, v, facing, reflectance, back_reflectance=None,
             emission=None, names=None):
        """A two-sided board: `name` front facing `facing` and `name` back, coincident (or the
        two `names`)."""
        front, back = names or (name + " front", name + " back")
        self.patch(front, origin, u, v, facing, reflectance, emission)
        self.patch(back, origin, u, v, scale(-1, facing),
                   back_reflectance if back_reflectance is not None else reflectance)

    def box(self, name, low, size, reflectance, faces=("-x", "+x", "-y", "+y", "-z", "+z")):
        """An axis-aligned box [low, low + size] with outward normals (the named faces only)."""
        x, y, z = [size[0], 0, 0], [0, size[1], 0], [0, 0, size[2]]
        high = add(low, size)
        table = {"-x": (low, z, y, [-1, 0, 0]), "+x": ([high[0], low[1], low[2]], z, y, [1, 0, 0]),
                 "-y": (low, x, z, [0, -1, 0]), "+y": ([low[0], high[1], low[2]], x, z, [0, 1, 0]),
                 "-z": (low, x, y, [0, 0, -1]), "+z": ([low[0], low[1], high[2]], x, y, [0, 0, 1])}
        for face in faces:
            origin, u, v, facing = table[face]
            self.patch(f"{name} {face}", origin, u, v, facing, reflectance)

    def json(self):
        out = {"patches": self.patches}
        if self.camera:
            out["camera"] = self.camera
        return out


def wall_with_hole(scene, name, origin, u, v, facing, reflectance, hole, emitter):
    """The rectangle {origin + s u + t v} split around the hole (s0, s1, t0, t1) in parameter
    units: four frame pieces and the hole itself, a flush emitter (name, reflectance,
    emission), all in one plane, touching along their edges."""
    s0, s1, t0, t1 = hole
    pieces = [("below", 0, 1, 0, t0), ("above", 0, 1, t1, 1), ("left", 0, s0, t0, t1),
              ("right", s1, 1, t0, t1)]
    for label, a0, a1, b0, b1 in pieces:
        if a1 > a0 and b1 > b0:
            scene.patch(f"{name} {label}", add(origin, add(scale(a0, u), scale(b0, v))),
                        scale(a1 - a0, u), scale(b1 - b0, v), facing, reflectance)
    light_name, light_reflectance, emission = emitter
    scene.patch(light_name, add(origin, add(scale(s0, u), scale(t0, v))), scale(s1 - s0, u),
                scale(t1 - t0, v), facing, light_reflectance, emission)


def room(scene, size, walls=None, holes=None):
    """The six inward-facing surfaces of [0,X] x [0,Y] x [0,Z]. `walls` overrides a surface's
    reflectance; `holes` maps a surface to (hole, emitter) for wall_with_hole."""
    X, Y, Z = size
    walls = walls or {}
    holes = holes or {}
    # (name, origin, u, v, inward normal, default reflectance)
    surfaces = [("floor", [0, 0, 0], [X, 0, 0], [0, 0, Z], [0, 1, 0], FLOOR),
                ("ceiling", [0, Y, 0], [X, 0, 0], [0, 0, Z], [0, -1, 0], CEILING),
                ("back wall", [0, 0, 0], [X, 0, 0], [0, Y, 0], [0, 0, 1], WHITE),
                ("front wall", [0, 0, Z], [X, 0, 0], [0, Y, 0], [0, 0, -1], WHITE),
                ("left wall", [0, 0, 0], [0, 0, Z], [0, Y, 0], [1, 0, 0], WARM),
                ("right wall", [X, 0, 0], [0, 0, Z], [0, Y, 0], [-1, 0, 0], COOL)]
    for name, origin, u, v, facing, default in surfaces:
        reflectance = walls.get(name, default)
        if name in holes:
            hole, emitter = holes[name]
            wall_with_hole(scene, name, origin, u, v, facing, reflectance, hole, emitter)
        else:
            scene.patch(name, origin, u, v, facing, reflectance)


def centred_hole(length_u, length_v, centre_u, centre_v, width_u, width_v):
    """The parameter rectangle of a width_u x width_v hole centred at (centre_u, centre_v) on a
    surface of length_u x length_v."""
    return ((centre_u - width_u / 2) / length_u, (centre_u + width_u / 2) / length_u,
            (centre_v - width_v / 2) / length_v, (centre_v + width_v / 2) / length_v)


def camera(eye, look_at, fov=70.0):
    return {"eye": eye, "look_at": look_at, "up": [0, 1, 0], "fov_degrees": fov, "width": 512,
            "height": 512}


def panel_wedge():
    s = Scene()
    X, Y, Z = 4.0, 2.8, 4.0
    hole = centred_hole(X, Z, 2.0, 2.2, 1.2, 1.2)
    room(s, (X, Y, Z), holes={"ceiling": (hole, ("ceiling light", BLACK, [12, 12, 12]))})
    # The panel: 1 m wide, its top edge 2 cm and its bottom edge 37 cm from the back wall, one
    # metre lower: a wedge of air open downwards between the panel's back and the wall.
    top = [1.5, 2.0, 0.02]
    down = [0.0, -1.0, 0.35]
    across = [1.0, 0.0, 0.0]
    s.twin("panel", top, across, down, cross(down, across), [0.75, 0.75, 0.75])
    s.camera = camera([2.0, 1.5, 3.9], [2.0, 1.4, 0.0])
    return s


def square_under_ceiling():
    s = Scene()
    X, Y, Z = 3.7, 2.5, 5.3
    hole = centred_hole(X, Z, X / 2, Z / 2, 1.0, 1.0)
    room(s, (X, Y, Z), holes={"floor": (hole, ("floor light", BLACK, [10, 10, 10]))})
    # An 8 x 8 cm square facing the ceiling 4 cm above it, off the ceiling's centre.
    s.patch("square", [0.96, Y - 0.04, 1.46], [0.08, 0, 0], [0, 0, 0.08], [0, 1, 0],
            [0.7, 0.7, 0.7])
    s.camera = camera([1.85, 1.2, 5.2], [1.0, 2.4, 1.5])
    return s


def cornell_blocks():
    s = Scene()
    size = 5.5
    white, red, green = [0.725, 0.71, 0.68], [0.63, 0.065, 0.05], [0.14, 0.45, 0.091]
    room(s, (size, size, size), walls={"floor": white, "ceiling": white, "left wall": red,
                                       "right wall": green})
    # Axis-aligned blocks: the tall block's -x face 0.69 from the red wall, the short block's
    # -x face 0.34 from the tall block's +x face, overlapping it in z by 0.55.
    s.box("tall block", [0.69, 0.0, 1.2], [1.65, 3.3, 1.65], white, faces=("-x", "+x", "+y",
                                                                           "-z", "+z"))
    s.box("short block", [2.68, 0.0, 2.3], [1.65, 1.65, 1.65], white, faces=("-x", "+x", "+y",
                                                                            "-z", "+z"))
    light_y = size * (1.0 - 1e-3)
    s.patch("light", [size / 2 - 0.65, light_y, size / 2 - 0.525], [1.3, 0, 0], [0, 0, 1.05],
            [0, -1, 0], [0.78, 0.78, 0.78], [40, 32, 24])
    s.camera = camera([2.75, 2.75, 5.45], [2.75, 2.75, 0.0], 75.0)
    return s


def block_spot():
    s = Scene()
    X, Y, Z = 4.0, 3.0, 4.0
    # A 20 x 20 cm emitter flush in the ceiling above the gap between the block and the wall.
    hole = centred_hole(X, Z, 0.25, 2.0, 0.2, 0.2)
    room(s, (X, Y, Z), holes={"ceiling": (hole, ("spot", BLACK, [400, 400, 400]))})
    s.box("block", [0.5, 0.0, 1.5], [1.0, 1.0, 1.0], WHITE, faces=("-x", "+x", "+y", "-z", "+z"))
    s.camera = camera([3.9, 1.6, 3.9], [0.5, 0.8, 1.8])
    return s


def block_wallwash():
    s = Scene()
    X, Y, Z = 4.0, 3.0, 4.0
    room(s, (X, Y, Z))
    s.box("block", [0.5, 0.0, 1.5], [1.0, 1.0, 1.0], WHITE, faces=("-x", "+x", "+y", "-z", "+z"))
    # A 20 x 20 cm emitter 30 cm from the left wall, 2.1-2.3 m high, facing the wall: the
    # room is lit only by the wall's hot spot, which the block's -x face sees from 0.5 m.
    s.patch("wall washer", [0.3, 2.1, 1.9], [0, 0.2, 0], [0, 0, 0.2], [-1, 0, 0], BLACK,
            [400, 400, 400])
    s.camera = camera([3.9, 1.6, 3.9], [0.5, 0.8, 1.8])
    return s


def light_back():
    s = Scene()
    X, Y, Z = 4.0, 3.0, 4.0
    room(s, (X, Y, Z))
    # A 1 x 1 m light 1 mm under the ceiling: its emitting face down, its black back (a twin)
    # up, facing the ceiling across the 1 mm gap.
    s.twin("light", [1.5, Y - 0.001, 1.5], [1.0, 0, 0], [0, 0, 1.0], [0, -1, 0], BLACK,
           emission=[10, 10, 10], names=("light", "light back"))
    s.camera = camera([2.0, 1.0, 3.9], [2.0, 2.9, 2.0])
    return s


def shelf():
    s = Scene()
    X, Y, Z = 4.0, 2.8, 3.5
    # A 1.2 x 1.2 m window flush in the right wall, 0.9-2.1 m high.
    hole = centred_hole(Z, Y, 1.75, 1.5, 1.2, 1.2)
    room(s, (X, Y, Z), holes={"right wall": (hole, ("window", BLACK, [8, 8, 8]))})
    # A two-sided board 1.2 x 0.3 m, 1.6 m high, its back edge 2 cm from the back wall.
    s.twin("shelf", [1.0, 1.6, 0.02], [1.2, 0, 0], [0, 0, 0.3], [0, 1, 0], WOOD,
           names=("shelf top", "shelf bottom"))
    s.camera = camera([2.0, 2.3, 3.4], [1.6, 1.5, 0.0])
    return s


def desk(s, name, x, z):
    """A 1.6 x 0.8 desk: a 3 cm top slab at 0.74 m on four 4 x 4 cm legs, and a monitor."""
    top_y, thickness, leg = 0.74, 0.03, 0.04
    s.box(f"{name} top", [x, top_y - thickness, z], [1.6, thickness, 0.8], WOOD)
    for i, (lx, lz) in enumerate([(0.05, 0.05), (1.51, 0.05), (0.05, 0.71), (1.51, 0.71)]):
        s.box(f"{name} leg {i}", [x + lx, 0.0, z + lz], [leg, top_y - thickness, leg], GREY,
              faces=("-x", "+x", "-z", "+z"))
    s.box(f"{name} monitor", [x + 0.55, top_y, z + 0.55], [0.5, 0.32, 0.05], DARK,
          faces=("-x", "+x", "+y", "-z", "+z"))


def chair(s, name, x, z):
    """A 45 x 45 cm seat slab at 0.45 m on four 3 x 3 cm legs, and a two-sided backrest."""
    seat_y, thickness, leg = 0.45, 0.05, 0.03
    s.box(f"{name} seat", [x, seat_y - thickness, z], [0.45, thickness, 0.45], COOL)
    for i, (lx, lz) in enumerate([(0.02, 0.02), (0.40, 0.02), (0.02, 0.40), (0.40, 0.40)]):
        s.box(f"{name} leg {i}", [x + lx, 0.0, z + lz], [leg, seat_y - thickness, leg], GREY,
              faces=("-x", "+x", "-z", "+z"))
    # The backrest stands on the seat's back edge (z + 0.45), 0.4 m high.
    s.twin(f"{name} backrest", [x, seat_y, z + 0.45], [0.45, 0, 0], [0, 0.4, 0], [0, 0, -1], COOL)


def bookcase(s, name, x, width):
    """Two-sided side boards and four two-sided shelves, 2 cm in front of the back wall."""
    depth, height, gap = 0.35, 2.0, 0.02
    for i, side_x in enumerate([x, x + width]):
        s.twin(f"{name} side {i}", [side_x, 0.0, gap], [0, height, 0], [0, 0, depth],
               [1 if i == 0 else -1, 0, 0], WOOD)
    for k, y in enumerate([0.4, 0.8, 1.2, 1.6]):
        s.twin(f"{name} shelf {k}", [x, y, gap], [width, 0, 0], [0, 0, depth], [0, 1, 0], WOOD)


def office():
    s = Scene()
    X, Y, Z = 6.0, 3.0, 5.0
    # A 3 x 1.4 m window flush in the left wall, 0.9-2.3 m high.
    hole = centred_hole(Z, Y, 2.5, 1.6, 3.0, 1.4)
    room(s, (X, Y, Z), walls={"left wall": WHITE, "right wall": WHITE},
         holes={"left wall": (hole, ("window", BLACK, [6, 6, 6]))})
    # A two-sided strip 4 cm under the ceiling (a cable tray), 15 cm wide, along the room.
    s.twin("ceiling strip", [0.5, Y - 0.04, 2.45], [5.0, 0, 0], [0, 0, 0.15], [0, -1, 0], WHITE)
    # Two hanging lamps 30 cm under the ceiling, emitting downwards, with dark backs (twins).
    for i, lx in enumerate([1.6, 3.8]):
        s.twin(f"lamp {i}", [lx, Y - 0.3, 1.0], [0.6, 0, 0], [0, 0, 3.0], [0, -1, 0], BLACK,
               back_reflectance=[0.3, 0.3, 0.3], emission=[4, 4, 4])
    for i, (dx, dz) in enumerate([(0.8, 0.6), (0.8, 2.8), (3.3, 1.7)]):
        desk(s, f"desk {i}", dx, dz)
        chair(s, f"chair {i}", dx + 0.6, dz + 0.9)
    bookcase(s, "bookcase 0", 3.2, 1.0)
    bookcase(s, "bookcase 1", 4.6, 1.0)
    # A filing cabinet 10 cm from the right wall.
    s.box("cabinet", [5.4, 0.0, 3.9], [0.5, 1.2, 0.8], GREY, faces=("-x", "+x", "+y", "-z", "+z"))
    s.camera = camera([5.9, 1.7, 4.9], [1.0, 0.8, 0.8], 75.0)
    return s


def furnace(rho):
    """The unit cube seen from inside, every face emitting 1 with reflectance rho: the exact
    radiosity is 1 / (1 - rho) everywhere."""
    s = Scene()
    grey = [rho, rho, rho]
    one = [1, 1, 1]
    for name, origin, u, v, facing in [
            ("floor", [0, 0, 0], [1, 0, 0], [0, 0, 1], [0, 1, 0]),
            ("ceiling", [0, 1, 0], [1, 0, 0], [0, 0, 1], [0, -1, 0]),
            ("back", [0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]),
            ("front", [0, 0, 1], [1, 0, 0], [0, 1, 0], [0, 0, -1]),
            ("left", [0, 0, 0], [0, 0, 1], [0, 1, 0], [1, 0, 0]),
            ("right", [1, 0, 0], [0, 0, 1], [0, 1, 0], [-1, 0, 0])]:
        s.patch(name, origin, u, v, facing, grey, one)
    return s


SCENES = {
    "panel_wedge": panel_wedge,
    "square_under_ceiling": square_under_ceiling,
    "cornell_blocks": cornell_blocks,
    "block_spot": block_spot,
    "block_wallwash": block_wallwash,
    "light_back": light_back,
    "shelf": shelf,
    "office": office,
    "furnace_0.5": lambda: furnace(0.5),
    "furnace_0.9": lambda: furnace(0.9),
    "furnace_0.99": lambda: furnace(0.99),
}


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    parser.add_argument("--out", default=os.path.join(root, "radiosity/scenes"))
    args = parser.parse_args()
    os.makedirs(args.out, exist_ok=True)
    for name, build in SCENES.items():
        scene = build().json()
        names = [p["name"] for p in scene["patches"]]
        assert len(names) == len(set(names)), name
        with open(os.path.join(args.out, name + ".json"), "w") as handle:
            handle.write(format_scene(scene))
        print(f"{name}: {len(names)} patches")


def format_scene(scene):
    """One patch per line, so that a diff shows which patch changed."""
    lines = ['{"patches": [']
    lines.append(",\n".join("  " + json.dumps(p) for p in scene["patches"]))
    lines.append("]" + (',\n "camera": ' + json.dumps(scene["camera"]) if "camera" in scene
                        else "") + "}")
    return "\n".join(lines) + "\n"


if __name__ == "__main__":
    main()
