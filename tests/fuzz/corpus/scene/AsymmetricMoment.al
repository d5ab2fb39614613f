shape_set box -desc {-sub {-box {1 1 1}}}
body b1 -shape box -moment {1 2 3 4 5 6 7 8 9}
