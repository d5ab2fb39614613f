shape_set box -desc {-sub {-box {1 1 1}}}
link -body1 zz -x 0
