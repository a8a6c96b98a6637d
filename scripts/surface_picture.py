#!/usr/bin/env python3
"""Draw surface patches of a mesh Strata wrote (MSH 4.1, ASCII) as a shaded PNG with the mesh
lines, seen from any direction (orthographic): for the README's pictures of the layers' outer
surface (patch layer_top of `strata layers ... -o X.msh`) and of the wall. Standard library only.

  scripts/surface_picture.py MESH.msh OUT.png --patches P1,P2,... [--view AZ EL] [--clip X0 X1 Y0 Y1 Z0 Z1]
             [--size W H] [--colors P=R,G,B ...] [--zoom F] [--center X Y Z] [--mirror]
             [--underlay SURFACE.msh PATCHES R,G,B]

--view AZ EL: the camera's direction in degrees: azimuth about z from +x (towards +y),
elevation above the x-y plane (negative: from below); the camera looks at the model from
there. --clip keeps the faces whose centroid lies in the box. The picture is fitted to the
faces drawn, enlarged by --zoom about --center (model units) if given. --mirror adds the
faces mirrored in y = 0 (a half model drawn whole). --underlay draws the patches of a second
mesh in one colour under the first (e.g. the wall under the layers' outer surface: it shows
where no layer covers it).
"""
import argparse
import math
import struct
import sys
import zlib


def read_msh41(path):
    """Points, and per physical surface name the list of faces (tuples of node ids)."""
    with open(path) as f:
        lines = f.read().split('\n')
    if '$MeshFormat' not in lines or not lines[lines.index('$MeshFormat') + 1].startswith('4.1 0'):
        sys.exit(f'{path}: not an ASCII MSH 4.1 file')
    names = {}
    if '$PhysicalNames' in lines:
        i = lines.index('$PhysicalNames')
        for l in lines[i + 2:i + 2 + int(lines[i + 1])]:
            d, tag, name = l.split(None, 2)
            if d == '2':
                names[int(tag)] = name.strip().strip('"')
    i = lines.index('$Entities')
    npt, ncu, nsu, _ = map(int, lines[i + 1].split())
    entity_name = {}
    for l in lines[i + 2 + npt + ncu:i + 2 + npt + ncu + nsu]:
        f = l.split()
        nphys = int(f[7])
        phys = [int(t) for t in f[8:8 + nphys]]
        entity_name[int(f[0])] = names.get(phys[0], f'surface_{f[0]}') if phys else f'surface_{f[0]}'
    i = lines.index('$Nodes')
    nblocks = int(lines[i + 1].split()[0])
    i += 2
    nodes = {}
    for _ in range(nblocks):
        k = int(lines[i].split()[3])
        tags = lines[i + 1:i + 1 + k]
        coords = lines[i + 1 + k:i + 1 + 2 * k]
        for t, c in zip(tags, coords):
            nodes[int(t)] = tuple(map(float, c.split()[:3]))
        i += 1 + 2 * k
    i = lines.index('$Elements')
    nblocks = int(lines[i + 1].split()[0])
    i += 2
    faces = {}
    for _ in range(nblocks):
        dim, ent, etype, k = map(int, lines[i].split())
        if dim == 2 and etype in (2, 3):
            name = entity_name.get(ent, f'surface_{ent}')
            lst = faces.setdefault(name, [])
            for l in lines[i + 1:i + 1 + k]:
                lst.append(tuple(int(v) for v in l.split()[1:]))
        i += 1 + k
    return nodes, faces


def write_png(path, width, height, rows):
    """rows: list of bytes objects, each width*3 long (RGB)."""
    raw = b''.join(b'\x00' + r for r in rows)

    def chunk(kind, data):
        c = struct.pack('>I', len(data)) + kind + data
        return c + struct.pack('>I', zlib.crc32(kind + data) & 0xffffffff)

    png = b'\x89PNG\r\n\x1a\n' + chunk(b'IHDR', struct.pack('>IIBBBBB', width, height, 8, 2, 0, 0, 0))
    png += chunk(b'IDAT', zlib.compress(raw, 9)) + chunk(b'IEND', b'')
    with open(path, 'wb') as f:
        f.write(png)


PALETTE = [(205, 205, 230), (230, 205, 160), (180, 220, 180), (225, 180, 180), (190, 210, 235),
           (220, 220, 170), (200, 180, 225)]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('mesh')
    ap.add_argument('out')
    ap.add_argument('--patches', required=True, help='comma-separated physical surface names')
    ap.add_argument('--view', nargs=2, type=float, default=[-60, 30], metavar=('AZ', 'EL'))
    ap.add_argument('--clip', nargs=6, type=float, metavar=('X0', 'X1', 'Y0', 'Y1', 'Z0', 'Z1'))
    ap.add_argument('--size', nargs=2, type=int, default=[1200, 800], metavar=('W', 'H'))
    ap.add_argument('--zoom', type=float, default=1.0)
    ap.add_argument('--center', nargs=3, type=float, metavar=('X', 'Y', 'Z'))
    ap.add_argument('--colors', nargs='*', default=[], help='PATCH=R,G,B')
    ap.add_argument('--mirror', action='store_true', help='also draw the faces mirrored in y = 0')
    ap.add_argument('--ss', type=int, default=2, help='supersampling factor (default 2)')
    ap.add_argument('--underlay', nargs=3, metavar=('SURFACE', 'PATCHES', 'RGB'))
    a = ap.parse_args()

    nodes, faces = read_msh41(a.mesh)
    wanted = a.patches.split(',')
    if a.underlay:
        # the second mesh's faces renumbered after the first's nodes, as patches of their own
        unodes, ufaces = read_msh41(a.underlay[0])
        off = max(nodes) + 1
        for k, v in unodes.items():
            nodes[k + off] = v
        rgb = tuple(int(v) for v in a.underlay[2].split(','))
        for p in a.underlay[1].split(','):
            if p not in ufaces:
                sys.exit(f'{a.underlay[0]}: no surface patch named {p}')
            faces['underlay:' + p] = [tuple(v + off for v in f) for f in ufaces[p]]
            wanted.append('underlay:' + p)
            a.colors.append(f'underlay:{p}={",".join(map(str, rgb))}')
    colors = {}
    for k, p in enumerate(wanted):
        colors[p] = PALETTE[k % len(PALETTE)]
    for c in a.colors:
        p, rgb = c.split('=')
        colors[p] = tuple(int(v) for v in rgb.split(','))
    missing = [p for p in wanted if p not in faces]
    if missing:
        sys.exit(f'{a.mesh}: no surface patch named {", ".join(missing)} (it has {", ".join(sorted(faces))})')

    az, el = math.radians(a.view[0]), math.radians(a.view[1])
    # Camera frame: d points from the model to the camera; right and up span the picture.
    d = (math.cos(el) * math.cos(az), math.cos(el) * math.sin(az), math.sin(el))
    zup = (0.0, 0.0, 1.0)
    right = (zup[1] * d[2] - zup[2] * d[1], zup[2] * d[0] - zup[0] * d[2], zup[0] * d[1] - zup[1] * d[0])
    n = math.sqrt(sum(c * c for c in right)) or 1.0
    right = tuple(c / n for c in right)
    up = (d[1] * right[2] - d[2] * right[1], d[2] * right[0] - d[0] * right[2], d[0] * right[1] - d[1] * right[0])
    light = tuple(0.8 * d[i] + 0.35 * up[i] - 0.2 * right[i] for i in range(3))
    ln = math.sqrt(sum(c * c for c in light))
    light = tuple(c / ln for c in light)

    tris = []  # (p0, p1, p2 in camera coords, colour, face edges to draw)
    for p in wanted:
        for mirror in ([False, True] if a.mirror else [False]):
            for f in faces[p]:
                pts = [nodes[v] for v in f]
                if mirror:
                    pts = [(x, -y, z) for x, y, z in pts][::-1]
                if a.clip:
                    cx = sum(q[0] for q in pts) / len(pts)
                    cy = sum(q[1] for q in pts) / len(pts)
                    cz = sum(q[2] for q in pts) / len(pts)
                    x0, x1, y0, y1, z0, z1 = a.clip
                    if not (x0 <= cx <= x1 and (y0 <= cy <= y1 or (mirror and y0 <= -cy <= y1)) and z0 <= cz <= z1):
                        continue
                cam = [(sum(q[i] * right[i] for i in range(3)), sum(q[i] * up[i] for i in range(3)),
                        sum(q[i] * d[i] for i in range(3))) for q in pts]
                # shading from the face normal (two-sided)
                u = [pts[1][i] - pts[0][i] for i in range(3)]
                v = [pts[2][i] - pts[0][i] for i in range(3)]
                nn = (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])
                nl = math.sqrt(sum(c * c for c in nn)) or 1.0
                lam = abs(sum(nn[i] * light[i] for i in range(3))) / nl
                shade = 0.35 + 0.65 * lam
                col = tuple(min(255, int(c * shade)) for c in colors[p])
                for k in range(1, len(cam) - 1):
                    edges = [(0, 1) if k == 1 else None, (1, 2), (2, 0) if k == len(cam) - 2 else None]
                    tris.append((cam[0], cam[k], cam[k + 1], col, edges))
    if not tris:
        sys.exit('nothing to draw: no face of those patches inside the clip box')

    xs = [q[0] for t in tris for q in t[:3]]
    ys = [q[1] for t in tris for q in t[:3]]
    W, H = a.size
    S = a.ss
    w, h = W * S, H * S
    cx, cy = (min(xs) + max(xs)) / 2, (min(ys) + max(ys)) / 2
    if a.center:
        c = a.center
        cx = sum(c[i] * right[i] for i in range(3))
        cy = sum(c[i] * up[i] for i in range(3))
    scale = 0.94 * min(w / (max(xs) - min(xs) or 1), h / (max(ys) - min(ys) or 1)) * a.zoom

    def to_screen(q):
        return ((q[0] - cx) * scale + w / 2, h / 2 - (q[1] - cy) * scale, q[2])

    zbuf = [[-1e300] * w for _ in range(h)]
    img = [[(255, 255, 255)] * w for _ in range(h)]
    screen = []
    for t in tris:
        p0, p1, p2 = (to_screen(q) for q in t[:3])
        screen.append((p0, p1, p2, t[3], t[4]))
        area = (p1[0] - p0[0]) * (p2[1] - p0[1]) - (p2[0] - p0[0]) * (p1[1] - p0[1])
        if abs(area) < 1e-12:
            continue
        xmin = max(0, int(math.floor(min(p0[0], p1[0], p2[0]))))
        xmax = min(w - 1, int(math.ceil(max(p0[0], p1[0], p2[0]))))
        ymin = max(0, int(math.floor(min(p0[1], p1[1], p2[1]))))
        ymax = min(h - 1, int(math.ceil(max(p0[1], p1[1], p2[1]))))
        col = t[3]
        for y in range(ymin, ymax + 1):
            py = y + 0.5
            row_z = zbuf[y]
            row_c = img[y]
            for x in range(xmin, xmax + 1):
                px = x + 0.5
                w0 = ((p1[0] - px) * (p2[1] - py) - (p2[0] - px) * (p1[1] - py)) / area
                w1 = ((p2[0] - px) * (p0[1] - py) - (p0[0] - px) * (p2[1] - py)) / area
                w2 = 1.0 - w0 - w1
                if w0 < 0 or w1 < 0 or w2 < 0:
                    continue
                z = w0 * p0[2] + w1 * p1[2] + w2 * p2[2]
                if z > row_z[x]:
                    row_z[x] = z
                    row_c[x] = col
    # Mesh lines: drawn where they are not behind a face (a small depth allowance).
    span = (max(max(q[2] for q in t[:3]) for t in screen) - min(min(q[2] for q in t[:3]) for t in screen)) or 1.0
    eps = 2e-3 * span
    line = (40, 40, 60)
    for p0, p1, p2, _, edges in screen:
        pts = (p0, p1, p2)
        for e in edges:
            if e is None:
                continue
            a0, a1 = pts[e[0]], pts[e[1]]
            steps = int(max(abs(a1[0] - a0[0]), abs(a1[1] - a0[1]))) + 1
            for s in range(steps + 1):
                f = s / steps
                x = int(a0[0] + f * (a1[0] - a0[0]))
                y = int(a0[1] + f * (a1[1] - a0[1]))
                if 0 <= x < w and 0 <= y < h:
                    z = a0[2] + f * (a1[2] - a0[2])
                    if z >= zbuf[y][x] - eps:
                        img[y][x] = line
    # Down-sample S x S blocks.
    rows = []
    for Y in range(H):
        out = bytearray()
        src = img[Y * S:(Y + 1) * S]
        for X in range(W):
            r = g = b = 0
            for row in src:
                for c in row[X * S:(X + 1) * S]:
                    r += c[0]
                    g += c[1]
                    b += c[2]
            n2 = S * S
            out += bytes((r // n2, g // n2, b // n2))
        rows.append(bytes(out))
    write_png(a.out, W, H, rows)


if __name__ == '__main__':
    main()
