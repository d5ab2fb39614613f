shape_set box -desc {-sub {-box {1 1 1}}}
body b1 -shape box -init_pos [list 1 2 3
set b 2
