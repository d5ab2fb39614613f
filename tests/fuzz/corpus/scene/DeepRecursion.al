shape_set box -desc {-sub {-box {1 1 1}}}
proc f {} {f}; f
