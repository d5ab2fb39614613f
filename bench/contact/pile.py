#!/usr/bin/env python3
"""Writes an Asgard scene: N unit cubes at random rotations dropped onto a
static floor (restitution 0.5, friction 0.5, gravity 9.81), in columns on a
grid 2 apart, each cube 1.8 above the one below.  Usage: pile.py N [T] [SEED]"""
import math
import random
import sys

n = int(sys.argv[1])
finish = float(sys.argv[2]) if len(sys.argv) > 2 else 5.0
rng = random.Random(int(sys.argv[3]) if len(sys.argv) > 3 else 14)
columns = max(1, math.ceil(math.sqrt(n / 10)))
side = columns * 2.0 + 20
print("shape_set cube -desc {-sub {-box {1 1 1}}}")
print(f"shape_set floor -desc {{-sub {{-box {{{side:.1f} 1 {side:.1f}}}}}}}")
print("body floor -shape floor -static 1 -init_pos {0 -0.5 0} -restitution 0.5 -friction 0.5")
for i in range(n):
    col, level = i % (columns * columns), i // (columns * columns)
    x = (col % columns - (columns - 1) / 2) * 2.0 + rng.uniform(-0.1, 0.1)
    z = (col // columns - (columns - 1) / 2) * 2.0 + rng.uniform(-0.1, 0.1)
    y = 1.0 + 1.8 * level
    r = [rng.uniform(-2, 2) for _ in range(3)]
    print(f"body c{i} -shape cube -mass 1 -init_pos {{{x:.4f} {y:.4f} {z:.4f}}}"
          f" -init_rot {{{r[0]:.4f} {r[1]:.4f} {r[2]:.4f}}} -restitution 0.5 -friction 0.5")
    print(f"force -body c{i} -y {{-9.81 * c{i}.mass}} -gravitational 1")
print(f"simulator -finish {finish}")
