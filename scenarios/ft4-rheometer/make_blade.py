#!/usr/bin/env python3
"""Writes dem/blade.stl: the FT4 twisted blade as a triangulated zero-thickness surface whose
vertex coordinates are cosim template expressions of the scene's blade parameters, so the mesh
LIGGGHTS reads is computed from blade_radius, blade_hub, blade_chord and blade_twist_deg when a
run folder is made (and follows --set on any of them). Run it again only to change the number
of triangles:

    python3 scenarios/ft4-rheometer/make_blade.py [--radial 8] [--chord 4]

Geometry (README.md of the scene): two arms, opposite each other, from the hub radius to the
tip radius. At radius r an arm is a strip of length blade_chord along the helix of angle
beta(r) to the horizontal, centred on the arm's radial line at z = 0, its leading edge (the
side the blade turns towards, +phi) higher. The twist is that of a helicoid (constant pitch):
tan(beta(r)) = blade_pitch_r / r with blade_pitch_r = blade_radius * tan(blade_twist_deg),
steep at the hub, blade_twist_deg at the tip. Points of the strip stay at radius r
(arc length s cos(beta) around the axis, height s sin(beta)). The blade's reference point,
about which LIGGGHTS computes the torque, is the origin of these coordinates (on the axis).
"""
import argparse
import pathlib


def radius(i, n):
    return f"(blade_hub + {i / n:.10g}*(blade_radius - blade_hub))"


def vertex(arm, i, n, j, m):
    r = radius(i, n)
    s = f"({j / m - 0.5:.10g}*blade_chord)"
    root = f"sqrt(1 + (blade_pitch_r/{r})^2)"
    phi = f"({arm}*pi + {s}/{root}/{r})"
    return (f"${{{r}*cos{phi}}}", f"${{{r}*sin{phi}}}", f"${{{s}*blade_pitch_r/{r}/{root}}}")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("--radial", type=int, default=8, help="segments from hub to tip (default 8)")
    ap.add_argument("--chord", type=int, default=4, help="segments across the chord (default 4)")
    ap.add_argument("-o", "--output", default=str(pathlib.Path(__file__).parent / "dem" / "blade.stl"))
    a = ap.parse_args()
    if a.radial < 1 or a.chord < 1:
        ap.error("--radial and --chord must be at least 1")
    # STL has no comments: what made the file is said in the solid's name line
    lines = [f"solid ft4blade made by scenarios/ft4-rheometer/make_blade.py, two arms of "
             f"{a.radial} x {a.chord} quads of two triangles, coordinates are scene-parameter "
             "expressions (README.md of the scene)"]
    for arm in (0, 1):
        for i in range(a.radial):
            for j in range(a.chord):
                p00 = vertex(arm, i, a.radial, j, a.chord)
                p10 = vertex(arm, i + 1, a.radial, j, a.chord)
                p11 = vertex(arm, i + 1, a.radial, j + 1, a.chord)
                p01 = vertex(arm, i, a.radial, j + 1, a.chord)
                for tri in ((p00, p10, p11), (p00, p11, p01)):
                    lines.append("  facet normal 0 0 0")
                    lines.append("    outer loop")
                    lines.extend(f"      vertex {x} {y} {z}" for x, y, z in tri)
                    lines.append("    endloop")
                    lines.append("  endfacet")
    lines.append("endsolid ft4blade")
    pathlib.Path(a.output).write_text("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
