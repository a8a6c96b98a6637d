#!/usr/bin/env python3
"""Draw the faces of one patch of a mesh Strata wrote (MSH 4.1, ASCII) as a PNG, seen along
an axis: for pictures of the planes the layers end on (symmetry and outflow planes).
Quadrilaterals (the layers' side faces) are drawn red, triangles blue. Standard library only.

  scripts/plane_picture.py MESH.msh PATCH OUT.png AXIS_U AXIS_V UMIN UMAX VMIN VMAX [WIDTH]

AXIS_U, AXIS_V: x, y or z, the picture's horizontal and vertical axes; the window is in
model units. Example (the README's symmetry plane):
  scripts/plane_picture.py out/hemisphere.msh surface_2 docs/images/hemisphere_symmetry_plane.png x z -1.2 1.6 -0.8 0.8
"""
import struct
import sys
import zlib


def read_msh41(path, patch):
    lines = open(path).read().split('\n')
    if '$MeshFormat' not in lines or not lines[lines.index('$MeshFormat') + 1].startswith('4.1 0'):
        sys.exit(f'{path}: not an ASCII MSH 4.1 file')
    i = lines.index('$PhysicalNames')
    tags = [int(l.split()[1]) for l in lines[i + 2:i + 2 + int(lines[i + 1])]
            if l.split()[0] == '2' and l.split(None, 2)[2].strip('"') == patch]
    if not tags:
        sys.exit(f'{path}: no surface patch named {patch}')
    # Surface entities carrying that physical tag.
    i = lines.index('$Entities')
    npt, ncu, nsu, _ = map(int, lines[i + 1].split())
    entities = set()
    for l in lines[i + 2 + npt + ncu:i + 2 + npt + ncu + nsu]:
        f = l.split()
        nphys = int(f[7])
        if tags[0] in map(int, f[8:8 + nphys]):
            entities.add(int(f[0]))
    i = lines.index('$Nodes')
    nblocks = int(lines[i + 1].split()[0])
    i += 2
    nodes = {}
    for _ in range(nblocks):
        k = int(lines[i].split()[3])
        ids = lines[i + 1:i + 1 + k]
        for j in range(k):
            nodes[int(ids[j])] = tuple(map(float, lines[i + 1 + k + j].split()))
        i += 1 + 2 * k
    i = lines.index('$Elements')
    nblocks = int(lines[i + 1].split()[0])
    i += 2
    faces = []
    for _ in range(nblocks):
        dim, ent, _, k = map(int, lines[i].split())
        if dim == 2 and ent in entities:
            faces += [list(map(int, l.split()))[1:] for l in lines[i + 1:i + 1 + k]]
        i += 1 + k
    return nodes, faces


def main():
    if len(sys.argv) not in (10, 11):
        sys.exit(__doc__)
    path, patch, out = sys.argv[1:4]
    au, av = ('xyz'.index(sys.argv[4]), 'xyz'.index(sys.argv[5]))
    u0, u1, v0, v1 = map(float, sys.argv[6:10])
    W = int(sys.argv[10]) if len(sys.argv) == 11 else 1000
    H = max(1, round(W * (v1 - v0) / (u1 - u0)))
    nodes, faces = read_msh41(path, patch)
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
    raw = b''.join(b'\x00' + bytes(img[r * W * 3:(r + 1) * W * 3]) for r in range(H))

    def chunk(kind, data):
        return struct.pack('>I', len(data)) + kind + data + struct.pack('>I', zlib.crc32(kind + data) & 0xffffffff)

    with open(out, 'wb') as f:
        f.write(b'\x89PNG\r\n\x1a\n' + chunk(b'IHDR', struct.pack('>IIBBBBB', W, H, 8, 2, 0, 0, 0)) +
                chunk(b'IDAT', zlib.compress(raw, 9)) + chunk(b'IEND', b''))
    print(f'{out}: {len(faces)} faces of {patch}')


if __name__ == '__main__':
    main()
