"""The node coordinates of a Gmsh MSH 4.1 ASCII file, in the file's node
order (signorini's node numbering), as a PETSc binary Vec (3 per node) for
solve_only.c: python3 coords.py mesh.msh coords.bin"""
import struct, sys
lines = open(sys.argv[1]).read().split("\n")
i = lines.index("$Nodes")
blocks, n, _, _ = map(int, lines[i + 1].split())
i += 2
xyz = []
for _ in range(blocks):
    k = int(lines[i].split()[3]); i += 1 + k
    for j in range(k):
        xyz.extend(map(float, lines[i + j].split()[:3]))
    i += k
assert len(xyz) == 3 * n, (len(xyz), n)
with open(sys.argv[2], "wb") as f:
    f.write(struct.pack(">ii", 1211214, len(xyz)))
    f.write(struct.pack(f">{len(xyz)}d", *xyz))
print(n, "nodes")
