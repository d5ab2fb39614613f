#!/usr/bin/env python3
"""Writes an Asgard scene: N balls (radius 0.2, restitution 1, random
velocities of speed ~2) on a jittered grid in a closed box of six static
walls (interior 10 x 10 x 10), no gravity.  Usage: balls_in_box.py N [T] [SEED]"""
import math
import random
import sys

n = int(sys.argv[1])
finish = float(sys.argv[2]) if len(sys.argv) > 2 else 10.0
rng = random.Random(int(sys.argv[3]) if len(sys.argv) > 3 else 14)
half = 5.0
side = math.ceil(n ** (1 / 3))
pitch = 2 * half / side
print("shape_set ball -desc {-sub {-pos {0 0 0} -sphere 0.2}}")
for i in range(n):
    c = [i % side, (i // side) % side, i // (side * side)]
    p = [-half + (k + 0.5) * pitch + rng.uniform(-0.1, 0.1) * pitch for k in c]
    v = [rng.gauss(0, 1.15) for _ in range(3)]
    print(f"body b{i} -shape ball -mass 1 -restitution 1 -init_pos {{{p[0]:.6f} {p[1]:.6f} {p[2]:.6f}}}"
          f" -init_dpos {{{v[0]:.6f} {v[1]:.6f} {v[2]:.6f}}}")
w = half + 0.5
print("shape_set wx -desc {-sub {-box {1 12 12}}}")
print("shape_set wy -desc {-sub {-box {12 1 12}}}")
print("shape_set wz -desc {-sub {-box {12 12 1}}}")
for name, shape, pos in [("xlo", "wx", (-w, 0, 0)), ("xhi", "wx", (w, 0, 0)),
                         ("ylo", "wy", (0, -w, 0)), ("yhi", "wy", (0, w, 0)),
                         ("zlo", "wz", (0, 0, -w)), ("zhi", "wz", (0, 0, w))]:
    print(f"body {name} -shape {shape} -static 1 -restitution 1 -init_pos {{{pos[0]} {pos[1]} {pos[2]}}}")
print(f"simulator -finish {finish}")
