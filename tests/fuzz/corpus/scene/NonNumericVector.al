shape_set box -desc {-sub {-box {1 1 1}}}
body b1 -shape box -init_pos {a b c}
