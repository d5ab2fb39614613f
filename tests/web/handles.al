# The editor's handle tests (issue 13): one of every handle kind, editable and
# read-only, a long trajectory and a long shape literal to elide.
simulator -finish 2 -step 0.05 -collisions 0

shape_set ball -desc {-sub {-pos {0 0 0} -sphere 0.5}}
shape_set brick -desc {-face {{-1 -0.5 -0.5} {1 -0.5 -0.5} {1 0.5 -0.5} {-1 0.5 -0.5}} -face {{-1 -0.5 0.5} {1 -0.5 0.5} {1 0.5 0.5} {-1 0.5 0.5}}}

body spinner -shape brick -init_pos {0 0 0} -init_rot {0 0 0.5} -init_dpos {1 0 0} -init_drot {0 0 2}
body anchor -shape ball -init_pos {-4 0 0}
set h 3
body computed -shape ball -init_pos [list 4 $h 0]

force -body anchor -x 0 -y -2 -z 0
force -body spinner -x 0 -y {-1 * spinner.mass} -z 0
link -body1 spinner -offset1 {1 0 0} -body2 anchor -offset2 {0.5 0 0} -tightness 20

lightsource -type directional -pos {0 4 4} -dir {0 -1 -1}
trajectory path -points {{0 0 0 0} {0.5 1 0 0} {1 1 1 0} {1.5 0 1 0} {2 0 0 0}}
