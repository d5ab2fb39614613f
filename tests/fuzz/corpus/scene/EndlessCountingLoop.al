shape_set box -desc {-sub {-box {1 1 1}}}
set i 0
while 1 {incr i}
