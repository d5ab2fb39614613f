# The editor's trajectory test (issue 13, seed Figure 4.4): a ball that rides
# a trajectory, a free ball, and a trajectory whose points are computed (its
# handles are read-only).
simulator -finish 2 -step 0.05 -collisions 0

shape_set ball -desc {-sub {-pos {0 0 0} -sphere 0.3}}

body rider -shape ball
body other -shape ball -init_pos {0 -3 0}
trajectory path -points {{0 -2 0 0} {0.5 -1 1 0} {1 0 0 0} {1.5 1 1 0} {2 2 0 0}} -body rider -state pos
set k 3
trajectory slanted -points [list {0 0 -2 0} [list 2 $k -2 0]]
