shape_set s -desc {-sub {-cone 1}}
