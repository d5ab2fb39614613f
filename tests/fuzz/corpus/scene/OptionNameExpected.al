shape_set box -desc {-sub {-box {1 1 1}}}
body b1 -shape box 12
