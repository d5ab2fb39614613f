# The scene embedded in an Ensemble document in the dissertation's
# Figure 6.2 (two balls moving apart), with the escaped braces unescaped.

shape_set ss1 -desc {-sub {-pos {0 0 0} -sphere 0.5}}
body b2 -artbody 1 -shape ss1 -init_pos {-1 0 0} -init_dpos {1 0 0}
body b3 -artbody 1 -shape ss1 -init_pos {1 0 0} -init_dpos {0 1 0}
simulator -finish 3
