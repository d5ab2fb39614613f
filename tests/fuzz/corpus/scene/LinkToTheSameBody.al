shape_set box -desc {-sub {-box {1 1 1}}}
body a -shape box
link -body1 a -body2 a
