"""A structured Hex8 block 2 x 2 x 1 as a Gmsh MSH 2.2 file, for the
distributed-run measurements (BENCHMARKS.md, "Distributed runs"):
region "body", surface sets "zmin" (contact), "zmax" (pressed), "xmin",
"ymin" (symmetry planes).

    python3 block.py NX NY NZ OUT.msh
"""
import sys
nx,ny,nz=map(int,sys.argv[1:4]); out=sys.argv[4]
L,W,H=2.0,2.0,1.0
def nid(i,j,k): return 1+i+(nx+1)*(j+(ny+1)*k)
lines=[]
with open(out,'w') as f:
    f.write("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n5\n3 1 \"body\"\n2 101 \"zmin\"\n2 102 \"zmax\"\n2 103 \"xmin\"\n2 104 \"ymin\"\n$EndPhysicalNames\n$Nodes\n")
    f.write(f"{(nx+1)*(ny+1)*(nz+1)}\n")
    for k in range(nz+1):
        for j in range(ny+1):
            for i in range(nx+1):
                f.write(f"{nid(i,j,k)} {L*i/nx} {W*j/ny} {H*k/nz}\n")
    f.write("$EndNodes\n$Elements\n")
    els=[]
    for j in range(ny):
        for i in range(nx):
            els.append((3,101,[nid(i,j,0),nid(i,j+1,0),nid(i+1,j+1,0),nid(i+1,j,0)]))
            els.append((3,102,[nid(i,j,nz),nid(i+1,j,nz),nid(i+1,j+1,nz),nid(i,j+1,nz)]))
    for k in range(nz):
        for j in range(ny):
            els.append((3,103,[nid(0,j,k),nid(0,j,k+1),nid(0,j+1,k+1),nid(0,j+1,k)]))
        for i in range(nx):
            els.append((3,104,[nid(i,0,k),nid(i+1,0,k),nid(i+1,0,k+1),nid(i,0,k+1)]))
    for k in range(nz):
        for j in range(ny):
            for i in range(nx):
                els.append((5,1,[nid(i,j,k),nid(i+1,j,k),nid(i+1,j+1,k),nid(i,j+1,k),nid(i,j,k+1),nid(i+1,j,k+1),nid(i+1,j+1,k+1),nid(i,j+1,k+1)]))
    f.write(f"{len(els)}\n")
    for n,(t,g,ns) in enumerate(els):
        f.write(f"{n+1} {t} 2 {g} {g} {' '.join(map(str,ns))}\n")
    f.write("$EndElements\n")
