shape_set box -desc {-sub {-box {1 1 1}}}
nosuchcmd 1 2
body b1 -shape box
