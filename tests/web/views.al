# The editor's camera tests (issue 13): a ball running along +x past a still
# brick, a view that follows the ball (its centre is the ball's state at each
# time, computed by the core), one whose options are expressions, a view
# from the side, and a red point light.
simulator -finish 2 -step 0.05 -collisions 0

shape_set ball -desc {-sub {-pos {0 0 0} -sphere 0.5}}
shape_set brick -desc {-face {{-1 -0.5 -0.5} {1 -0.5 -0.5} {1 0.5 -0.5} {-1 0.5 -0.5}} -face {{-1 -0.5 0.5} {1 -0.5 0.5} {1 0.5 0.5} {-1 0.5 0.5}}}

body runner -shape ball -init_pos {-3 0 0} -init_dpos {3 0 0}
body brick -shape brick -init_pos {0 -2 0}

view chase -follow runner -scale 4
# A view whose -pos and -scale are expressions of the ball's state and of
# time (seed 4.1.7): it looks at (runner.x, -1, t) and zooms in as it goes.
view crane -center {0 0 0} -rot {0 0 0} -pos {{-runner.x} 1 {-t}} -scale {2 + t}
view side -rot {0 1.5707963267948966 0}
lightsource key -type point -pos {0 6 8} -color red -intensity 1

# Torques: a literal one, one written as a force with -torque 1, and one
# whose -z is an expression of time (read-only in the viewer, drawn at its
# evaluated value).
torque -body brick -x 0 -y 0 -z 2
force -torque 1 -body runner -x 1 -y 0 -z 0
torque -body brick -x 0 -y 0 -z {0.5 * sin(t) * brick.mass}
