#!/usr/bin/env python3
"""Draw the faces of one patch of a mesh Strata wrote (MSH 4.1, ASCII) as a PNG, seen along
an axis: for pictures of the planes the layers end on (symmetry and outflow planes).
Quadrilaterals (the layers' side faces) are drawn red, triangles blue. Standard library only.

  scripts/plane_picture.py MESH.msh PATCH OUT.png AXIS_U AXIS_V UMIN UMAX VMIN VMAX [WIDTH]

AXIS_U, AXIS_V: x, y or z, the picture's horizontal and vertical axes; the window is in
model units. Example (the README's symmetry plane):
  scripts/plane_picture.py out/hemisphere.msh surface_2 docs/images/hemisphere_symmetry_plane.png x z -1.2 1.6 -0.8 0.8
"""
import sys

from surface_picture import read_msh41, write_png


def read_patch(path, patch):
    """Nodes, and the faces of surface patch \p patch (surface_picture.read_msh41)."""
    nodes, faces = read_msh41(path)
    if patch not in faces:
        sys.exit(f'{path}: no surface patch named {patch}')
    return nodes, faces[patch]


def main():
    if len(sys.argv) not in (10, 11):
        sys.exit(__doc__)
    path, patch, out = sys.argv[1:4]
    au, av = ('xyz'.index(sys.argv[4]), 'xyz'.index(sys.argv[5]))
    u0, u1, v0, v1 = map(float, sys.argv[6:10])
    W = int(sys.argv[10]) if len(sys.argv) == 11 else 1000
    H = max(1, round(W * (v1 - v0) / (u1 - u0)))
    nodes, faces = read_patch(path, patch)
    img = bytearray(b'\xff' * (W * H * 3))

    def pixel(p):
        return (p[au] - u0) / (u1 - u0) * (W - 1), (1 - (p[av] - v0) / (v1 - v0)) * (H - 1)

    def segment(p, q, colour):
        (ax, ay), (bx, by) = pixel(p), pixel(q)
        n = min(20000, int(max(abs(bx - ax), abs(by - ay))) + 1)
        for s in range(n + 1):
            x, y = int(ax + (bx - ax) * s / n), int(ay + (by - ay) * s / n)
            if 0 <= x < W and 0 <= y < H:
                img[(y * W + x) * 3:(y * W + x) * 3 + 3] = colour

    for f in faces:
        colour = b'\xc8\x00\x00' if len(f) == 4 else b'\x00\x00\xa0'
        for j in range(len(f)):
            segment(nodes[f[j]], nodes[f[(j + 1) % len(f)]], colour)
    write_png(out, W, H, [bytes(img[r * W * 3:(r + 1) * W * 3]) for r in range(H)])
    print(f'{out}: {len(faces)} faces of {patch}')


if __name__ == '__main__':
    main()
