shape_set box -desc {-sub {-box {1 1 1}}}
body a.b -shape box
